#include "ffr/preproc/solver/memory.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace ffr::preproc {

namespace {

// Value in kB of a "Key:   123 kB" line of a /proc file, in bytes.
std::optional<std::uint64_t> proc_kb_field(const char* path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size(), key) == 0 && line.size() > key.size() &&
        line[key.size()] == ':') {
      std::istringstream is(line.substr(key.size() + 1));
      std::uint64_t kb = 0;
      if (is >> kb) return kb * 1024u;
    }
  }
  return std::nullopt;
}

// A single unsigned number in a sysfs file; nullopt for "max", missing or malformed files.
std::optional<std::uint64_t> read_number(const char* path) {
  std::ifstream in(path);
  std::string s;
  if (!(in >> s) || s == "max") return std::nullopt;
  try {
    std::size_t used = 0;
    const unsigned long long v = std::stoull(s, &used);
    if (used != s.size()) return std::nullopt;
    return static_cast<std::uint64_t>(v);
  } catch (...) {
    return std::nullopt;
  }
}

// Headroom below a cgroup memory limit, if one is set. Limits at or above 2^60 are the
// v1 "unlimited" sentinel and ignored.
std::optional<std::uint64_t> cgroup_headroom() {
  auto limit = read_number("/sys/fs/cgroup/memory.max");
  auto usage = read_number("/sys/fs/cgroup/memory.current");
  if (!limit) {
    limit = read_number("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    usage = read_number("/sys/fs/cgroup/memory/memory.usage_in_bytes");
  }
  if (!limit || !usage || *limit >= (std::uint64_t{1} << 60)) return std::nullopt;
  return *limit > *usage ? *limit - *usage : 0;
}

}  // namespace

std::optional<std::uint64_t> available_memory_bytes() {
  auto avail = proc_kb_field("/proc/meminfo", "MemAvailable");
  if (!avail) return std::nullopt;
  if (auto cg = cgroup_headroom()) avail = std::min(*avail, *cg);
  return avail;
}

std::uint64_t peak_rss_bytes() { return proc_kb_field("/proc/self/status", "VmHWM").value_or(0); }

std::uint64_t current_rss_bytes() {
  return proc_kb_field("/proc/self/status", "VmRSS").value_or(0);
}

bool reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

std::string format_bytes(std::uint64_t bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 4) {
    v /= 1024.0;
    ++u;
  }
  char buf[32];
  if (u == 0) std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  else std::snprintf(buf, sizeof buf, "%.2f %s", v, units[u]);
  return buf;
}

void release_free_heap() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

}  // namespace ffr::preproc
