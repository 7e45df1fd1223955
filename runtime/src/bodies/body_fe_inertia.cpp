// The co-rotational way of the shape-integral paper's comparison (docs/references.md): the body's mass matrix and velocity-dependent
// inertia forces from the full FE mass matrix at every evaluation,
//   B_p = [I, xbar_p0 I, xbar_p1 I, xbar_p2 I, A Phi_p],  M = B^T M_FE B,
//   Q_v = -B^T M_FE w,  w_p = 2 A_dot Phi_p y_dot,
// i.e. products whose size is the mesh's. Used only when a body carries FullMass (benchmarks).
#include "ffr/runtime/dynamics.hpp"

namespace ffr::runtime {

void fe_mass_matrix(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& z) {
  const FullMass& F = *b.full_mass;
  const Eigen::Index N = F.X.size() / 3;
  const auto y = z.tail(b.nq);
  MatrixXd& B = bd.feB;
  for (Eigen::Index p = 0; p < N; ++p) {
    const Vector3d xbar = F.X.segment<3>(3 * p) + F.Phi.middleRows<3>(3 * p) * y;
    auto Bp = B.middleRows<3>(3 * p);
    Bp.leftCols<12>().setZero();
    Bp.block<3, 3>(0, 0).setIdentity();
    for (int a = 0; a < 3; ++a) Bp.block<3, 3>(0, 3 + 3 * a).diagonal().setConstant(xbar(a));
    Bp.rightCols(b.nq).noalias() = bd.A * F.Phi.middleRows<3>(3 * p);
  }
  bd.feG.noalias() = F.M * B;
  bd.M.noalias() = B.transpose() * bd.feG;
}

void fe_inertia_forces(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<VectorXd> Qb) {
  const FullMass& F = *b.full_mass;
  const Eigen::Index N = F.X.size() / 3;
  const auto yd = zd.tail(b.nq);
  for (Eigen::Index p = 0; p < N; ++p) bd.few.segment<3>(3 * p).noalias() = 2.0 * bd.Ad * (F.Phi.middleRows<3>(3 * p) * yd);
  Qb.noalias() -= bd.feG.transpose() * bd.few;
}

void fe_inertia_tangents(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<MatrixXd> Cb) {
  const FullMass& F = *b.full_mass;
  const Eigen::Index N = F.X.size() / 3;
  const auto yd = zd.tail(b.nq);
  MatrixXd& D = bd.feD;  // dw/dz_dot
  for (Eigen::Index p = 0; p < N; ++p) {
    auto Dp = D.middleRows<3>(3 * p);
    Dp.leftCols<12>().setZero();
    const Vector3d py = F.Phi.middleRows<3>(3 * p) * yd;
    for (int c = 0; c < 3; ++c) Dp.block<3, 3>(0, 3 + 3 * c).diagonal().setConstant(2.0 * py(c));
    Dp.rightCols(b.nq).noalias() = 2.0 * bd.Ad * F.Phi.middleRows<3>(3 * p);
  }
  Cb.noalias() += bd.feG.transpose() * D;
}

}  // namespace ffr::runtime
