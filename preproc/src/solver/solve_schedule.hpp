#pragma once
// How the supernodal substitutions (supernodal_solve.hpp) and the factorization by subtrees
// (tree_cholesky.hpp) split over threads.
//
// The supernodes of CHOLMOD's factor are post-ordered: every subtree of the supernodal
// elimination tree is a contiguous range of supernodes ending at its root. Disjoint subtrees
// touch disjoint rows except their common ancestors. So the tree is cut into a serial "top"
// (the root and the separators near it) and subtrees below it, dealt to the threads with about
// equal numbers of factor entries:
//   forward: each thread sweeps its subtrees; the updates they send to rows of the top go into
//            the thread's own accumulator, summed into the vector afterwards; then the top
//            is swept on one thread;
//   back:    the top on one thread, then each thread sweeps its subtrees (reading the final
//            rows of the top, writing only its own rows).
// Each sweep reads the same entries of L as the serial one, in the same order within a supernode,
// so the solution differs from the serial one only in the summation order of the top's updates.

#include <cholmod.h>

#include <cstdint>
#include <vector>

namespace ffr::preproc::detail {

struct SupernodeRange {
  std::int64_t first, last;  ///< supernodes first .. last (inclusive), ascending
};

struct SolveSchedule {
  std::vector<SupernodeRange> top;                 ///< serial part, ascending
  std::vector<std::vector<SupernodeRange>> parts;  ///< one list of subtrees per thread
  std::vector<std::int32_t> slot;    ///< column -> row of the top accumulators, -1 outside the top
  std::vector<std::int64_t> top_columns;  ///< the columns of the top, by slot
  double parallel_fraction = 0;      ///< entries in the parts / all entries (0: serial)
};

/// What the cut balances: the factor entries each supernode holds (a substitution reads each
/// once) or, for the factorization (tree_cholesky.hpp), its flops, about nscol * nsrow^2 (its
/// own Cholesky and the updates it sends to its ancestors).
enum class TreeWork { Entries, Flops };

/// The schedule for `threads` threads (empty parts: run serially). Gives none when threads < 2,
/// when the factor has fewer than min_entries stored values, or when the best cut leaves
/// less than a third of the work to the parts (the serial top would dominate).
SolveSchedule make_solve_schedule(const cholmod_factor& L, unsigned threads, std::int64_t min_entries,
                                  TreeWork measure = TreeWork::Entries);

}  // namespace ffr::preproc::detail
