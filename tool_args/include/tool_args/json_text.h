#pragma once

// The few pieces of JSON the tools print, one object per line: a string quoted and escaped as
// RFC 8259 asks (file names may hold quotes, backslashes or control characters), and a number
// that JSON can hold (NaN and the infinities are not numbers there: null).
#include <cmath>
#include <cstdio>
#include <string>

namespace multirobot_audio::tools {

inline std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", u);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// `value` with `decimals` decimals, or null when it is not finite.
inline std::string JsonNumber(double value, int decimals) {
  if (!std::isfinite(value)) return "null";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// `value` to `digits` significant digits (for figures whose scale varies: tone powers from 1e-9
// to 1), or null when it is not finite.
inline std::string JsonSignificant(double value, int digits) {
  if (!std::isfinite(value)) return "null";
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

}  // namespace multirobot_audio::tools
