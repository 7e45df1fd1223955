// HEX8 with incompatible modes (Wilson, Taylor, Doherty & Ghaboussi 1973) and the Taylor,
// Beresford & Wilson (1976) correction: the bubble modes P_k = 1 - xi_k^2, one per
// displacement component, get physical gradients
//     g_k(xi) = detJ(0)/detJ(xi) * J(0)^-T dP_k/dxi,
// so that int g_k dV = detJ(0) J(0)^-T int dP_k/dxi dxi = 0 on any hexahedron: a constant
// strain field excites no bubble and the element passes the patch test. The 9 internal DOFs
// are condensed element by element.
#include "isoparametric.hpp"

#include <Eigen/Cholesky>

namespace ffr::preproc::detail {

Eigen::Matrix3d hex8_centre_jacobian(const Eigen::MatrixX3d& xe) {
  const SolidShape& s = solid_shape(ElementType::Hex8);
  ShapeValues N(8);
  ShapeGradients dN(8, 3);
  s.eval(Eigen::Vector3d::Zero(), N, dN);
  return jacobian(xe, dN);
}

Eigen::Matrix3d hex8_bubble_gradients(const Eigen::Vector3d& xi, const Eigen::Matrix3d& J0inv, double detJ0,
                                      double detJ) {
  // Row k = (dP_k/dxi)^T J0^-1 scaled; dP_k/dxi = -2 xi_k e_k.
  Eigen::Matrix3d G;
  for (int k = 0; k < 3; ++k) G.row(k) = (-2 * xi[k] * detJ0 / detJ) * J0inv.row(k);
  return G;
}

Hex8Condensed hex8_incompatible(const SolidShape& s, const Eigen::MatrixX3d& xe, Lame L) {
  const Eigen::Matrix3d J0 = hex8_centre_jacobian(xe);
  const Eigen::Matrix3d J0inv = J0.inverse();
  const double detJ0 = J0.determinant();
  Eigen::Matrix<double, 33, 33> K = Eigen::Matrix<double, 33, 33>::Zero();
  Eigen::Matrix<double, 11, 3> G;  // 8 nodes, then the 3 bubble modes
  ShapeGradients Gn(8, 3);
  for (int g = 0; g < s.stiffness_rule.size(); ++g) {
    const Eigen::Matrix3d J = jacobian(xe, s.dN_stiffness[g]);
    const double detJ = J.determinant();
    physical_gradients(s.dN_stiffness[g], J.inverse(), Gn);
    G.topRows<8>() = Gn;
    G.bottomRows<3>() = hex8_bubble_gradients(s.stiffness_rule.xi[g], J0inv, detJ0, detJ);
    add_isotropic_stiffness(K, G, L, s.stiffness_rule.w[g] * detJ);
  }
  // Static condensation: alpha = -Kaa^-1 Kau d, K = Kuu - Kua Kaa^-1 Kau.
  const Eigen::Matrix<double, 9, 9> Kaa = K.bottomRightCorner<9, 9>();
  Eigen::LDLT<Eigen::Matrix<double, 9, 9>> ldlt(Kaa);
  Hex8Condensed out;
  out.A = -ldlt.solve(K.bottomLeftCorner<9, 24>());
  out.K = K.topLeftCorner<24, 24>() + K.topRightCorner<24, 9>() * out.A;
  out.K = 0.5 * (out.K + out.K.transpose()).eval();
  return out;
}

}  // namespace ffr::preproc::detail
