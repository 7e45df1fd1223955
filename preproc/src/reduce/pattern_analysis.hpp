#pragma once
// The structure the early analysis orders and analyses (early_analysis.cpp), built from the
// assembly's entity pattern (assembly/pattern.hpp) where the matrix to factorize is a principal
// submatrix of the assembled one.
//
// Why: that structure was first formed as a matrix of the full DOF pattern (7.8 million entries
// on the 100k-DOF plate of tools/bench/reduce, 125 MB of fresh pages), then its constrained upper
// triangle, then the DOF graph METIS's quotient graph came from (nodal_ordering.hpp). On two
// threads the analysis thread took 0.9-1.4 s for it beside an assembly of 0.4-0.8 s, so the
// reduction waited for it. The entity pattern already is the node graph, and the upper triangle
// of A(rows, rows) can be written from it directly.
#include "../assembly/pattern.hpp"
#include "../solver/nodal_ordering.hpp"

#include "ffr/preproc/model/constraints.hpp"
#include "ffr/preproc/reduce/reduction.hpp"
#include "ffr/preproc/solver/cholmod_factor.hpp"

#include <atomic>
#include <optional>
#include <vector>

namespace ffr::preproc::detail {

struct SelectedStructure {
  SparseMatrix upper;   ///< structure of the upper triangle of A(rows, rows); values unset (never read)
  QuotientGraph graph;  ///< its node graph: one group per entity with kept DOFs
  std::uint64_t hash = 0;      ///< PatternHash of that upper triangle (solver/pattern_hash.hpp) ...
  std::int64_t upper_nnz = 0;  ///< ... and its entries, with or without `upper`
};

/// The full DOFs whose matrix is the one factorized (C = A(rows, rows)), ascending: T's column
/// of each independent DOF in `columns` must be a unit vector, rows strictly increasing. Empty
/// otherwise (a rigid spider's coupling, say): the caller then forms C by the transform.
std::vector<Index> unit_column_rows(const DofTransform& t, const std::vector<Index>& columns);

/// unit_column_rows for the independent DOFs of the reduction's eigen-solve: all of them, or
/// Craig-Bampton's interior ones. Empty where its matrix is not a principal submatrix.
std::vector<Index> factorized_rows(const FeModel& model, const DofTransform& t, const ReductionSpec& spec);

/// The structure of A(rows, rows) for the pattern's matrix A and ascending, distinct full DOFs
/// `rows`: its node graph and the hash of its upper triangle, and with `upper` that triangle
/// itself. The analysis needs only the graph and the hash (analyse_from_pattern); `upper` is
/// what a check compares entry for entry with the matrix the transform forms (the early
/// analysis's tests), from the same column walk as the hash. Empty when the pattern's
/// entities are not numbered in DOF order (each entity's DOFs contiguous, entities ascending),
/// which the direct construction relies on.
std::optional<SelectedStructure> selected_structure(const Pattern& p, const std::vector<Index>& rows, bool upper);

/// The eigen-solve's factor analysed from the mesh's node graph, with or without the matrix:
/// METIS on the graph of the entities that keep DOFs in the factorized matrix, the order
/// expanded to their DOFs, and the symbolic factorization of that graph expanded too
/// (CholmodFactor::analyze_groups); `C`, when given, is only hashed for factorize's check. False (f untouched) where the factorized matrix is not a principal submatrix of the
/// assembled one (a rigid spider left free, say), the factor options ask for another ordering
/// than METIS, or METIS fails: the caller analyses C by
/// itself then. Why one function for both: the early analysis and the one after the assembly
/// must give one order, so that the modes do not depend on the number of threads.
bool analyse_from_pattern(const FeModel& model, const DofTransform& t, const ReductionSpec& spec, const SparseMatrix* C,
                          const std::atomic<bool>* cancel, CholmodFactor& f);

}  // namespace ffr::preproc::detail
