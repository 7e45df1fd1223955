#pragma once
// Numbers as the runtime's error and warning messages print them (internal).

#include <cstdio>
#include <string>

namespace ffr::runtime {

/// v to three significant digits: a step, a change, a residual, whose size is the message.
inline std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

/// v to six significant digits: a value the user looks up in their own input.
inline std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace ffr::runtime
