// QUAD4 membrane: bilinear displacements enriched with the incompatible modes (1 - xi^2),
// (1 - eta^2) of Wilson et al. (1973) in Taylor, Beresford & Wilson's form (IJNME 10 (1976)):
// their gradients use the centre Jacobian J0 and the factor det J0 / det J, so
// int B_alpha dA = 0 and the element passes the patch test for any convex shape. The modes make
// in-plane bending of a parallelogram exact (no parasitic shear: no membrane "locking" in
// in-plane bending). Drilling rotations follow Hughes–Brezzi (hb_drilling.hpp: full penalty
// on the element mean of omega - rz, a soft one on its fluctuation); omega includes the
// incompatible modes, so the pure-bending rotation field is matched exactly.
// The four mode amplitudes alpha are condensed out: K = Kdd - Kda Kaa^-1 Kad.
//
// Local DOFs per node (u, v, rz); alpha = (a_u1, a_u2, a_v1, a_v2).

#include "hb_drilling.hpp"
#include "local_part.hpp"
#include "shape2d.hpp"

#include <Eigen/Dense>

namespace ffr::preproc::shell {

LocalPart quad4_membrane(const Eigen::Matrix<double, 4, 2>& xy, const Material& m, double t) {
  const Eigen::Matrix3d D = plane_stress(m.E, m.nu) * t;  // membrane rigidity
  const double gamma = kDrillingGammaOverG * m.E / (2 * (1 + m.nu)) * t;
  const Eigen::Matrix2d J0 = quad4_dN(0, 0) * xy;
  const double det0 = J0.determinant();
  const Eigen::Matrix2d J0inv = J0.inverse();

  constexpr int nd = 12, na = 4, nt = nd + na;
  Eigen::Matrix<double, nt, nt> K = Eigen::Matrix<double, nt, nt>::Zero();
  std::vector<Eigen::Matrix<double, 3, nt>> Bfull;

  LocalPart part;
  std::vector<Eigen::Matrix<double, 1, nt>> rows;  // omega - rz at the Gauss points
  const Rule2 rule = quad_gauss2();
  for (std::size_t g = 0; g < rule.xi.size(); ++g) {
    const double xi = rule.xi[g].x(), eta = rule.xi[g].y();
    const Eigen::Vector4d N = quad4_N(xi, eta);
    const Eigen::Matrix<double, 2, 4> dN = quad4_dN(xi, eta);
    const Eigen::Matrix2d J = dN * xy;
    const double det = J.determinant();
    const Eigen::Matrix<double, 2, 4> dNx = J.inverse() * dN;
    Eigen::Matrix2d dP;  // columns: modes (1 - xi^2), (1 - eta^2); rows d/dxi, d/deta
    dP << -2 * xi, 0, 0, -2 * eta;
    const Eigen::Matrix2d dPx = (det0 / det) * (J0inv * dP);

    Eigen::Matrix<double, 3, nt> B = Eigen::Matrix<double, 3, nt>::Zero();
    Eigen::Matrix<double, 1, nt> r = Eigen::Matrix<double, 1, nt>::Zero();
    for (int i = 0; i < 4; ++i) {
      const int cu = 3 * i, cv = 3 * i + 1, cr = 3 * i + 2;
      B(0, cu) = dNx(0, i);
      B(1, cv) = dNx(1, i);
      B(2, cu) = dNx(1, i);
      B(2, cv) = dNx(0, i);
      add_skew(r, cu, cv, dNx(0, i), dNx(1, i));
      r(cr) = -N(i);
    }
    for (int k = 0; k < 2; ++k) {
      const int cu = nd + k, cv = nd + 2 + k;
      B(0, cu) = dPx(0, k);
      B(1, cv) = dPx(1, k);
      B(2, cu) = dPx(1, k);
      B(2, cv) = dPx(0, k);
      add_skew(r, cu, cv, dPx(0, k), dPx(1, k));
    }
    const double dA = det * rule.w[g];
    K += dA * B.transpose() * D * B;
    rows.push_back(r);
    Bfull.push_back(B);
    part.xi.push_back(rule.xi[g]);
    part.area.push_back(dA);
  }

  // Drilling penalty: the element mean of omega - rz with gamma, the rest with gamma_s.
  double area = 0;
  Eigen::Matrix<double, 1, nt> mean = Eigen::Matrix<double, 1, nt>::Zero();
  for (std::size_t g = 0; g < rows.size(); ++g) {
    mean += part.area[g] * rows[g];
    area += part.area[g];
  }
  mean /= area;
  K += gamma * area * mean.transpose() * mean;
  for (std::size_t g = 0; g < rows.size(); ++g)
    K += kDrillingFluctuationFactor * gamma * part.area[g] * (rows[g] - mean).transpose() * (rows[g] - mean);

  const Eigen::Matrix<double, na, na> Kaa = K.bottomRightCorner<na, na>();
  const Eigen::Matrix<double, na, nd> Kad = K.bottomLeftCorner<na, nd>();
  const Eigen::LLT<Eigen::Matrix<double, na, na>> llt(Kaa);
  const Eigen::Matrix<double, na, nd> A = -llt.solve(Kad);  // alpha = A d
  part.K = K.topLeftCorner<nd, nd>() + K.topRightCorner<nd, na>() * A;
  part.K = 0.5 * (part.K + part.K.transpose()).eval();
  for (const auto& B : Bfull) part.B.push_back(B.leftCols<nd>() + B.rightCols<na>() * A);
  return part;
}

}  // namespace ffr::preproc::shell
