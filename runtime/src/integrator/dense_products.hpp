#pragma once
// Products of the small dense matrices of a time step with vectors: the constraint Jacobian
// (tens of rows and columns) and its transpose, and the projections' metric W.
//
// Why not Eigen's: the runtime builds for plain x86-64, where Eigen's products use SSE2 and a
// general kernel with set-up per call; these are compiled for AVX2 as well, skip the columns
// whose coefficients are zero, and are called some 30 times a step. With Eigen's matrix-vector
// products in their place the step of tools/bench/runtime_step took about 8 % longer
// (RESULTS.md there), above the 5 % for which an own kernel is kept.

#include <Eigen/Core>

namespace ffr::runtime::detail {

/// y = A x (accumulate = false) or y += A x, for the leading rows x cols block of A (column-major,
/// leading dimension A.rows()): x and y are read and written in their first cols and rows
/// entries (the unknowns of a step with driven bodies eliminated). x and y must not overlap.
/// Columns whose coefficients are zero are skipped, so a non-finite entry there does not reach
/// y (the callers test the state, not these products, for NaN).
void times(const Eigen::MatrixXd& A, Eigen::Index rows, Eigen::Index cols, const Eigen::VectorXd& x, Eigen::VectorXd& y,
           bool accumulate);
/// The same on raw storage: A column-major with leading dimension ld (also for the stacked
/// modal integrals, Body::PPdm_stack, whose products with y and y_dot each evaluation makes).
void times(const double* A, Eigen::Index ld, Eigen::Index rows, Eigen::Index cols, const double* x, double* y,
           bool accumulate);
inline void times(const Eigen::MatrixXd& A, const Eigen::VectorXd& x, Eigen::VectorXd& y, bool accumulate) {
  times(A, A.rows(), A.cols(), x, y, accumulate);
}

/// y += B^T x for the leading rows x cols block B of A (x and y must not overlap).
void add_transpose_times(const Eigen::MatrixXd& A, Eigen::Index rows, Eigen::Index cols, const Eigen::VectorXd& x,
                         Eigen::VectorXd& y);
inline void add_transpose_times(const Eigen::MatrixXd& A, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  add_transpose_times(A, A.rows(), A.cols(), x, y);
}

}  // namespace ffr::runtime::detail
