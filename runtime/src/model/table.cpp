// Tables (table.hpp). Every kind is stored as a cubic Hermite segment per interval, from the two
// samples and the two end slopes: linear (the chord's slope at both ends), PCHIP (Fritsch-Carlson
// slopes), natural spline (the slopes of its second-derivative solution). One evaluation path
// then serves values, derivatives and the exact integral.
#include "ffr/runtime/table.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace ffr::runtime {

const char* to_string(Interpolation k) {
  switch (k) {
    case Interpolation::Linear: return "linear";
    case Interpolation::Pchip: return "pchip";
    case Interpolation::Spline: return "spline";
  }
  return "?";
}

namespace {

// Natural spline: the second derivatives at the knots (tridiagonal system, Thomas algorithm).
void spline_curvatures(const Eigen::VectorXd& t, const Eigen::MatrixXd& v, Eigen::MatrixXd& m) {
  const Eigen::Index n = t.size();
  if (n < 3) return;
  Eigen::VectorXd a(n), b(n), c(n), d(n);
  for (Eigen::Index col = 0; col < v.cols(); ++col) {
    for (Eigen::Index i = 1; i + 1 < n; ++i) {
      const double h0 = t(i) - t(i - 1), h1 = t(i + 1) - t(i);
      a(i) = h0;
      b(i) = 2 * (h0 + h1);
      c(i) = h1;
      d(i) = 6 * ((v(i + 1, col) - v(i, col)) / h1 - (v(i, col) - v(i - 1, col)) / h0);
    }
    for (Eigen::Index i = 2; i + 1 < n; ++i) {
      const double w = a(i) / b(i - 1);
      b(i) -= w * c(i - 1);
      d(i) -= w * d(i - 1);
    }
    for (Eigen::Index i = n - 2; i >= 1; --i) m(i, col) = (d(i) - (i + 2 < n ? c(i) * m(i + 1, col) : 0.0)) / b(i);
  }
}

// PCHIP knot slopes (F. N. Fritsch and R. E. Carlson, "Monotone piecewise cubic interpolation",
// SIAM J. Numer. Anal. 17 (1980); the weighted harmonic mean of F. N. Fritsch and J. Butland,
// "A method for constructing local monotone piecewise cubic interpolants", SIAM J. Sci. Stat.
// Comput. 5 (1984), and the shape-preserving three-point end formula, as in Moler's pchip):
// zero where the data turn, so each segment stays between its two samples.
void pchip_slopes(const Eigen::VectorXd& t, const Eigen::MatrixXd& v, Eigen::MatrixXd& d) {
  const Eigen::Index n = t.size();
  if (n < 2) return;
  for (Eigen::Index col = 0; col < v.cols(); ++col) {
    auto delta = [&](Eigen::Index i) { return (v(i + 1, col) - v(i, col)) / (t(i + 1) - t(i)); };
    if (n == 2) {
      d(0, col) = d(1, col) = delta(0);
      continue;
    }
    for (Eigen::Index k = 1; k + 1 < n; ++k) {
      const double d0 = delta(k - 1), d1 = delta(k);
      const double h0 = t(k) - t(k - 1), h1 = t(k + 1) - t(k);
      if (d0 * d1 <= 0) {
        d(k, col) = 0;
      } else {
        const double w1 = 2 * h1 + h0, w2 = h1 + 2 * h0;
        d(k, col) = (w1 + w2) / (w1 / d0 + w2 / d1);
      }
    }
    auto end = [&](double h0, double h1, double d0, double d1) {
      double s = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
      if (s * d0 <= 0) s = 0;
      else if (d0 * d1 <= 0 && std::abs(s) > 3 * std::abs(d0)) s = 3 * d0;
      return s;
    };
    d(0, col) = end(t(1) - t(0), t(2) - t(1), delta(0), delta(1));
    d(n - 1, col) = end(t(n - 1) - t(n - 2), t(n - 2) - t(n - 3), delta(n - 2), delta(n - 3));
  }
}

}  // namespace

Table::Table(Eigen::VectorXd t, Eigen::MatrixXd values, Interpolation kind)
    : t_(std::move(t)), v_(std::move(values)), kind_(kind) {
  assert(t_.size() == v_.rows());
  const Eigen::Index n = t_.size();
  m_ = Eigen::MatrixXd::Zero(n, v_.cols());
  if (kind_ == Interpolation::Spline) spline_curvatures(t_, v_, m_);
  if (kind_ == Interpolation::Pchip) pchip_slopes(t_, v_, m_);
  cum_ = Eigen::MatrixXd::Zero(n, v_.cols());
  for (Eigen::Index c = 0; c < v_.cols(); ++c)
    for (Eigen::Index i = 0; i + 1 < n; ++i)
      cum_(i + 1, c) = cum_(i, c) + segment_integral(i, t_(i + 1), static_cast<int>(c));
}

