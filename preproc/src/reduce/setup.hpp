#pragma once
// What the reductions and their early symbolic analysis (EarlyAnalysis) must build alike: the
// interface states of a method, the constrained matrices and the factor options of the free
// and clamped eigen-solves.
#include "ffr/preproc/model/constraints.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/solver/cholmod_factor.hpp"

#include <vector>

namespace ffr::preproc::detail {

/// Frees a matrix's storage. (Assigning an empty matrix keeps Eigen 3.4's allocation: its
/// SparseMatrix has no move assignment, and the copy assignment only sets the size to 0.)
inline void release(SparseMatrix& A) { SparseMatrix().swap(A); }

/// The state of every interface under the reduction (held, boundary or free).
std::vector<InterfaceState> states_for(const FeModel& model, const ReductionSpec& spec);

/// T^T A T over the independent DOFs: its upper triangle for the eigen-solves, the full
/// matrix for Craig-Bampton (which partitions it into blocks).
SparseMatrix constrained(const DofTransform& t, const SparseMatrix& A, bool full);

/// Options of the factorization the eigen-solve uses: K - sigma M for the free and clamped
/// methods, K_ii (the interior block) for Craig-Bampton.
FactorOptions eigen_factor_options(const ReductionSpec& spec);

/// Craig-Bampton: the independent DOFs of the boundary, the six of every non-frame interface node.
std::vector<Index> boundary_dofs(const FeModel& model, const DofTransform& t, const ReductionSpec& spec);

}  // namespace ffr::preproc::detail
