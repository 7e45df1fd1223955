#pragma once
// Shape functions and in-plane quadrature of the order-1 shell facets (gmsh node order):
// QUAD4 on [-1,1]^2 with corners (-1,-1), (1,-1), (1,1), (-1,1); TRI3 on the unit triangle
// with area coordinates (1 - xi - eta, xi, eta).

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <vector>

namespace ffr::preproc::shell {

inline constexpr double kGauss2 = 0.577350269189625764509148780502;  // 1/sqrt(3)
inline constexpr std::array<double, 4> kQuadXi{-1, 1, 1, -1};
inline constexpr std::array<double, 4> kQuadEta{-1, -1, 1, 1};

inline Eigen::Vector4d quad4_N(double xi, double eta) {
  Eigen::Vector4d N;
  for (int i = 0; i < 4; ++i) N(i) = 0.25 * (1 + kQuadXi[i] * xi) * (1 + kQuadEta[i] * eta);
  return N;
}

/// Rows d/dxi, d/deta.
inline Eigen::Matrix<double, 2, 4> quad4_dN(double xi, double eta) {
  Eigen::Matrix<double, 2, 4> d;
  for (int i = 0; i < 4; ++i) {
    d(0, i) = 0.25 * kQuadXi[i] * (1 + kQuadEta[i] * eta);
    d(1, i) = 0.25 * kQuadEta[i] * (1 + kQuadXi[i] * xi);
  }
  return d;
}

inline Eigen::Vector3d tri3_N(double xi, double eta) { return {1 - xi - eta, xi, eta}; }

inline Eigen::Matrix<double, 2, 3> tri3_dN() {
  Eigen::Matrix<double, 2, 3> d;
  d << -1, 1, 0, -1, 0, 1;
  return d;
}

/// An in-plane rule: natural coordinates and weights (reference measure 4 or 1/2).
struct Rule2 {
  std::vector<Eigen::Vector2d> xi;
  std::vector<double> w;
};

/// 2 x 2 Gauss on the square (exact to degree 3 per variable).
inline Rule2 quad_gauss2() {
  Rule2 r;
  for (double e : {-kGauss2, kGauss2})
    for (double x : {-kGauss2, kGauss2}) {
      r.xi.emplace_back(x, e);
      r.w.push_back(1.0);
    }
  return r;
}

/// 3-point interior rule on the triangle (exact to degree 2).
inline Rule2 tri_rule3() {
  Rule2 r;
  r.xi = {{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
  r.w = {1.0 / 6, 1.0 / 6, 1.0 / 6};
  return r;
}

/// Plane-stress elasticity [[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu)/2]] E / (1 - nu^2).
inline Eigen::Matrix3d plane_stress(double E, double nu) {
  Eigen::Matrix3d D;
  D << 1, nu, 0, nu, 1, 0, 0, 0, 0.5 * (1 - nu);
  return D * (E / (1 - nu * nu));
}

}  // namespace ffr::preproc::shell
