// Gravity, modal elasticity and damping, and geometric stiffening of one body.
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/kinematics.hpp"

#include "../integrator/dense_products.hpp"

#include <Eigen/Eigenvalues>

namespace ffr::runtime {
namespace {

// KG = sum_c a_c Kt[c] + alpha_c Kr[c] + sum_j omega_bar_j Kw[j] + sum over interfaces of
// F_c KF[c] + M_c KM[c] (FORMULATION.md 7), with a the frame acceleration minus gravity (the
// inertial load a body feels), alpha the angular acceleration, omega_bar = (wx^2, wy^2, wz^2,
// wx wy, wy wz, wx wz), and F, M the loads of the joints at each interface node (bd.iface_load,
// set by interface_loads), all in the body frame.
// The spin the centrifugal cases see. A Craig-Bampton body's frame is a node's, which its joints
// may leave free to turn with the bending there: its rate then carries every bending vibration at
// that node, and squared into the centrifugal stress that fluctuation pumped the highest modes
// of Simeon's rod with a massless slider until Newton stalled; such a body uses its mean spin,
// the frame's plus I^-1 (spin_h y_dot) (I = tr(Jc) 1 - Jc about O). A clamped body's frame is its
// clamp, whose spin is the one its inertial loads have in it (its vibration's rotation is not
// centrifugal: with the mean spin the spring chain on a driven hub diverged); a free body's modes
// carry no angular momentum about its mean axes. (FORMULATION.md 7.)
Vector3d mean_spin(const StiffeningTerms& s, const BodyData& bd, const Eigen::Ref<const VectorXd>& yd, Matrix3d* Iinv) {
  if (!s.use_mean_spin) {
    if (Iinv) Iinv->setZero();
    return bd.omega;
  }
  // A pseudo-inverse: a body of points on a line (a lumped chain) has no inertia about it, and
  // its modal rates no angular momentum about it either.
  const Matrix3d I = bd.Jc.trace() * Matrix3d::Identity() - bd.Jc;
  Eigen::SelfAdjointEigenSolver<Matrix3d> es;
  es.computeDirect(0.5 * (I + I.transpose()));
  const Vector3d ev = es.eigenvalues();
  const double tol = 1e-12 * ev.cwiseAbs().maxCoeff();
  Vector3d ie = Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    if (ev(a) > tol) ie(a) = 1.0 / ev(a);
  const Matrix3d inv = es.eigenvectors() * ie.asDiagonal() * es.eigenvectors().transpose();
  if (Iinv) *Iinv = inv;
  return bd.omega + inv * (s.spin_h * yd);
}

void geometric_stiffness(const StiffeningTerms& s, const BodyData& bd, const Vector3d& w, MatrixXd& KG) {
  const double wbar[6] = {w(0) * w(0), w(1) * w(1), w(2) * w(2), w(0) * w(1), w(1) * w(2), w(0) * w(2)};
  KG.setZero();
  for (int c = 0; c < 3; ++c) KG += bd.acc(c) * s.Kt[c] + bd.alpha(c) * s.Kr[c];
  for (int j = 0; j < 6; ++j) KG += wbar[j] * s.Kw[j];
  for (std::size_t i = 0; i < s.interfaces.size(); ++i) {
    const auto load = bd.iface_load.col(static_cast<Eigen::Index>(i));
    for (int c = 0; c < 3; ++c) KG += load(c) * s.interfaces[i].KF[c] + load(3 + c) * s.interfaces[i].KM[c];
  }
}

}  // namespace

// The strain energy of Ke/M1 with its quartic closure (FORMULATION.md 7):
//   U = 1/2 s^T Ke s,  s = y + Ke^+ g(y),  g_k = 1/2 y^T M1[k] y
// (M1[k] is the stress of mode k against the nonlinear strain of y, so g is that strain
// projected on the modal stresses and s the modal strain, linear plus nonlinear). It writes
//   X1 (column k = M1[k] y), g (bd.Py column 0), s (column 1), and
//   G1 = sum_k s_k M1[k] + X1 + X1^T + X1 Ke^+ X1^T, the second derivative of U - 1/2 y^T Ke y.
// bd.Py is work here: update_bodies fills and reads it before, nothing after.
void modal_stress_terms(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& y) {
  const ModalStressStiffness& m = *b.modal_stress;
  const Eigen::Index nq = b.nq, ld = m.by_mode.rows();
  const auto Kinv = m.by_mode.bottomRows(nq);
  detail::times(m.by_mode.data(), ld, nq * nq, nq, y.data(), bd.X1.data(), false);
  auto g = bd.Py.col(0);
  auto s = bd.Py.col(1);
  auto v = bd.Py.col(2);
  g.noalias() = 0.5 * (bd.X1.transpose() * y);
  s = y;
  s.noalias() += Kinv * g;
  detail::times(m.by_coeff.data(), nq * nq, nq * nq, nq, s.data(), bd.G1.data(), false);
  bd.G1 += bd.X1;
  bd.G1 += bd.X1.transpose();
  for (Eigen::Index j = 0; j < nq; ++j) {
    v.noalias() = Kinv * bd.X1.row(j).transpose();
    bd.G1.col(j).noalias() += bd.X1 * v;
  }
}

void body_applied_forces(const Body& b, BodyData& bd, const Vector3d& g, const Eigen::Ref<const VectorXd>& z,
                         const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<VectorXd> Qb) {
  // Gravity: int B^T g dm.
  Qb.head<3>() += b.mass * g;
  for (int a = 0; a < 3; ++a) Qb.segment<3>(3 + 3 * a) += bd.md(a) * g;
  if (b.nq == 0) return;
  const auto y = z.tail(b.nq);
  const auto yd = zd.tail(b.nq);
  auto Qy = Qb.tail(b.nq);
  const Vector3d gl = bd.A.transpose() * g;
  Qy.noalias() += b.Pdm.transpose() * gl;
  // A beam's or plate's Ke and De are zero (its elements' forces are below): 102 x 102 products
  // at every evaluation of a 16-element beam.
  if (!b.beam && !b.plate) {
    Qy.noalias() -= b.Ke * y;
    Qy.noalias() -= b.De * yd;
  }
  if (b.stiffening) {
    geometric_stiffness(*b.stiffening, bd, mean_spin(*b.stiffening, bd, yd, nullptr), bd.KG);
    Qy.noalias() -= bd.KG * y;
  }
  // -dU/dy beyond -Ke y: -(g + X1 s) (modal_stress_terms).
  if (b.modal_stress) {
    modal_stress_terms(b, bd, y);
    Qy -= bd.Py.col(0);
    Qy.noalias() -= bd.X1 * bd.Py.col(1);
  }
  if (b.prestress) {
    Qy -= b.prestress->f0;
    Qy.noalias() -= b.prestress->K1 * y;
  }
  // A beam's or plate's elastic and damping forces (their tangents: body_applied_tangents, at a
  // refresh only).
  if (b.beam) ancf_beam_forces(*b.beam, y, yd, Qy, nullptr, nullptr);
  if (b.plate) ancf_plate_forces(*b.plate, y, yd, Qy, nullptr, nullptr);
}

void body_applied_tangents(const Body& b, const BodyData& bd, const Vector3d& g, const Eigen::Ref<const VectorXd>& z,
                           const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<MatrixXd> Kb, Eigen::Ref<MatrixXd> Cb) {
  if (b.nq == 0) return;
  const int nq = b.nq;
  for (int a = 0; a < 3; ++a) {
    Kb.block(3 + 3 * a, 12, 3, nq).noalias() -= g * b.Pdm.row(a);
    Kb.block(12, 3 + 3 * a, nq, 3).noalias() -= b.Pdm.row(a).transpose() * g.transpose();
  }
  auto Kyy = Kb.block(12, 12, nq, nq);
  auto Cyy = Cb.block(12, 12, nq, nq);
  // A beam's or plate's Ke and De are zero; its elements' tangents go onto their own blocks.
  if (b.beam) {
    ancf_beam_tangents(*b.beam, z.tail(nq), zd.tail(nq), Kyy, Cyy);
  } else if (b.plate) {
    ancf_plate_tangents(*b.plate, z.tail(nq), zd.tail(nq), Kyy, Cyy);
  } else {
    Kyy += b.Ke;
    Cyy += b.De;
  }
  // Stiffening: the y-dependence at the current (frozen) accelerations, spin and joint loads.
  if (b.stiffening) Kyy += bd.KG;
  // The rest of d^2 U / dy^2, as modal_stress_terms left it at the y of the last
  // body_applied_forces (the tangent's state).
  if (b.modal_stress) Kyy += bd.G1;
  if (b.prestress) Kyy += b.prestress->K1;
}

// The load-case stiffening -KG y depends on the frame's accelerations and spin (FORMULATION.md
// 7): a = A^T (r0_dd - g), alpha = Gbar(A) vec(A_dd), omega = Gbar(A) vec(A_d). Inside the
// implicit scheme the accelerations are c2 q + qdd_hat, so this dependence weighs as much as
// the mass matrix itself: left out of the tangent, a Craig-Bampton rod under its inertial
// stress (Simeon's slider-crank with a massless slider) made Newton stall. At frozen A and y,
//   Wb(y, r0) += sum_c (Kt[c] y) A_c^T,   Wb(y, A) += sum_c (Kr[c] y) Gbar_c
//   Wb(y, A) += kv sum_j (Kw[j] y) (d omega_bar_j / d omega)^T Gbar
//   Wb(y, y) += kv sum_j (Kw[j] y) (d omega_bar_j / d omega)^T I^-1 spin_h
// (Gbar_c its row c; omega the mean spin, see mean_spin). bd.Py column 0 is work (as in modal_stress_terms).
void body_stiffening_rate_tangents(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& y,
                                   const Eigen::Ref<const VectorXd>& yd, double kv, Eigen::Ref<MatrixXd> Wb) {
  if (!b.stiffening || b.nq == 0) return;
  const StiffeningTerms& s = *b.stiffening;
  const int nq = b.nq;
  auto v = bd.Py.col(0);
  const Eigen::Matrix<double, 3, 9> G = gbar(bd.A);
  for (int c = 0; c < 3; ++c) {
    v.noalias() = s.Kt[c] * y;
    Wb.block(12, 0, nq, 3).noalias() += v * bd.A.col(c).transpose();
    v.noalias() = s.Kr[c] * y;
    Wb.block(12, 3, nq, 9).noalias() += v * G.row(c);
  }
  Matrix3d Iinv;
  const Vector3d w = mean_spin(s, bd, yd, &Iinv);
  const Vector3d dw[6] = {{2 * w(0), 0, 0}, {0, 2 * w(1), 0}, {0, 0, 2 * w(2)},
                          {w(1), w(0), 0},  {0, w(2), w(1)}, {w(2), 0, w(0)}};
  for (int j = 0; j < 6; ++j) {
    v.noalias() = s.Kw[j] * y;
    v *= kv;
    // d omega / d vec(A_d) = Gbar (the frame's part; the mean spin's y- and A-dependence at
    // frozen rates is left out, as a's and alpha's), d omega / d y_dot = I^-1 spin_h.
    const Eigen::Matrix<double, 1, 9> r = dw[j].transpose() * G;
    Wb.block(12, 3, nq, 9).noalias() += v * r;
    const Eigen::Matrix<double, 1, 3> ry = dw[j].transpose() * Iinv;
    for (int k = 0; k < nq; ++k) Wb.col(12 + k).segment(12, nq) += ry.dot(s.spin_h.col(k)) * v;
  }
}

}  // namespace ffr::runtime
