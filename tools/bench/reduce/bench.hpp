#pragma once
// Options shared by the two benchmarks of reduce_bench and their entry points.

#include "child_process.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ffr::bench {

struct Options {
  std::filesystem::path workdir = "reduce_bench_work";  ///< meshes (cached), part files, run outputs
  std::filesystem::path ffr;                             ///< ffr-reduce (default: next to reduce_bench)
  std::string ccx = "ccx";
  std::vector<std::int64_t> sizes;                       ///< target DOF per row
  std::vector<int> threads{1};                           ///< thread counts, every size is run with each
  /// solid benchmark: ffr-reduce's --factorization backends, each run at every size and thread
  /// count beside the one CalculiX run ("" : the default, no option given)
  std::vector<std::string> factorizations{""};
  int modes = 0;                                         ///< 0: the benchmark's default
  double thickness = 0.003;                              ///< shell benchmark: wall thickness [m]
  double ccx_timeout_s = 2700;                           ///< CalculiX wall-time cap
  std::int64_t ccx_max_dof = 0;                          ///< run CalculiX only up to this size (0: no limit)
  std::int64_t mem_cap_mib = 0;                          ///< kill a run above this RSS (0: MemAvailable - 1 GiB)
  double wait_load = 0;                                  ///< wait for a 1-min load average below this (0: no)
  double wait_max_s = 1800;                              ///< ... but at most this long
  double goal_s = 120;                                   ///< shell benchmark: the wall-time goal
  std::string md;                                        ///< Markdown report to append to ("" : none)
  std::string title;                                     ///< section title in the report
};

int run_solid(const Options& o);
int run_shell(const Options& o);

/// "OMP_NUM_THREADS=1 ... " prefix and the matching environment for a run with t threads.
std::vector<std::pair<std::string, std::string>> thread_env(int t, bool calculix);
std::string env_text(const std::vector<std::pair<std::string, std::string>>& env);

/// RSS cap of a run: --mem-cap-mib, else MemAvailable minus 1 GiB.
std::int64_t memory_cap_kib(const Options& o);

/// The ffr-reduce run of `json` into dir/stem[-factorization].sid.h5 with t threads (stdout and
/// stderr in dir), with --factorization when one is given, and its command line appended to
/// `commands` for the report.
ChildSpec ffr_reduce_run(const Options& o, const std::filesystem::path& json, const std::filesystem::path& dir,
                         const std::string& stem, int t, std::string& commands, const std::string& factorization = "");

/// The SID file ffr_reduce_run writes.
std::filesystem::path ffr_sid(const std::filesystem::path& dir, const std::string& stem, const std::string& factorization);

}  // namespace ffr::bench
