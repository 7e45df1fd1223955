// reduce_bench: performance benchmarks of ffr-reduce (they measure; they are not tests).
//
//   reduce_bench solid [--sizes 100000,265000,500000,1000000] [--modes 20] [--threads 1[,2]]
//                      [--factorizations default,cholmod] [--ccx-timeout 2700] [--ccx-max-dof N] [--mem-cap-mib M]
//       TET10 plate with holes, clamped, side by side with CalculiX *FREQUENCY on the identical
//       mesh: wall/CPU time, peak RSS, ratios, and the largest relative frequency difference;
//       ffr-reduce once per --factorization backend listed (default: its default only).
//   reduce_bench shell [--sizes 1000000] [--modes 30] [--thickness 0.003] [--threads 2] [--goal-s 120]
//       QUAD4 tube of ~1M DOF, clamped: stage times and peak memory against the goal.
//
// Common: [--workdir DIR] [--ffr PATH] [--ccx PATH] [--wait-load L] [--wait-max S]
//         [--md REPORT.md] [--title TEXT]
// Every number is measured on child processes (wait4 rusage: wall, user+sys CPU, peak RSS);
// see README.md next to this file.
#include "bench.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <unistd.h>

using namespace ffr::bench;

namespace {

[[noreturn]] void usage(const std::string& msg) {
  std::fprintf(stderr,
               "reduce_bench: %s\n"
               "usage: reduce_bench solid|shell [--sizes N1,N2,..] [--modes K] [--threads 1,2] [--thickness T]\n"
               "       [--factorizations default,supernodal,cholmod]\n"
               "       [--workdir DIR] [--ffr PATH] [--ccx PATH] [--ccx-timeout S] [--ccx-max-dof N]\n"
               "       [--mem-cap-mib M] [--wait-load L] [--wait-max S] [--goal-s S] [--md FILE] [--title TEXT]\n",
               msg.c_str());
  std::exit(2);
}

double number(const std::string& s, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || !(v >= 0)) usage("bad value '" + s + "' for " + what);
  return v;
}

// "100000,265k,1M" -> {100000, 265000, 1000000}
std::vector<std::int64_t> size_list(const std::string& s) {
  std::vector<std::int64_t> out;
  std::istringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    double mult = 1;
    if (!item.empty() && (item.back() == 'k' || item.back() == 'K')) mult = 1e3, item.pop_back();
    else if (!item.empty() && (item.back() == 'm' || item.back() == 'M')) mult = 1e6, item.pop_back();
    const double v = number(item, "--sizes") * mult;
    if (v < 100) usage("sizes are DOF counts (>= 100)");
    out.push_back(static_cast<std::int64_t>(v));
  }
  if (out.empty()) usage("empty --sizes");
  return out;
}

std::filesystem::path own_dir() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  buf[n] = 0;
  return std::filesystem::path(buf).parent_path();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) usage("expected 'solid' or 'shell'");
  const std::string what = argv[1];
  if (what == "--help" || what == "-h") usage("help");
  if (what != "solid" && what != "shell") usage("unknown benchmark '" + what + "'");
  Options o;
  for (int i = 2; i < argc; ++i) {
    const std::string k = argv[i];
    if (i + 1 >= argc) usage("missing value after " + k);
    const std::string v = argv[++i];
    if (k == "--sizes") o.sizes = size_list(v);
    else if (k == "--modes") o.modes = static_cast<int>(number(v, k));
    else if (k == "--threads") {
      o.threads.clear();
      std::istringstream in(v);
      std::string t;
      while (std::getline(in, t, ',')) {
        const double n = number(t, k);
        if (n < 1 || n > 256 || n != static_cast<int>(n)) usage("--threads takes counts like 1,2");
        o.threads.push_back(static_cast<int>(n));
      }
      if (o.threads.empty()) usage("empty --threads");
    } else if (k == "--factorizations") {
      o.factorizations.clear();
      std::istringstream in(v);
      std::string f;
      while (std::getline(in, f, ','))
        if (f == "default") o.factorizations.push_back("");
        else if (f == "supernodal" || f == "cholmod") o.factorizations.push_back(f);
        else usage("--factorizations takes default, supernodal or cholmod, comma-separated");
      if (o.factorizations.empty()) usage("empty --factorizations");
    } else if (k == "--thickness") o.thickness = number(v, k);
    else if (k == "--workdir") o.workdir = v;
    else if (k == "--ffr") o.ffr = v;
    else if (k == "--ccx") o.ccx = v;
    else if (k == "--ccx-timeout") o.ccx_timeout_s = number(v, k);
    else if (k == "--ccx-max-dof") o.ccx_max_dof = static_cast<std::int64_t>(number(v, k));
    else if (k == "--mem-cap-mib") o.mem_cap_mib = static_cast<std::int64_t>(number(v, k));
    else if (k == "--wait-load") o.wait_load = number(v, k);
    else if (k == "--wait-max") o.wait_max_s = number(v, k);
    else if (k == "--goal-s") o.goal_s = number(v, k);
    else if (k == "--md") o.md = v;
    else if (k == "--title") o.title = v;
    else usage("unknown option " + k);
  }
  if (o.ffr.empty()) o.ffr = own_dir() / "ffr-reduce";
  try {
    std::filesystem::create_directories(o.workdir);
    o.workdir = std::filesystem::absolute(o.workdir);
    return what == "solid" ? run_solid(o) : run_shell(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reduce_bench: %s\n", e.what());
    return 1;
  }
}