void Table::slopes(Eigen::Index i, int c, double& s0, double& s1) const {
  const double h = t_(i + 1) - t_(i), delta = (v_(i + 1, c) - v_(i, c)) / h;
  switch (kind_) {
    case Interpolation::Linear: s0 = s1 = delta; return;
    case Interpolation::Pchip: s0 = m_(i, c); s1 = m_(i + 1, c); return;
    case Interpolation::Spline:
      s0 = delta - h * (2 * m_(i, c) + m_(i + 1, c)) / 6;
      s1 = delta + h * (m_(i, c) + 2 * m_(i + 1, c)) / 6;
      return;
  }
}

void Table::segment(Eigen::Index i, double t, int c, double& value, double& d1, double& d2) const {
  const double h = t_(i + 1) - t_(i), u = (t - t_(i)) / h;
  const double y0 = v_(i, c), y1 = v_(i + 1, c);
  if (kind_ == Interpolation::Linear) {
    const double delta = (y1 - y0) / h;
    value = y0 + delta * (t - t_(i));
    d1 = delta;
    d2 = 0;
    return;
  }
  double s0, s1;
  slopes(i, c, s0, s1);
  // Cubic Hermite basis in u = (t - t_i) / h.
  const double u2 = u * u, u3 = u2 * u;
  value = y0 * (2 * u3 - 3 * u2 + 1) + h * s0 * (u3 - 2 * u2 + u) + y1 * (-2 * u3 + 3 * u2) + h * s1 * (u3 - u2);
  d1 = (y0 * (6 * u2 - 6 * u) + h * s0 * (3 * u2 - 4 * u + 1) + y1 * (-6 * u2 + 6 * u) + h * s1 * (3 * u2 - 2 * u)) / h;
  d2 = (y0 * (12 * u - 6) + h * s0 * (6 * u - 4) + y1 * (6 - 12 * u) + h * s1 * (6 * u - 2)) / (h * h);
}

double Table::segment_integral(Eigen::Index i, double t, int c) const {
  const double h = t_(i + 1) - t_(i), u = (t - t_(i)) / h;
  double s0, s1;
  slopes(i, c, s0, s1);
  const double u2 = u * u, u3 = u2 * u, u4 = u3 * u;
  return h * (v_(i, c) * (u4 / 2 - u3 + u) + h * s0 * (u4 / 4 - 2 * u3 / 3 + u2 / 2) + v_(i + 1, c) * (u3 - u4 / 2) +
              h * s1 * (u4 / 4 - u3 / 3));
}

void Table::eval(double t, int c, double& value, double& d1, double& d2) const {
  const Eigen::Index n = t_.size();
  if (n == 1) {
    value = v_(0, c);
    d1 = d2 = 0;
    return;
  }
  // Beyond the ends: straight continuation with the end slope.
  if (t < t_(0) || t >= t_(n - 1)) {
    const bool lo = t < t_(0);
    double s0, s1;
    slopes(lo ? 0 : n - 2, c, s0, s1);
    const Eigen::Index k = lo ? 0 : n - 1;
    d1 = lo ? s0 : s1;
    value = v_(k, c) + d1 * (t - t_(k));
    d2 = 0;
    return;
  }
  const auto it = std::upper_bound(t_.data(), t_.data() + n, t);
  const Eigen::Index i = std::clamp<Eigen::Index>((it - t_.data()) - 1, 0, n - 2);
  segment(i, t, c, value, d1, d2);
}

double Table::integral(double t, int c) const {
  const Eigen::Index n = t_.size();
  if (n == 1) return v_(0, c) * (t - t_(0));
  if (t < t_(0) || t >= t_(n - 1)) {
    const bool lo = t < t_(0);
    double s0, s1;
    slopes(lo ? 0 : n - 2, c, s0, s1);
    const Eigen::Index k = lo ? 0 : n - 1;
    const double dt = t - t_(k), s = lo ? s0 : s1;
    return cum_(k, c) + v_(k, c) * dt + 0.5 * s * dt * dt;
  }
  const auto it = std::upper_bound(t_.data(), t_.data() + n, t);
  const Eigen::Index i = std::clamp<Eigen::Index>((it - t_.data()) - 1, 0, n - 2);
  return cum_(i, c) + segment_integral(i, t, c);
}

}  // namespace ffr::runtime
