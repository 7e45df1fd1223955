#pragma once
// The tests' oracle for derivatives: central differences, column by column, of a vector function,
// and the relative error a test compares a derivative with them by.
#include <Eigen/Core>

#include <algorithm>

namespace ffr::runtime::test {

/// Central differences of f: R^n -> R^m at x with step eps, column by column.
template <class F>
Eigen::MatrixXd central_differences(const F& f, const Eigen::VectorXd& x, double eps) {
  Eigen::MatrixXd D;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd a = x, b = x;
    a(i) += eps;
    b(i) -= eps;
    const Eigen::VectorXd col = (f(a) - f(b)) / (2 * eps);
    if (i == 0) D.resize(col.size(), x.size());
    D.col(i) = col;
  }
  return D;
}

/// The largest entry of a - b over the largest of b (or over 1 when b is smaller).
inline double rel_err(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

}  // namespace ffr::runtime::test
