// eigen_bench: times the sparse factorization and the shift-invert Lanczos solve of
// ffr::preproc on generated 3D pencils of growing size and prints one table row per size.
//
//   eigen_bench [--sizes 50000,200000,1000000] [--dpn 3|1] [--nev 20]
//               [--backend spectra|arpack] [--ordering metis|nesdis|amd|auto]
//               [--threads T]      threads of ffr's solver and of OpenBLAS (default: all cores)
//               [--rhs 0]          also time a block solve with that many right-hand sides,
//                                  beside CHOLMOD's own cholmod_l_solve2 (best of 3 each)
//               [--analyze-only 1] symbolic analysis only: sizes and memory estimate (for
//                                  sizes that would not fit or take too long here)
//
// Times are wall-clock; "cpu s" is the process CPU time of the whole eigen-solve (all
// threads), which tells how much of the wall time was lost to a loaded machine.
//
// Every row is verified against the closed-form eigenvalues of the generated pencil
// (grid_pencil.hpp); "max err" is the largest relative eigenvalue error.

#include "cholmod_solve_reference.hpp"
#include "grid_pencil.hpp"

#include "ffr/preproc/solver/eigen_solver.hpp"
#include "ffr/preproc/solver/memory.hpp"
#include "ffr/preproc/threads.hpp"
#include "ffr/cli/process_threads.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

using namespace ffr::preproc;

namespace {

struct Args {
  std::vector<std::int64_t> sizes{50000, 200000, 1000000};
  int dpn = 3, nev = 20, rhs = 0;
  unsigned threads = 0;  ///< 0: all cores
  bool analyze_only = false;
  EigenBackend backend = EigenBackend::Spectra;
  Ordering ordering = Ordering::Metis;
};

constexpr const char* kUsage =
    "usage: eigen_bench [--sizes N1,N2,..] [--dpn 1|3] [--nev K] [--backend spectra|arpack] "
    "[--ordering metis|nesdis|amd|auto] [--rhs R] [--threads T] [--analyze-only 0|1]\n";

[[noreturn]] void usage(const std::string& msg) {
  std::fprintf(stderr, "eigen_bench: %s\n%s", msg.c_str(), kUsage);
  std::exit(2);
}

long parse_int(const char* s, const char* what) {
  char* end = nullptr;
  const long v = std::strtol(s, &end, 10);
  if (!end || *end || v <= 0) usage(std::string("bad value '") + s + "' for " + what);
  return v;
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (k == "--help") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    }
    // The option's value, taken by the branch that knows the option (an unknown one is named
    // as such below, not as one missing its value).
    const auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage("missing value after " + k);
      return argv[++i];
    };
    if (k == "--sizes") {
      a.sizes.clear();
      std::stringstream ss(value());
      std::string item;
      while (std::getline(ss, item, ',')) a.sizes.push_back(parse_int(item.c_str(), "--sizes"));
    } else if (k == "--dpn") {
      a.dpn = static_cast<int>(parse_int(value(), "--dpn"));
      if (a.dpn != 1 && a.dpn != 3) usage("--dpn must be 1 or 3");
    } else if (k == "--nev") {
      a.nev = static_cast<int>(parse_int(value(), "--nev"));
    } else if (k == "--analyze-only") {
      const std::string f = value();
      if (f != "0" && f != "1") usage("--analyze-only must be 0 or 1");
      a.analyze_only = f == "1";
    } else if (k == "--rhs") {
      a.rhs = static_cast<int>(parse_int(value(), "--rhs"));
    } else if (k == "--threads") {
      a.threads = static_cast<unsigned>(parse_int(value(), "--threads"));
    } else if (k == "--backend") {
      const std::string b = value();
      if (b == "spectra") a.backend = EigenBackend::Spectra;
      else if (b == "arpack") a.backend = EigenBackend::Arpack;
      else usage("unknown backend " + b);
    } else if (k == "--ordering") {
      const std::string o = value();
      if (o == "metis") a.ordering = Ordering::Metis;
      else if (o == "nesdis") a.ordering = Ordering::Nesdis;
      else if (o == "amd") a.ordering = Ordering::Amd;
      else if (o == "auto") a.ordering = Ordering::Auto;
      else usage("unknown ordering " + o);
    } else {
      usage("unknown option " + k);
    }
  }
  return a;
}

