#pragma once
// T += Ja^T diag(w) Jb for a few rows: the penalty term of the tangent (add_penalty_tangent,
// the rows of one constraint block) and the products J_a^T J_b of the constraint Hessian (the
// three rows of two marker quantities' Jacobians).
//
// Why not Eigen's product: for a block of 5 or 6 rows and 9 to 22 columns a side, its GEMM
// packed both operands first, and that was 7-9 % of a time step of the runtime benchmark.

#include <Eigen/Core>

namespace ffr::runtime::detail {

/// buf = (diag(w) Ja)^T (na x rows, column-major): the weighted rows of Ja (rows x na,
/// column-major with leading dimension ld, a block of the constraint Jacobian), each made a
/// contiguous column. buf holds at least na * rows doubles.
void weight_rows(const double* Ja, Eigen::Index ld, int rows, int na, const double* w, double* buf);

/// T(0:na, 0:nb) += buf Jb, for buf from weight_rows and Jb (rows x nb, leading dimension ld);
/// T has leading dimension ldt. One buf serves every Jb against the same Ja.
void add_weighted_product(const double* buf, int rows, int na, const double* Jb, Eigen::Index ld, int nb, double* T,
                          Eigen::Index ldt);

/// T(0:na, 0:nb) += Ja^T diag(w) Jb: weight_rows then add_weighted_product.
void add_weighted_gram(const double* Ja, const double* Jb, Eigen::Index ld, int rows, int na, int nb,
                       const double* w, double* buf, double* T, Eigen::Index ldt);

}  // namespace ffr::runtime::detail
