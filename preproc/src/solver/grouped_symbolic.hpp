#pragma once
// The supernodal symbolic factor of a matrix whose columns come in groups of identical
// structure (a mesh node's DOFs), from CHOLMOD's analysis of the group graph, expanded to the
// columns.
//
// Why: the eigen-solve's matrix has three columns per mesh node, each node's DOFs coupled to
// the same neighbours. CHOLMOD's symbolic analysis of the DOF matrix (its transpose, elimination
// tree, column counts and supernodes over 3.9 million entries on the 100k-DOF plate of
// tools/bench/reduce), and writing that structure from the mesh's node graph beside the
// assembly, cost time the node graph, with a ninth of the entries, mostly saves. A group's columns have the same rows below it, so the DOF factor's structure is the
// node factor's with each node row and column replaced by its DOFs, and a node's DOFs (a dense
// lower triangle) within the supernode of the node.
//
// CHOLMOD's relaxed amalgamation then merges supernodes by node columns, not DOF columns: its
// column limits (nrelax) are divided by the groups' mean size, so that the supernodes are about
// as wide as an analysis of the DOF matrix makes them.

#include "nodal_ordering.hpp"

#include <cholmod.h>

#include <cstdint>
#include <vector>

namespace ffr::preproc::detail {

struct GroupedSymbolic {
  cholmod_factor* L = nullptr;  ///< supernodal, pattern only, in the group order given (postordered by CHOLMOD)
  /// Entries of L without amalgamation's explicit zeros, and the sum of the squared column
  /// counts (CHOLMOD's Common->lnz and ->fl): exact where all groups have one size, an estimate
  /// from each column's own group size otherwise.
  double lnz = 0;
  double flops = 0;
};

/// The symbolic factor of the n x n matrix whose column groups are q.first (group g: columns
/// first[g] .. first[g + 1] - 1) and whose strictly upper structure couples every column of g
/// with every column of each neighbour of g in q (xadj, adjncy; symmetric, without g itself),
/// with the groups eliminated in the order group_perm (group_perm[k] = the group at position k).
/// L is null when CHOLMOD fails (c->status says why); the caller frees it with
/// cholmod_l_free_factor.
GroupedSymbolic grouped_symbolic(const QuotientGraph& q, const std::vector<std::int64_t>& group_perm, cholmod_common* c);

/// The group order of a column order that keeps each group's columns together (metis_ordering's):
/// the groups in the order of their first columns in perm. Empty if perm splits a group.
std::vector<std::int64_t> group_order(const QuotientGraph& q, const std::vector<std::int64_t>& perm);

}  // namespace ffr::preproc::detail
