#pragma once
// Forward and back substitution with CHOLMOD's numeric supernodal LL^T factor, for blocks of
// right-hand sides.
//
// Why not cholmod_l_solve2: with a few right-hand sides (the block Lanczos solves 4 at a time)
// it hands each supernode to dtrsm and dgemm, and OpenBLAS packs the triangular block and the
// rectangular panel before multiplying, so the 435 MB factor of the 100k-DOF plate of
// tools/bench/reduce was streamed at about 9 GB/s (2.5 s of solves in a 8.6 s run, perf)
// against the 21-24 GB/s one core reads here. The solves are bandwidth-bound; this one reads
// each supernode's values once per pass, in place, four columns at a time, with the
// right-hand sides interleaved (row-major) so that each factor entry meets all of them in
// one vector operation.

#include "solve_schedule.hpp"

#include <cholmod.h>

#include <cstdint>
#include <vector>

namespace ffr::preproc::detail {

/// The arrays of a numeric supernodal factor the sweeps read: CHOLMOD's structure, the values
/// (owned by the supernodal backend) packed (factor_packing.hpp; see supernodal_solve.cpp).
struct SupernodalView {
  std::int64_t nsuper = 0;
  const SuiteSparse_long* super = nullptr;
  const SuiteSparse_long* pi = nullptr;
  const SuiteSparse_long* px = nullptr;  ///< packed offsets (factor_packing.hpp)
  const SuiteSparse_long* rows = nullptr;
  const double* values = nullptr;
};

class SupernodalSolver {
 public:
  /// Keeps pointers into L's structure and into `values` (not copies): L is CHOLMOD's supernodal
  /// analysis, only read; `values` the numeric factor packed by pack_values with these offsets
  /// (packed_offsets, factor_packing.hpp). Both must stay alive while solve() is used.
  /// With threads > 1 and a factor of at least kMinParallelEntries values, the sweeps run on
  /// up to that many threads (solve_schedule.hpp).
  SupernodalSolver(const cholmod_factor& L, const double* values, std::vector<SuiteSparse_long> packed_offsets,
                   unsigned threads = 1);

  /// Smaller factors are solved on one thread: a sweep over a 2^20-entry (8 MB) factor
  /// takes about a millisecond, where starting and joining threads starts to show.
  static constexpr std::int64_t kMinParallelEntries = std::int64_t{1} << 20;

  /// Threads the sweeps use (1: serial).
  unsigned threads() const;
  /// Share of the factor's entries swept in parallel (0 when serial).
  double parallel_fraction() const { return schedule_.parallel_fraction; }

  /// X = A^-1 B for the A = P^T L L^T P that L factorises; B and X are n x ncols column-major
  /// with leading dimensions ldb and ldx (they may alias: B is read before X is written, per
  /// chunk of columns). The interleaved workspace grows to n x 16 doubles at most.
  void solve(const double* B, std::int64_t ldb, std::int64_t ncols, double* X, std::int64_t ldx);

 private:
  std::int64_t n_ = 0;
  const SuiteSparse_long* perm_ = nullptr;  ///< null: identity
  std::vector<SuiteSparse_long> px_;        ///< packed offsets, view_.px
  SupernodalView view_;
  std::int64_t max_update_rows_ = 0;  ///< largest nsrow - nscol over the supernodes
  SolveSchedule schedule_;
  std::vector<double> y_;                ///< n x width, row-major (interleaved)
  std::vector<std::vector<double>> t_;   ///< per thread: one supernode's update rows x width
  std::vector<std::vector<double>> acc_; ///< per thread: its updates of the top's rows

  void sweep_block(int width);  ///< forward and back on y_
};

}  // namespace ffr::preproc::detail
