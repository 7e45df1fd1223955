// Gravity, modal elasticity and damping, and geometric stiffening of one body.
#include "ffr/runtime/dynamics.hpp"

#include "../integrator/dense_products.hpp"

namespace ffr::runtime {
namespace {

// KG = sum_c a_c Kt[c] + alpha_c Kr[c] + sum_j omega_bar_j Kw[j] + sum over interfaces of
// F_c KF[c] + M_c KM[c] (FORMULATION.md 7), with a the frame acceleration minus gravity (the
// inertial load a body feels), alpha the angular acceleration, omega_bar = (wx^2, wy^2, wz^2,
// wx wy, wy wz, wx wz), and F, M the loads of the joints at each interface node (bd.iface_load,
// set by interface_loads), all in the body frame.
void geometric_stiffness(const StiffeningTerms& s, const BodyData& bd, MatrixXd& KG) {
  const Vector3d& w = bd.omega;
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

void modal_stress_terms(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& y) {
  const ModalStressStiffness& m = *b.modal_stress;
  const Eigen::Index nq = b.nq;
  // X1 column k = M1[k] y (by_mode y, read column-major); G1 = sum_k y_k M1[k] (by_coeff y).
  detail::times(m.by_mode.data(), nq * nq, nq * nq, nq, y.data(), bd.X1.data(), false);
  detail::times(m.by_coeff.data(), nq * nq, nq * nq, nq, y.data(), bd.G1.data(), false);
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
  Qy.noalias() -= b.Ke * y;
  Qy.noalias() -= b.De * yd;
  if (b.stiffening) {
    geometric_stiffness(*b.stiffening, bd, bd.KG);
    Qy.noalias() -= bd.KG * y;
  }
  // The cubic strain energy's force: -dU3/dy_m = -(G1 y)_m - 1/2 y^T M1[m] y, the second term
  // being (X1^T y)_m.
  if (b.modal_stress) {
    modal_stress_terms(b, bd, y);
    Qy.noalias() -= bd.G1 * y;
    Qy.noalias() -= 0.5 * (bd.X1.transpose() * y);
  }
  if (b.prestress) {
    Qy -= b.prestress->f0;
    Qy.noalias() -= b.prestress->K1 * y;
  }
}

void body_applied_tangents(const Body& b, const BodyData& bd, const Vector3d& g, Eigen::Ref<MatrixXd> Kb,
                           Eigen::Ref<MatrixXd> Cb) {
  if (b.nq == 0) return;
  const int nq = b.nq;
  for (int a = 0; a < 3; ++a) {
    Kb.block(3 + 3 * a, 12, 3, nq).noalias() -= g * b.Pdm.row(a);
    Kb.block(12, 3 + 3 * a, nq, 3).noalias() -= b.Pdm.row(a).transpose() * g.transpose();
  }
  auto Kyy = Kb.block(12, 12, nq, nq);
  Kyy += b.Ke;
  Cb.block(12, 12, nq, nq) += b.De;
  // Stiffening: the y-dependence at the current (frozen) accelerations, spin and joint loads.
  if (b.stiffening) Kyy += bd.KG;
  // d^2 U3 / dy_m dy_n = G1_mn + (M1[m] y)_n + (M1[n] y)_m = G1 + X1^T + X1 (at the y of the
  // last body_applied_forces, which is the tangent's state).
  if (b.modal_stress) {
    Kyy += bd.G1;
    Kyy += bd.X1;
    Kyy += bd.X1.transpose();
  }
  if (b.prestress) Kyy += b.prestress->K1;
}

}  // namespace ffr::runtime
