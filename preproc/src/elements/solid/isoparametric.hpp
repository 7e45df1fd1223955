#pragma once
// Private helpers shared by the solid kernels: Jacobians, physical gradients and the
// isotropic / geometric stiffness accumulation written per node pair (no B matrix, no heap).
#include "ffr/preproc/elements/element.hpp"
#include "ffr/preproc/elements/solid_shape.hpp"

#include <Eigen/Core>
#include <Eigen/LU>

namespace ffr::preproc::detail {

/// J(i, j) = dx_i / dxi_j for element coordinates xe (nn x 3) and reference gradients dN.
template <class XE, class DN>
inline Eigen::Matrix3d jacobian(const XE& xe, const DN& dN) {
  return xe.transpose() * dN;
}

/// Physical gradients G(a, k) = dN_a / dx_k = sum_j dN(a, j) (J^-1)(j, k).
inline void physical_gradients(const ShapeGradients& dN, const Eigen::Matrix3d& Jinv, ShapeGradients& G) {
  G.noalias() = dN * Jinv;
}

/// Lame constants of an isotropic material (nu already validated).
struct Lame {
  double lambda, mu;
};
inline Lame lame(const Material& m) {
  return {m.E * m.nu / ((1 + m.nu) * (1 - 2 * m.nu)), m.E / (2 * (1 + m.nu))};
}

/// K(3a.., 3b..) += dv [lambda g_a g_b^T + mu (g_a . g_b) I + mu g_b g_a^T] for all a, b:
/// the isotropic B^T D B written per node pair (energy lambda/2 (div u)^2 + mu eps:eps).
template <class KM, class GM>
inline void add_isotropic_stiffness(KM& K, const GM& G, Lame L, double dv) {
  // Scalar loops: this is the innermost kernel of the assembly (HEX20: 27 points x 210 pairs).
  const int n = static_cast<int>(G.rows());
  const double l = L.lambda * dv, m = L.mu * dv;
  for (int a = 0; a < n; ++a) {
    const double ax = G(a, 0), ay = G(a, 1), az = G(a, 2);
    for (int b = a; b < n; ++b) {
      const double bx = G(b, 0), by = G(b, 1), bz = G(b, 2);
      const double d = m * (ax * bx + ay * by + az * bz);
      const double k[3][3] = {{l * ax * bx + m * bx * ax + d, l * ax * by + m * bx * ay, l * ax * bz + m * bx * az},
                              {l * ay * bx + m * by * ax, l * ay * by + m * by * ay + d, l * ay * bz + m * by * az},
                              {l * az * bx + m * bz * ax, l * az * by + m * bz * ay, l * az * bz + m * bz * az + d}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          K(3 * a + i, 3 * b + j) += k[i][j];
          if (b != a) K(3 * b + j, 3 * a + i) += k[i][j];
        }
    }
  }
}

/// K_G(3a+i, 3b+i) += dv g_a^T S g_b (the initial-stress stiffness for stress S).
template <class KM, class GM>
inline void add_geometric_stiffness(KM& K, const GM& G, const Eigen::Matrix3d& S, double dv) {
  const int n = static_cast<int>(G.rows());
  for (int a = 0; a < n; ++a) {
    const Eigen::Vector3d Sga = S * G.row(a).transpose();
    for (int b = a; b < n; ++b) {
      const double k = dv * G.row(b).dot(Sga);
      for (int i = 0; i < 3; ++i) {
        K(3 * a + i, 3 * b + i) += k;
        if (b != a) K(3 * b + i, 3 * a + i) += k;
      }
    }
  }
}

/// Symmetric 3x3 stress from Voigt (xx, yy, zz, xy, yz, xz) and back.
inline Eigen::Matrix3d voigt_to_tensor(const Eigen::Matrix<double, 6, 1>& s) {
  Eigen::Matrix3d S;
  S << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return S;
}
inline Eigen::Matrix<double, 6, 1> tensor_to_voigt(const Eigen::Matrix3d& S) {
  Eigen::Matrix<double, 6, 1> s;
  s << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
  return s;
}

/// Throws ElementError if xe has the wrong shape or non-finite coordinates, or if the
/// Jacobian determinant is not positive at every corner and every quadrature point.
void check_geometry(const SolidShape& s, const Eigen::MatrixX3d& xe);

/// Range of detJ over the corners and all quadrature points; `where` names the minimum.
struct JacobianRange {
  double min = 0, max = 0;
  std::string where;
};
JacobianRange jacobian_range(const SolidShape& s, const Eigen::MatrixX3d& xe);

/// HEX8 incompatible modes (Taylor et al. 1976): condensed 24 x 24 stiffness and the map
/// from nodal displacements to the internal mode amplitudes, alpha = A d.
struct Hex8Condensed {
  Eigen::Matrix<double, 24, 24> K;
  Eigen::Matrix<double, 9, 24> A;
};
Hex8Condensed hex8_incompatible(const SolidShape& s, const Eigen::MatrixX3d& xe, Lame L);
/// Physical gradients of the three bubble modes at xi (rows), with the Taylor correction.
Eigen::Matrix3d hex8_bubble_gradients(const Eigen::Vector3d& xi, const Eigen::Matrix3d& J0inv,
                                      double detJ0, double detJ);
/// Reference-centre Jacobian of a HEX8.
Eigen::Matrix3d hex8_centre_jacobian(const Eigen::MatrixX3d& xe);

}  // namespace ffr::preproc::detail
