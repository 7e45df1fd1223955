#pragma once
// Runs one measured process: its wall time, CPU time and peak resident memory (getrusage of
// that child alone, via wait4), with a wall-time cap and a resident-memory cap that kill it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ffr::bench {

struct ChildSpec {
  std::vector<std::string> argv;                            ///< argv[0] is looked up in PATH
  std::vector<std::pair<std::string, std::string>> env;     ///< set on top of the inherited environment
  std::filesystem::path cwd;                                ///< working directory (empty: inherited)
  std::filesystem::path out, err;                           ///< stdout and stderr files
  double timeout_s = 0;                                     ///< 0: none
  std::int64_t max_rss_kib = 0;                             ///< 0: none
};

struct ChildResult {
  int exit_status = -1;      ///< exit code if it exited, else -1
  int signal = 0;            ///< terminating signal, 0 if it exited
  bool timed_out = false;    ///< killed by the wall-time cap
  bool memory_capped = false;///< killed by the memory cap
  double wall_s = 0, user_s = 0, sys_s = 0;
  std::int64_t peak_rss_kib = 0;
  double load_before = 0, load_after = 0;  ///< 1-minute load average around the run
  bool ok() const { return exit_status == 0; }
  double cpu_s() const { return user_s + sys_s; }
};

/// Forks, execs and waits. Throws std::runtime_error if the process cannot be started.
ChildResult run_child(const ChildSpec& spec);

/// 1-minute load average (/proc/loadavg).
double load_average();
/// MemAvailable in KiB (/proc/meminfo), 0 if unknown.
std::int64_t mem_available_kib();
/// Waits (sleeping) until the 1-minute load average is below `below` or `max_wait_s` passed;
/// returns the load average it finally saw. below <= 0: returns at once.
double wait_for_quiet(double below, double max_wait_s, bool verbose);

}  // namespace ffr::bench
