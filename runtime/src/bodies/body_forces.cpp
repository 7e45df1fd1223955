// Gravity, modal elasticity and damping, and geometric stiffening of one body.
#include "ffr/runtime/dynamics.hpp"

namespace ffr::runtime {
namespace {

// KG = sum_c a_c Kt[c] + alpha_c Kr[c] + sum_j omega_bar_j Kw[j] (formats/SPEC.md section 10), with
// a the frame acceleration minus gravity (the inertial load a body feels), alpha the angular
// acceleration and omega_bar = (wx^2, wy^2, wz^2, wx wy, wy wz, wx wz), all in the body frame.
void geometric_stiffness(const StiffeningTerms& s, const BodyData& bd, MatrixXd& KG) {
  const Vector3d& w = bd.omega;
  const double wbar[6] = {w(0) * w(0), w(1) * w(1), w(2) * w(2), w(0) * w(1), w(1) * w(2), w(0) * w(2)};
  KG.setZero();
  for (int c = 0; c < 3; ++c) KG += bd.acc(c) * s.Kt[c] + bd.alpha(c) * s.Kr[c];
  for (int j = 0; j < 6; ++j) KG += wbar[j] * s.Kw[j];
}

}  // namespace

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
}

void body_applied_tangents(const Body& b, const BodyData& bd, const Vector3d& g, Eigen::Ref<MatrixXd> Kb,
                           Eigen::Ref<MatrixXd> Cb) {
  if (b.nq == 0) return;
  const int nq = b.nq;
  for (int a = 0; a < 3; ++a) {
    Kb.block(3 + 3 * a, 12, 3, nq).noalias() -= g * b.Pdm.row(a);
    Kb.block(12, 3 + 3 * a, nq, 3).noalias() -= b.Pdm.row(a).transpose() * g.transpose();
  }
  Kb.block(12, 12, nq, nq) += b.Ke;
  Cb.block(12, 12, nq, nq) += b.De;
  // Stiffening: the y-dependence at the current (frozen) accelerations and spin.
  if (b.stiffening) Kb.block(12, 12, nq, nq) += bd.KG;
}

}  // namespace ffr::runtime
