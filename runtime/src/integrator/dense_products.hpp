#pragma once
// Products of the small dense matrices of a time step with vectors: the constraint Jacobian
// (tens of rows and columns) and its transpose, and the projections' metric W.
//
// Why not Eigen's: the runtime builds for plain x86-64, where Eigen's products use SSE2 and a
// general kernel with set-up per call; these are compiled for AVX2 and AVX-512 as well and
// called some 30 times a step (Eigen's matrix-vector products were 18 % of a step).

#include <Eigen/Core>

namespace ffr::runtime::detail {

/// y = A x (accumulate = false) or y += A x, for A (m x n, column-major, leading dimension m).
/// x and y must not overlap. Columns whose coefficients are zero are skipped, so a non-finite
/// entry there does not reach y (the callers test the state, not these products, for NaN).
void times(const Eigen::MatrixXd& A, const Eigen::VectorXd& x, Eigen::VectorXd& y, bool accumulate);

/// y += A^T x (x and y must not overlap).
void add_transpose_times(const Eigen::MatrixXd& A, const Eigen::VectorXd& x, Eigen::VectorXd& y);

}  // namespace ffr::runtime::detail
