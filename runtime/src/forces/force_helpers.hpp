#pragma once
// Second-derivative pieces shared by the force elements (FORMULATION.md section 8).
// For a marker quantity x (a point or an axis) with Jacobian J_x and mode slice S (its phi, or
// phiE_k for an axis), the only configuration dependence of J_x is through xbar (in the frame
// blocks) and A (in the modal block), so for a constant vector f:
//   d(J_x^T f)/dz : (A_a, y) block = f S_a,  (y, A_a) block = S_a^T f^T   (S_a = row a of S)
//   d(J_x z_dot)/dz : (A_a) block = (S y_dot)_a I,  (y) block = A_dot S
// Both vanish for a marker rigidly on its frame.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

namespace ffr::runtime::detail {

/// H += s * d(J_x^T f)/dz for a quantity with mode slice S (nq columns) on a body with nq modes.
template <class Mat>
void add_jt_f_derivative(const Matrix3Xd& S, const Vector3d& f, double s, Mat&& H) {
  const Eigen::Index nq = S.cols();
  if (nq == 0) return;
  // Mode by mode in fixed-size pieces: as dynamic-size outer products of a 3-vector with a row
  // of S (strided) these took as long as a tenth of a tangent build.
  for (Eigen::Index k = 0; k < nq; ++k) {
    const Vector3d sk = s * S.col(k);
    for (int a = 0; a < 3; ++a) {
      H.template block<3, 1>(3 + 3 * a, 12 + k) += sk(a) * f;
      H.template block<1, 3>(12 + k, 3 + 3 * a) += sk(a) * f.transpose();
    }
  }
}

/// out += s * d(J_x^T f)/dz times v (the product of add_jt_f_derivative's matrix with v, without
/// forming it): rows 3 + 3a.. += s f (S_a . v_y), rows 12 + k += s sum_a S_ak (f . v_(3+3a..)).
template <class Vec, class Out>
void add_jt_f_derivative_times(const Matrix3Xd& S, const Vector3d& f, double s, const Vec& v, Out&& out) {
  const Eigen::Index nq = S.cols();
  if (nq == 0) return;
  const Vector3d Sv = S * v.tail(nq);
  Vector3d fv;
  for (int a = 0; a < 3; ++a) {
    out.segment(3 + 3 * a, 3) += (s * Sv(a)) * f.transpose();
    fv(a) = f.dot(v.segment(3 + 3 * a, 3));
  }
  out.tail(nq).noalias() += (s * fv).transpose() * S;
}

/// D = d(J_x z_dot)/dz ([3, nb]) for a quantity with mode slice S.
template <class Mat>
void jzd_derivative(const Matrix3Xd& S, const Matrix3d& Ad, const Eigen::Ref<const VectorXd>& yd, Mat&& D) {
  D.setZero();
  const Eigen::Index nq = S.cols();
  if (nq == 0) return;
  for (int a = 0; a < 3; ++a) D.block(0, 3 + 3 * a, 3, 3).diagonal().setConstant(S.row(a).dot(yd));
  D.rightCols(nq).noalias() = Ad * S;
}

/// Global coordinate range of a body.
inline int offset(const Model& m, int body) { return m.bodies[body].offset; }
inline int ncoord(const Model& m, int body) { return body == kGround ? 0 : m.bodies[body].ncoord(); }

/// Mode slice of a marker quantity: k < 0 the point, else axis k. Empty when rigidly attached.
inline const Matrix3Xd& slice(const Marker& mk, int k) { return k < 0 ? mk.phi : mk.phiE[k]; }
inline bool on_node(const Model& m, const Marker& mk) {
  return mk.body != kGround && mk.node >= 0 && m.bodies[mk.body].nq > 0;
}

}  // namespace ffr::runtime::detail
