// Body mass matrix M = int B^T B dm from the primitive integrals (FORMULATION.md section 3), plus the
// rotary coupling Gbar^T PsiI^T. Coordinates z = [r0, u, v, w, y].
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/kinematics.hpp"

#include "../integrator/dense_products.hpp"
#include "../integrator/tangent_blocks.hpp"
#include "../model/known_frame.hpp"

namespace ffr::runtime {
void body_mass_matrix(const Body& b, BodyData& bd) {
  MatrixXd& M = bd.M;
  // The rigid part: [[m, md^T], [md, Jc]] (x) I3.
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double s = (i == 0 && j == 0) ? b.mass : (i == 0) ? bd.md(j - 1) : (j == 0) ? bd.md(i - 1) : bd.Jc(i - 1, j - 1);
      M.block<3, 3>(3 * i, 3 * j) = s * Matrix3d::Identity();
    }
  if (b.nq == 0) return;
  const int nq = b.nq;
  auto Mry = M.block(0, 12, 3, nq);
  Mry.noalias() = bd.A * b.Pdm;
  for (int a = 0; a < 3; ++a) M.block(3 + 3 * a, 12, 3, nq).noalias() = bd.A * bd.S[a];
  if (b.has_rotary_coupling) M.block(3, 12, 9, nq).noalias() += gbar(bd.A).transpose() * b.PsiI.transpose();
  M.block(12, 0, nq, 12) = M.block(0, 12, 12, nq).transpose();
  // M_yy is constant: Data placed it once (a beam's is 102 x 102 at 16 elements, whose copy at
  // every evaluation was a tenth of its step).
}

void mass_matrices(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    // A rigid body's mass matrix is constant: it was filled when Data was built.
    const Body& b = model.bodies[i];
    if (b.nq == 0) continue;
    // An ancf beam's known frame is at rest (update_bodies): its rows and columns of M, which
    // read S_a and Jc, multiply zero rates and accelerations and are not among the unknowns'.
    // They stay as Data left them (zero); M_yy, the rest, is constant (placed by Data).
    if (detail::frame_known(model, b)) continue;
    if (b.full_mass)
      fe_mass_matrix(b, data.bodies[i], data.state.q.segment(b.offset, b.ncoord()));
    else
      body_mass_matrix(b, data.bodies[i]);
  }
}

void mass_times(const Model& model, const Data& data, const VectorXd& x, VectorXd& y) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!data.integrated[i]) continue;  // a driven body's rows are not unknowns
    const Body& b = model.bodies[i];
    const MatrixXd& M = data.bodies[i].M;  // through the step's vectorised kernel
    const Eigen::Index ld = M.rows();
    if (!data.banded[i]) {
      detail::times(M.data(), ld, b.ncoord(), b.ncoord(), x.data() + b.offset, y.data() + b.offset, false);
      continue;
    }
    // A banded beam's M is zero outside its blocks (tangent_blocks.hpp): the product costs in
    // proportion to its nodes, not to their square.
    y.segment(b.offset, b.ncoord()).setZero();
    detail::for_each_body_block(model, data, static_cast<int>(i), [&](int r0, int nr, int c0, int nc) {
      detail::times(M.data() + (c0 - b.offset) * ld + (r0 - b.offset), ld, nr, nc, x.data() + c0, y.data() + r0, true);
    });
  }
}

// The modal rows of M q_dd hold S_a(y)^T A^T A_dd_a, and S_a(y) = rPdm[a] + P_a(y) with row b of
// P_a(y) = y^T PPdm[a][b]: their derivative in y is sum_ab (A_b . A_dd_a) PPdm[a][b]^T, and
// PPdm[a][b]^T = PPdm[b][a]. Why only this block of d(M(q) q_dd)/dq: on the benchmark's
// slider-crank it is what kept Newton from converging quadratically once the tangent had been
// rebuilt (spectral radius of T^-1 (T_fd - T) 1.6e-4 with it missing, 3.5e-5 with it, the rest
// spread over the other blocks), at the cost of nine scaled nq x nq sums.
void add_modal_acceleration_tangent(const Model& model, Data& data, double scale, MatrixXd& T) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    // A beam's held frame has no acceleration (Om = 0: FORMULATION.md 15).
    if (b.nq == 0 || b.beam || !data.integrated[i]) continue;
    auto Tyy = T.block(b.offset + 12, b.offset + 12, b.nq, b.nq);
    if (b.full_mass) {
      fe_modal_acceleration_tangent(b, data.bodies[i], scale, Tyy);
      continue;
    }
    const BodyData& bd = data.bodies[i];
    const Matrix3d Om = bd.A.transpose() * bd.Add;  // Om(c, a) = A_c . A_dd_a, the weight of PPdm[c][a]
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) Tyy += (scale * Om(c, a)) * b.PPdm[c][a];
  }
}

}  // namespace ffr::runtime
