#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include <ros/ros.h>

#include "nava_modem/modem_profile.h"

namespace multirobot_audio::testing {

// The modem profile an over-the-air rostest runs on, from its ~profile parameter (`fallback` when
// unset); a name that is no profile ends the test program with one line naming it.
inline nava_modem::Profile ProfileParam(const char* test, const std::string& fallback) {
  std::string name;
  ros::NodeHandle("~").param<std::string>("profile", name, fallback);
  const auto parsed = nava_modem::ParseProfile(name);
  if (!parsed) {
    std::fprintf(stderr, "%s: ~profile: expected %s, got '%s'\n", test, nava_modem::kProfileNames, name.c_str());
    std::exit(1);
  }
  return *parsed;
}

}  // namespace multirobot_audio::testing
