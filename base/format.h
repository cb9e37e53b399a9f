#pragma once
// One number through a printf pattern, as a std::string ("%.3f", "%g" …): for messages and
// tables built by concatenation.

#include <cstdio>
#include <string>

namespace weft::base {

inline std::string format(const char* pattern, double v) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

}  // namespace weft::base
