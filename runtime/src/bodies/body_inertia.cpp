// Velocity-dependent inertia forces of a flexible body and their analytic tangents.
//
// With r = r0 + A xbar, xbar = c + Phi y, the acceleration of a material point is
// B z_dd + 2 A_dot Phi y_dot (the B_dot z_dot term collapses because xbar_dot = Phi y_dot), so
// Q_v = -int B^T 2 A_dot Phi y_dot dm, which the primitive integrals give as (FORMULATION.md 4)
//   Q_r = -2 A_dot Pdm y_dot,   Q_Aa = -2 A_dot S_a y_dot,
//   Q_y = -2 sum_bc (A^T A_dot)_bc PPdm[b][c] y_dot,
// plus the rotary coupling -2 Gbar(a_dot)^T PsiI^T y_dot on the frame vectors. A rigid body has
// none: in natural coordinates its inertia forces are all constraint reactions.
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/kinematics.hpp"

namespace ffr::runtime {
namespace {

// d(Gbar(x)^T s)/dx for fixed s (9 x 9): the rotary-coupling Coriolis tangent.
Eigen::Matrix<double, 9, 9> gbar_transpose_derivative(const Vector3d& s) {
  Eigen::Matrix<double, 9, 9> D = Eigen::Matrix<double, 9, 9>::Zero();
  const Matrix3d I = Matrix3d::Identity();
  D.block<3, 3>(0, 3) = 0.5 * s(2) * I;
  D.block<3, 3>(0, 6) = -0.5 * s(1) * I;
  D.block<3, 3>(3, 0) = -0.5 * s(2) * I;
  D.block<3, 3>(3, 6) = 0.5 * s(0) * I;
  D.block<3, 3>(6, 0) = 0.5 * s(1) * I;
  D.block<3, 3>(6, 3) = -0.5 * s(0) * I;
  return D;
}

}  // namespace

void body_inertia_forces(const Body& b, const BodyData& bd, const Eigen::Ref<const VectorXd>& zd,
                         Eigen::Ref<VectorXd> Qb) {
  // A beam's frame is held at the global frame by linear rows (FORMULATION.md 15): A_dot = 0
  // to the constraint tolerance, so every term here (each a product with A_dot) vanishes.
  if (b.nq == 0 || b.beam) return;
  const int nq = b.nq;
  const auto yd = zd.tail(nq);
  const Vector3d vy = b.Pdm * yd;
  Qb.head<3>().noalias() -= 2.0 * bd.Ad * vy;
  for (int a = 0; a < 3; ++a) {
    const Vector3d sa = bd.S[a] * yd;
    Qb.segment<3>(3 + 3 * a).noalias() -= 2.0 * bd.Ad * sa;
  }
  const Matrix3d Wm = bd.A.transpose() * bd.Ad;
  auto Qy = Qb.tail(nq);
  for (int k = 0; k < 9; ++k) Qy.noalias() -= 2.0 * Wm(k / 3, k % 3) * bd.Pyd.col(k);
  if (b.has_rotary_coupling) {
    const Vector3d s = b.PsiI.transpose() * yd;
    Qb.segment<9>(3).noalias() -= 2.0 * gbar(bd.Ad).transpose() * s;
  }
}

void body_inertia_tangents(const Body& b, const BodyData& bd, const Eigen::Ref<const VectorXd>& zd,
                           Eigen::Ref<MatrixXd> Kb, Eigen::Ref<MatrixXd> Cb) {
  // A beam's held frame: no inertia forces (above); their derivatives in the frame's rates only
  // couple rates the linear rows hold at zero (Newton's matrix, not the solution).
  if (b.nq == 0 || b.beam) return;
  const int nq = b.nq;
  const auto yd = zd.tail(nq);
  const Matrix3d I = Matrix3d::Identity();
  const Vector3d vy = b.Pdm * yd;
  // Q_r = -2 A_dot Pdm y_dot
  for (int c = 0; c < 3; ++c) Cb.block<3, 3>(0, 3 + 3 * c) += 2.0 * vy(c) * I;
  Cb.block(0, 12, 3, nq).noalias() += 2.0 * bd.Ad * b.Pdm;
  // Q_Aa = -2 A_dot S_a(y) y_dot
  for (int a = 0; a < 3; ++a) {
    const Vector3d sa = bd.S[a] * yd;
    for (int c = 0; c < 3; ++c) Cb.block<3, 3>(3 + 3 * a, 3 + 3 * c) += 2.0 * sa(c) * I;
    Cb.block(3 + 3 * a, 12, 3, nq).noalias() += 2.0 * bd.Ad * bd.S[a];
  }
  // The outer products with the columns of Pyd, mode by mode in fixed-size pieces (as
  // dynamic-size outer products they cost more than their multiply-adds):
  //   d(S_a y_dot)/dy has row c = (PPdm[a][c] y_dot)^T: column k of the (A_a, y) block of K is
  //   2 A_dot p_a(k), p_a(k) = (Pyd(k, 3a + c))_c;
  //   Q_y = -2 sum_bc (A_b . A_dot_c) PPdm[b][c] y_dot: row k of the (y, A_c) block of C is
  //   2 (A q_c(k))^T with q_c(k) = (Pyd(k, 3b + c))_b, and of the (y, A_b) block of K 2 (A_dot p_b(k))^T.
  for (int k = 0; k < nq; ++k) {
    const auto P = bd.Pyd.row(k);
    for (int a = 0; a < 3; ++a) {
      const Vector3d pa(P(3 * a), P(3 * a + 1), P(3 * a + 2));
      const Vector3d qa(P(a), P(3 + a), P(6 + a));
      const Vector3d Kp = 2.0 * bd.Ad * pa;
      Kb.block<3, 1>(3 + 3 * a, 12 + k) += Kp;
      Kb.block<1, 3>(12 + k, 3 + 3 * a) += Kp.transpose();
      Cb.block<1, 3>(12 + k, 3 + 3 * a) += 2.0 * (bd.A * qa).transpose();
    }
  }
  const Matrix3d Wm = bd.A.transpose() * bd.Ad;
  for (int bb = 0; bb < 3; ++bb)
    for (int c = 0; c < 3; ++c) Cb.block(12, 12, nq, nq) += 2.0 * Wm(bb, c) * b.PPdm[bb][c];
  if (b.has_rotary_coupling) {
    const Vector3d s = b.PsiI.transpose() * yd;
    Cb.block<9, 9>(3, 3) += 2.0 * gbar_transpose_derivative(s);
    Cb.block(3, 12, 9, nq).noalias() += 2.0 * gbar(bd.Ad).transpose() * b.PsiI.transpose();
  }
}

}  // namespace ffr::runtime
