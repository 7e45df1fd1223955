#pragma once
// The exact triad of a plate node (FORMULATION.md 16, "Welds"): the Gram-Schmidt frame of its
// gradients a = r_x, b = r_y,
//   t1 = a / |a|,  t3 = (a x b) / |a x b|,  t2 = t3 x t1 = v2 / |v2|,  v2 = (a.a) b - (a.b) a,
// each axis the unit vector n(v) = v / |v| of a polynomial v(a, b) (v1 = a, linear; v3 = a x b,
// bilinear; v2, cubic), so its derivatives are those of n composed with those of v:
//   Dn[u]       = P u / r                                   (P = I - n n^T, r = |v|)
//   D2n[u, w]   = -((n.w) P u + (n.u) P w + (u.P w) n) / r^2
//   f . D2n     = -(P f n^T + n f^T P + (n.f) P) / r^2       (as a bilinear form)
//   D2t[z, z']  = D2n[Dv z, Dv z'] + Dn[D2v[z, z']]
// with z = (da, db) in R^6. A marker on a node reads its axes e_k = A T R_k (R = its axes in the
// reference triad, constant): exact for any rotation of the node, with no linearisation.
// Allocation-free (fixed-size arithmetic only).

#include <Eigen/Core>

namespace ffr::runtime::detail {

using Matrix36 = Eigen::Matrix<double, 3, 6>;
using Matrix66 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

struct PlateTriad {
  Eigen::Vector3d a, b;       ///< the gradients r_x, r_y
  Eigen::Vector3d t[3];       ///< the unit axes t1, t2, t3
  Matrix36 J[3];              ///< dt_i / d(a, b)
  Eigen::Vector3d v[3];       ///< the unnormalised axes v_i
  Matrix36 Jv[3];             ///< dv_i / d(a, b)
  double r[3] = {0, 0, 0};    ///< |v_i|
};

/// The triad and its first derivatives. a and b must not be parallel (a plate node's gradients
/// never are while the element's membrane energy is finite; the caller checks nothing).
void plate_triad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, PlateTriad& T);

/// The axis e = sum_i w_i t_i and its Jacobian d e / d(a, b).
Eigen::Vector3d triad_axis(const PlateTriad& T, const Eigen::Vector3d& w, Matrix36* G = nullptr);

/// sum_i w_i D2t_i[z, z] (the acceleration bias of the axis e = sum_i w_i t_i along the rate z).
Eigen::Vector3d triad_axis_second(const PlateTriad& T, const Eigen::Vector3d& w, const Vector6& z);

/// H = f . D2e (6 x 6, symmetric) for the axis e = sum_i w_i t_i: the second derivative of f . e.
void triad_axis_hessian(const PlateTriad& T, const Eigen::Vector3d& w, const Eigen::Vector3d& f, Matrix66& H);

}  // namespace ffr::runtime::detail
