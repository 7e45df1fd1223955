#include "mitc4_shear.hpp"

#include "shape2d.hpp"

#include <Eigen/Dense>

namespace ffr::preproc::shell {

namespace {

/// Row of the covariant shear strain along natural direction `dir` (0: xi, 1: eta) at (xi, eta).
Eigen::Matrix<double, 1, 12> covariant_row(const Eigen::Matrix<double, 4, 2>& xy, double xi, double eta, int dir) {
  const Eigen::Vector4d N = quad4_N(xi, eta);
  const Eigen::Matrix<double, 2, 4> dN = quad4_dN(xi, eta);
  const Eigen::Vector2d g = (dN * xy).row(dir).transpose();  // x,dir and y,dir
  Eigen::Matrix<double, 1, 12> r = Eigen::Matrix<double, 1, 12>::Zero();
  for (int i = 0; i < 4; ++i) {
    r(3 * i) = dN(dir, i);                // w,dir
    r(3 * i + 2) = N(i) * g.x();          // beta_x = ry
    r(3 * i + 1) = -N(i) * g.y();         // beta_y = -rx
  }
  return r;
}

}  // namespace

Eigen::Matrix<double, 2, 12> mitc4_shear_B(const Eigen::Matrix<double, 4, 2>& xy, double xi, double eta) {
  const auto gxi_bottom = covariant_row(xy, 0, -1, 0);
  const auto gxi_top = covariant_row(xy, 0, 1, 0);
  const auto geta_left = covariant_row(xy, -1, 0, 1);
  const auto geta_right = covariant_row(xy, 1, 0, 1);
  Eigen::Matrix<double, 2, 12> gnat;
  gnat.row(0) = 0.5 * (1 - eta) * gxi_bottom + 0.5 * (1 + eta) * gxi_top;
  gnat.row(1) = 0.5 * (1 - xi) * geta_left + 0.5 * (1 + xi) * geta_right;
  const Eigen::Matrix2d J = quad4_dN(xi, eta) * xy;
  return J.inverse() * gnat;
}

}  // namespace ffr::preproc::shell
