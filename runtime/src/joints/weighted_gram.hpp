#pragma once
// T += Ja^T diag(w) Jb for a few rows: the penalty term of the tangent (add_penalty_tangent,
// the rows of one constraint block) and the products J_a^T J_b of the constraint Hessian (the
// three rows of two marker quantities' Jacobians).
//
// Why not Eigen's product: for a block of 5 or 6 rows and 9 to 22 columns a side, its GEMM
// packed both operands first, and that was 7-9 % of a time step of the runtime benchmark.

#include <Eigen/Core>

namespace ffr::runtime::detail {

/// T(0:na, 0:nb) += Ja^T diag(w) Jb, where Ja (rows x na) and Jb (rows x nb) are column-major
/// with leading dimension ld (blocks of the constraint Jacobian), T has leading dimension ldt,
/// and buf holds at least na * rows doubles of work space.
void add_weighted_gram(const double* Ja, const double* Jb, Eigen::Index ld, int rows, int na, int nb,
                       const double* w, double* buf, double* T, Eigen::Index ldt);

}  // namespace ffr::runtime::detail
