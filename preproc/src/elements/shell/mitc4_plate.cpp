// QUAD4 Reissner–Mindlin plate: bilinear w and rotations, full 2 x 2 integration of the
// bending energy, MITC4 assumed transverse shear (mitc4_shear.hpp) with shear factor 5/6.
// Plate DOFs per node (w, rx, ry); beta = (ry, -rx) is the in-plane fibre rotation, so the
// curvatures are (beta_x,x, beta_y,y, beta_x,y + beta_y,x).

#include "local_part.hpp"
#include "mitc4_shear.hpp"
#include "shape2d.hpp"

#include <Eigen/Dense>

namespace ffr::preproc::shell {

LocalPart mitc4_plate(const Eigen::Matrix<double, 4, 2>& xy, const Material& m, double t) {
  const Eigen::Matrix3d Db = plane_stress(m.E, m.nu) * (t * t * t / 12);
  const double Ds = 5.0 / 6.0 * m.E / (2 * (1 + m.nu)) * t;

  LocalPart part;
  part.K = Eigen::MatrixXd::Zero(12, 12);
  const Rule2 rule = quad_gauss2();
  for (std::size_t g = 0; g < rule.xi.size(); ++g) {
    const double xi = rule.xi[g].x(), eta = rule.xi[g].y();
    const Eigen::Matrix<double, 2, 4> dN = quad4_dN(xi, eta);
    const Eigen::Matrix2d J = dN * xy;
    const double dA = J.determinant() * rule.w[g];
    const Eigen::Matrix<double, 2, 4> dNx = J.inverse() * dN;

    Eigen::Matrix<double, 3, 12> Bb = Eigen::Matrix<double, 3, 12>::Zero();
    for (int i = 0; i < 4; ++i) {
      const int crx = 3 * i + 1, cry = 3 * i + 2;
      Bb(0, cry) = dNx(0, i);   // beta_x,x
      Bb(1, crx) = -dNx(1, i);  // beta_y,y
      Bb(2, cry) = dNx(1, i);   // beta_x,y
      Bb(2, crx) = -dNx(0, i);  // beta_y,x
    }
    const Eigen::Matrix<double, 2, 12> Bs = mitc4_shear_B(xy, xi, eta);
    part.K += dA * (Bb.transpose() * Db * Bb + Ds * Bs.transpose() * Bs);
    part.xi.push_back(rule.xi[g]);
    part.area.push_back(dA);
    part.B.push_back(Bb);
    part.Bs.push_back(Bs);
  }
  return part;
}

}  // namespace ffr::preproc::shell