double mib(std::uint64_t b) { return static_cast<double>(b) / (1024.0 * 1024.0); }

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse(argc, argv);
  set_max_threads(args.threads);  // the library's own threads
  // The default (supernodal) factorization: OpenBLAS on one thread under its own threads, OpenMP off.
  ffr::cli::set_numerical_library_threads(ffr::cli::blas_threads_for("supernodal", ffr::preproc::max_threads()));
  std::printf("eigen_bench: Q1 box 2x1x1 clamped at x=0, %s, nev = %d, backend %s, ordering %s\n",
              args.dpn == 3 ? "3 DOF/node (elasticity-like K (x) D)" : "scalar Laplacian",
              args.nev, to_string(args.backend), to_string(args.ordering));
  if (args.analyze_only) {
    std::printf("%9s %10s %11s %9s %7s %9s %9s\n", "DOF", "nnz(K)", "nnz(L)", "GFlop", "anlz s",
                "est MiB", "RSS MiB");
    for (const std::int64_t target : args.sizes) {
      const ffr::bench::GridPencil g = ffr::bench::make_grid_pencil(target, args.dpn);
      FactorOptions fo;
      fo.ordering = args.ordering;
      CholmodFactor f(fo);
      const FactorStatistics& s = f.analyze(g.K);
      std::printf("%9lld %10lld %11.4g %9.1f %7.2f %9.0f %9.0f   (grid %dx%dx%d)\n",
                  static_cast<long long>(g.K.rows()), static_cast<long long>(g.K.nonZeros()),
                  s.nnz_L, s.flops * 1e-9, s.analyze_seconds, mib(s.peak_bytes),
                  mib(peak_rss_bytes()), g.nx, g.ny, g.nz);
    }
    return 0;
  }
  std::printf("%9s %10s %11s %8s %7s %7s %6s %8s %5s %7s %7s %9s %9s %9s %8s%s\n", "DOF",
              "nnz(K)", "nnz(L)", "GFlop", "anlz s", "fact s", "GF/s", "Lanczos", "ops",
              "verify", "cpu s", "est MiB", "chol MiB", "RSS MiB", "max err",
              args.rhs ? "   solve s  chol s  chol/ffr  diff" : "");
  for (const std::int64_t target : args.sizes) {
    reset_peak_rss();
    const auto t0 = std::chrono::steady_clock::now();
    const ffr::bench::GridPencil g = ffr::bench::make_grid_pencil(target, args.dpn);
    const double gen_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EigenOptions o;
    o.nev = args.nev;
    o.sigma = 0.0;  // clamped: K itself is positive definite
    o.backend = args.backend;
    o.factor.ordering = args.ordering;
    EigenSolver solver(o);
    const std::clock_t c0 = std::clock();
    try {
      solver.compute(g.K, g.M);
    } catch (const std::exception& e) {
      std::printf("%9lld  failed: %s\n", static_cast<long long>(g.K.rows()), e.what());
      return 1;
    }
    const double cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    const EigenResult& r = solver.result();
    const EigenInfo& in = solver.info();
    const auto ref = ffr::bench::grid_eigenvalues(g, args.nev);
    double err = 0;
    for (int k = 0; k < args.nev; ++k) err = std::max(err, std::abs(r.lambda[k] / ref[k] - 1));
    double solve_s = 0, ref_s = 0, diff = 0;
    if (args.rhs > 0) {
      CholmodFactor f(o.factor);
      f.factorize(g.K);
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(g.K.rows(), args.rhs);
      Eigen::MatrixXd X;
      solve_s = 1e300;
      for (int k = 0; k < 3; ++k) {
        const auto ts = std::chrono::steady_clock::now();
        X = f.solve(B);
        solve_s = std::min(solve_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - ts).count());
      }
      const ffr::bench::ReferenceSolve ref = ffr::bench::cholmod_reference_solve(g.K, B, 3);
      ref_s = ref.seconds;
      diff = (X - ref.X).norm() / ref.X.norm();
    }
    const FactorStatistics& s = in.factor;
    std::printf("%9lld %10lld %11.4g %8.1f %7.2f %7.2f %6.1f %8.2f %5lld %7.2f %7.1f %9.0f %9.0f %9.0f %8.1e",
                static_cast<long long>(g.K.rows()), static_cast<long long>(g.K.nonZeros()),
                s.nnz_L, s.flops * 1e-9, s.analyze_seconds, s.factorize_seconds,
                s.flops * 1e-9 / std::max(s.factorize_seconds, 1e-9), in.lanczos_seconds,
                static_cast<long long>(in.operator_applications), in.verify_seconds, cpu_s,
                mib(s.peak_bytes), mib(s.cholmod_peak_bytes), mib(peak_rss_bytes()), err);
    if (args.rhs > 0) std::printf(" %10.3f %7.3f %9.2f %5.0e", solve_s, ref_s, ref_s / solve_s, diff);
    std::printf("   (grid %dx%dx%d, generated in %.1f s, max rel. residual %.1e)\n", g.nx, g.ny,
                g.nz, gen_s, r.max_relative_residual);
    std::fflush(stdout);
  }
  return 0;
}
