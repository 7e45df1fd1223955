// The co-rotational way of the shape-integral paper's comparison (docs/references.md): the body's
// mass matrix, velocity-dependent inertia forces and their tangents from the FE mass matrix M_FE
// of all N nodes at every evaluation,
//   B_p = [I, xbar_p0 I, xbar_p1 I, xbar_p2 I, A Phi_p],  xbar_p = X_p + Phi_p y,
//   M = B^T M_FE B,   Q_v = -B^T M_FE w,   w_p = 2 A_dot Phi_p y_dot,
// i.e. products whose size is the mesh's. The same quantities as the shape-integral path
// (body_mass.cpp, body_inertia.cpp) by the other route, term for term, so the two give the same
// motion: M, Q_v, -dQ_v/dz_dot (C), -dQ_v/dz (K) and the modal block of d(M(q) q_dd)/dy. Used
// only when a body carries FullMass (benchmarks and their tests).
#include "ffr/runtime/dynamics.hpp"

namespace ffr::runtime {

void fe_mass_matrix(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& z) {
  const FullMass& F = *b.full_mass;
  const Eigen::Index N = F.X.size() / 3;
  const int nq = b.nq;
  const auto y = z.tail(nq);
  MatrixXd& B = bd.feB;
  for (Eigen::Index p = 0; p < N; ++p) {
    const Vector3d xbar = F.X.segment<3>(3 * p) + F.Phi.middleRows<3>(3 * p) * y;
    auto Bp = B.middleRows<3>(3 * p);
    Bp.leftCols<12>().setZero();
    Bp.block<3, 3>(0, 0).setIdentity();
    for (int a = 0; a < 3; ++a) Bp.block<3, 3>(0, 3 + 3 * a).diagonal().setConstant(xbar(a));
    Bp.rightCols(nq).noalias() = bd.A * F.Phi.middleRows<3>(3 * p);
  }
  bd.feG.noalias() = F.M * B;
  bd.M.noalias() = B.transpose() * bd.feG;
  // What else reads the deformed integrals (gravity's m c_G, the momentum outputs, the stiffening's
  // spin), from the same products: M's (r0, A_a) block is md_a I, its (A_a, A_c) block Jc(a,c) I,
  // its (A_a, y) block A S_a (update_bodies leaves them to this path for such a body).
  for (int a = 0; a < 3; ++a) {
    bd.md(a) = bd.M(0, 3 + 3 * a);
    for (int c = 0; c < 3; ++c) bd.Jc(a, c) = bd.M(3 + 3 * a, 3 + 3 * c);
    bd.S[a].noalias() = bd.A.transpose() * bd.M.block(3 + 3 * a, 12, 3, nq);
  }
}

void fe_inertia_forces(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<VectorXd> Qb) {
  const FullMass& F = *b.full_mass;
  const Eigen::Index N = F.X.size() / 3;
  const auto yd = zd.tail(b.nq);
  for (Eigen::Index p = 0; p < N; ++p) bd.few.segment<3>(3 * p).noalias() = 2.0 * bd.Ad * (F.Phi.middleRows<3>(3 * p) * yd);
  Qb.noalias() -= bd.feG.transpose() * bd.few;
}

void fe_inertia_tangents(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<MatrixXd> Kb,
                         Eigen::Ref<MatrixXd> Cb) {
  const FullMass& F = *b.full_mass;
  const Eigen::Index N = F.X.size() / 3;
  const int nq = b.nq;
  const auto yd = zd.tail(nq);
  // C = -dQ_v/dz_dot = B^T M_FE dw/dz_dot: w_p = 2 A_dot Phi_p y_dot is linear in the frame rates
  // (column block A_c: 2 (Phi_p y_dot)_c I) and in y_dot (2 A_dot Phi_p).
  MatrixXd& D = bd.feD;
  for (Eigen::Index p = 0; p < N; ++p) {
    auto Dp = D.middleRows<3>(3 * p);
    Dp.leftCols<12>().setZero();
    const Vector3d py = F.Phi.middleRows<3>(3 * p) * yd;
    bd.few.segment<3>(3 * p).noalias() = 2.0 * bd.Ad * py;
    for (int c = 0; c < 3; ++c) Dp.block<3, 3>(0, 3 + 3 * c).diagonal().setConstant(2.0 * py(c));
    Dp.rightCols(nq).noalias() = 2.0 * bd.Ad * F.Phi.middleRows<3>(3 * p);
  }
  Cb.noalias() += bd.feG.transpose() * D;
  // K = -dQ_v/dz = d(B^T)/dz g with g = M_FE w (w does not depend on z): B's (A_a) columns carry
  // xbar_pa = X_pa + Phi_pa y, its modal columns A Phi_p, so
  //   K(A_a, y) = sum_p g_p Phi_pa  (Phi_pa: row a of Phi_p),   K(y, A_a) = K(A_a, y)^T.
  // As products: g as a 3 x N matrix times the N x nq rows a of Phi (stride 3).
  bd.feg.noalias() = F.M * bd.few;
  const Eigen::Map<const Matrix3Xd> g(bd.feg.data(), 3, N);
  using RowsA = Eigen::Map<const MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, 3>>;
  for (int a = 0; a < 3; ++a) {
    const RowsA Phi_a(F.Phi.data() + a, N, nq, Eigen::Stride<Eigen::Dynamic, 3>(F.Phi.rows(), 3));
    Kb.block(3 + 3 * a, 12, 3, nq).noalias() += g * Phi_a;
    Kb.block(12, 3 + 3 * a, nq, 3).noalias() += Phi_a.transpose() * g.transpose();
  }
}

// The modal rows of M(q) q_dd are sum_p (A Phi_p)^T (M_FE B q_dd)_p, and B q_dd depends on y
// through xbar: d(B_p q_dd)/dy = sum_a A_dd_a Phi_pa = A_dd Phi_p. So the block is
// (A Phi)^T M_FE (A_dd Phi) = (M_FE B)_y^T (A_dd Phi), (M_FE B)_y the modal columns of feG.
void fe_modal_acceleration_tangent(const Body& b, BodyData& bd, double scale, Eigen::Ref<MatrixXd> Tyy) {
  const FullMass& F = *b.full_mass;
  const Eigen::Index N = F.X.size() / 3;
  const int nq = b.nq;
  auto P = bd.feD.rightCols(nq);  // work: the tangents are done with feD when this is built
  for (Eigen::Index p = 0; p < N; ++p) P.middleRows<3>(3 * p).noalias() = bd.Add * F.Phi.middleRows<3>(3 * p);
  Tyy.noalias() += scale * (bd.feG.rightCols(nq).transpose() * P);
}

}  // namespace ffr::runtime
