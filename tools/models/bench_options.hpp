#pragma once
// What the runtime's benchmarks do with an argument they do not take: a full run takes
// minutes, so an unknown option (or --help) must not start one.

#include <cstdio>
#include <cstring>

namespace bench {

/// For an argument no option matched: the usage on stdout and 0 for --help; otherwise the
/// argument named and the usage on stderr, and 2. The caller returns the result from main.
inline int refuse_option(const char* program, const char* arg, const char* usage) {
  const bool help = std::strcmp(arg, "--help") == 0;
  if (!help) std::fprintf(stderr, "%s: unknown option %s\n", program, arg);
  std::fputs(usage, help ? stdout : stderr);
  return help ? 0 : 2;
}

}  // namespace bench
