#include "ffr/runtime/table.hpp"

#include <algorithm>
#include <cassert>

namespace ffr::runtime {

Table::Table(Eigen::VectorXd t, Eigen::MatrixXd values) : t_(std::move(t)), v_(std::move(values)) {
  assert(t_.size() == v_.rows());
  const Eigen::Index n = t_.size();
  m_ = Eigen::MatrixXd::Zero(n, v_.cols());
  if (n < 3) return;
  // Natural spline: tridiagonal system for the interior second derivatives (Thomas algorithm).
  Eigen::VectorXd a(n), b(n), c(n), d(n);
  for (Eigen::Index col = 0; col < v_.cols(); ++col) {
    for (Eigen::Index i = 1; i + 1 < n; ++i) {
      const double h0 = t_(i) - t_(i - 1), h1 = t_(i + 1) - t_(i);
      a(i) = h0;
      b(i) = 2 * (h0 + h1);
      c(i) = h1;
      d(i) = 6 * ((v_(i + 1, col) - v_(i, col)) / h1 - (v_(i, col) - v_(i - 1, col)) / h0);
    }
    for (Eigen::Index i = 2; i + 1 < n; ++i) {
      const double w = a(i) / b(i - 1);
      b(i) -= w * c(i - 1);
      d(i) -= w * d(i - 1);
    }
    for (Eigen::Index i = n - 2; i >= 1; --i)
      m_(i, col) = (d(i) - (i + 2 < n ? c(i) * m_(i + 1, col) : 0.0)) / b(i);
  }
}

void Table::eval(double t, int c, double& value, double& d1, double& d2) const {
  const Eigen::Index n = t_.size();
  if (n == 1) {
    value = v_(0, c);
    d1 = d2 = 0;
    return;
  }
  // Beyond the ends: straight continuation with the end slope (the end curvature is zero).
  if (t <= t_(0) || t >= t_(n - 1)) {
    const bool lo = t <= t_(0);
    const Eigen::Index i = lo ? 0 : n - 2;
    const double h = t_(i + 1) - t_(i);
    const double slope = (v_(i + 1, c) - v_(i, c)) / h +
                         (lo ? -h * (2 * m_(i, c) + m_(i + 1, c)) / 6 : h * (m_(i, c) + 2 * m_(i + 1, c)) / 6);
    const Eigen::Index k = lo ? 0 : n - 1;
    value = v_(k, c) + slope * (t - t_(k));
    d1 = slope;
    d2 = 0;
    return;
  }
  const auto it = std::upper_bound(t_.data(), t_.data() + n, t);
  const Eigen::Index i = std::clamp<Eigen::Index>((it - t_.data()) - 1, 0, n - 2);
  const double h = t_(i + 1) - t_(i);
  const double A = (t_(i + 1) - t) / h, B = (t - t_(i)) / h;
  const double m0 = m_(i, c), m1 = m_(i + 1, c), y0 = v_(i, c), y1 = v_(i + 1, c);
  value = A * y0 + B * y1 + ((A * A * A - A) * m0 + (B * B * B - B) * m1) * h * h / 6;
  d1 = (y1 - y0) / h - (3 * A * A - 1) * h * m0 / 6 + (3 * B * B - 1) * h * m1 / 6;
  d2 = A * m0 + B * m1;
}

}  // namespace ffr::runtime
