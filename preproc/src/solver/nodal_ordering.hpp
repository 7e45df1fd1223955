#pragma once
// METIS nested dissection on the quotient graph of a symmetric pattern's supervariables.
//
// Why: an FE matrix couples the DOFs of a node to exactly the same columns, so its graph is the
// node graph with every vertex tripled (or sextupled) and every edge multiplied by 9 (or 36).
// CHOLMOD's own METIS call orders that expanded graph, most of the symbolic analysis's time.
// Ordering the node graph (vertices weighted by their DOF count) and expanding the order gives
// the same kind of nested-dissection order on a graph about 3x smaller in vertices and 9x in
// edges: on the 100k-DOF plate of tools/bench/reduce the analysis took about a third less time
// for a factor 0.4 % larger.

#include "ffr/preproc/solver/sparse_types.hpp"

#include <cstdint>
#include <vector>

namespace ffr::preproc::detail {

struct NodalOrdering {
  std::vector<std::int64_t> perm;  ///< perm[k] = original column at position k (CHOLMOD's Perm)
  std::int64_t groups = 0;         ///< vertices of the quotient graph METIS ordered
};

/// Groups the runs of consecutive columns whose closed patterns (the column with its own
/// diagonal) are identical, orders the quotient graph with METIS_NodeND and expands the order.
/// Reads the strictly upper entries of A (full or upper-only storage). Returns an empty perm
/// when grouping would not shrink the graph (fewer than 1.5 columns per group on average), when
/// the graph does not fit METIS's 32-bit indices, or when METIS fails: the caller then lets
/// CHOLMOD order the matrix itself.
NodalOrdering nodal_metis_ordering(const SparseMatrix& A);

/// A quotient graph given by the caller: group G holds the columns first[G] .. first[G + 1] - 1
/// (first[0] = 0, increasing, first.back() = n), and its neighbours are adjncy[xadj[G] ..
/// xadj[G + 1] - 1] (other groups, each once, G itself not among them). What the reductions
/// build from the mesh's node graph, without the matrix's own graph (reduce/pattern_analysis.hpp).
struct QuotientGraph {
  std::vector<std::int64_t> first, xadj, adjncy;
};

/// METIS_NodeND on that graph (each group weighted by its columns), expanded to the columns.
/// An empty perm when the graph does not fit METIS's indices or METIS fails.
NodalOrdering metis_ordering(const QuotientGraph& q);

}  // namespace ffr::preproc::detail
