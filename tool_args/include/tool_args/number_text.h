#pragma once

#include <cstdio>
#include <string>

namespace multirobot_audio::tools {

// A number as a person would type it back ("%g": 0.3, -15, 1e-06), for messages and files.
inline std::string NumberText(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace multirobot_audio::tools
