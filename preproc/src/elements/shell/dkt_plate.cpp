// TRI3 discrete Kirchhoff plate (DKT; Batoz, Bathe & Ho, IJNME 15 (1980) 1771–1812),
// constructed from its definition rather than from tabulated coefficients:
//  - the fibre rotations beta = (ry, -rx) are quadratic over the triangle (6-node
//    interpolation: corners and edge midpoints);
//  - at the corners beta takes the nodal values;
//  - at each edge midpoint the Kirchhoff constraint fixes the tangential component from a
//    cubic w along the edge, beta_s = -w,s = -3/(2l) (w_j - w_i) - (beta_i + beta_j).s / 4, and the
//    normal component is the mean of the corner values, beta_n = (beta_i + beta_j).n / 2.
// Curvatures (beta_x,x, beta_y,y, beta_x,y + beta_y,x) are linear; the 3-point rule integrates
// the bending energy exactly. No transverse shear energy (thin plate).

#include "local_part.hpp"
#include "shape2d.hpp"

#include <Eigen/Dense>

namespace ffr::preproc::shell {

namespace {

/// Derivatives (rows d/dxi, d/deta) of the 6-node quadratic functions: corners 1-3, then
/// midpoints of edges 2-3, 3-1, 1-2.
Eigen::Matrix<double, 2, 6> quadratic_dN(double xi, double eta) {
  const double L1 = 1 - xi - eta, L2 = xi, L3 = eta;
  Eigen::Matrix<double, 2, 6> d;
  d << -(4 * L1 - 1), 4 * L2 - 1, 0, 4 * L3, -4 * L3, 4 * (L1 - L2),  //
      -(4 * L1 - 1), 0, 4 * L3 - 1, 4 * L2, 4 * (L1 - L3), -4 * L2;
  return d;
}

}  // namespace

LocalPart dkt_plate(const Eigen::Matrix<double, 3, 2>& xy, const Material& m, double t) {
  const Eigen::Matrix3d Db = plane_stress(m.E, m.nu) * (t * t * t / 12);

  // Tb (12 x 9): beta at the 6 interpolation nodes from (w, rx, ry) at the corners.
  Eigen::Matrix<double, 12, 9> Tb = Eigen::Matrix<double, 12, 9>::Zero();
  for (int a = 0; a < 3; ++a) {
    Tb(2 * a, 3 * a + 2) = 1;       // beta_x = ry
    Tb(2 * a + 1, 3 * a + 1) = -1;  // beta_y = -rx
  }
  constexpr int edge[3][2] = {{1, 2}, {2, 0}, {0, 1}};
  for (int k = 0; k < 3; ++k) {
    const int i = edge[k][0], j = edge[k][1];
    const Eigen::Vector2d d = (xy.row(j) - xy.row(i)).transpose();
    const double l = d.norm();
    const Eigen::Vector2d s = d / l, n(s.y(), -s.x());
    const Eigen::Matrix2d P = -0.25 * s * s.transpose() + 0.5 * n * n.transpose();
    auto rows = Tb.middleRows<2>(6 + 2 * k);
    rows = P * (Tb.middleRows<2>(2 * i) + Tb.middleRows<2>(2 * j));
    rows.col(3 * j) += -1.5 / l * s;
    rows.col(3 * i) += 1.5 / l * s;
  }

  const Eigen::Matrix2d J = tri3_dN() * xy;
  const Eigen::Matrix2d Jinv = J.inverse();
  const double det = J.determinant();

  LocalPart part;
  part.K = Eigen::MatrixXd::Zero(9, 9);
  const Rule2 rule = tri_rule3();
  for (std::size_t g = 0; g < rule.xi.size(); ++g) {
    const Eigen::Matrix<double, 2, 6> dNx = Jinv * quadratic_dN(rule.xi[g].x(), rule.xi[g].y());
    Eigen::Matrix<double, 3, 12> G = Eigen::Matrix<double, 3, 12>::Zero();
    for (int a = 0; a < 6; ++a) {
      G(0, 2 * a) = dNx(0, a);
      G(1, 2 * a + 1) = dNx(1, a);
      G(2, 2 * a) = dNx(1, a);
      G(2, 2 * a + 1) = dNx(0, a);
    }
    const Eigen::Matrix<double, 3, 9> B = G * Tb;
    const double dA = det * rule.w[g];
    part.K += dA * B.transpose() * Db * B;
    part.xi.push_back(rule.xi[g]);
    part.area.push_back(dA);
    part.B.push_back(B);
  }
  return part;
}

}  // namespace ffr::preproc::shell
