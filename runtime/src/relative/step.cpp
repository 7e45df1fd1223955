// One ALI3-P step in the relative coordinates (relative.hpp, FORMULATION.md 18): the absolute
// step's scheme (the trapezoidal rule or generalized-alpha, scheme_coefficients.cpp),
// augmented-Lagrangian Newton iteration and projections (ali3p.cpp, FORMULATION.md 9) with the
// absolute residual and tangent projected by R = dq/ds (h^2/4 below is the scheme's kq):
//   f(s) = h^2/4 R^T [M q_ddot - Q + Phi_q^T (lambda + alpha Phi)]            (kept rows)
//   T    = R^T (M + h/2 C + h^2/4 K) R + h^2/4 (Phi_q R)^T alpha (Phi_q R)
//          + R^T (h M + h^2/4 C) R_dot + h^2/4 [R^T M Ra + sum_k (dR/ds_k)^T F]
// the last line R's derivatives (R_dot = dR/dt, Ra = dq_ddot/ds at fixed rates, F the absolute
// residual force M q_ddot - Q + Phi_q^T lambda; FORMULATION.md 18), so that Newton contracts
// quadratically. The projections weigh by the tangent without them (a metric: symmetric up to
// the force elements' terms).
#include "ffr/runtime/relative.hpp"

#include "ffr/runtime/beam.hpp"
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "ffr/runtime/scheme.hpp"
#include "ffr/runtime/state.hpp"
#include "../forces/forces.hpp"
#include "solves.hpp"
#include "../number_text.hpp"
#include "../integrator/newton_remedies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ffr::runtime {

using namespace relative_detail;

namespace {

double scaled(const RelativeWork& w, const VectorXd& ds) {
  return ds.size() == 0 ? 0.0 : ds.cwiseAbs().cwiseProduct(w.weight).maxCoeff();
}

// The kept rows' violation, in model lengths.
double violation(const Model& model, const Data& data) {
  const RelativeWork& w = *data.relative;
  return w.keep.size() == 0 ? 0.0 : data.Phi.cwiseProduct(w.keep).cwiseAbs().maxCoeff() / model.length;
}

// Phi_q R on the kept rows (the others stay zero), block by block over the columns of the
// block's bodies and their ranges of relative coordinates. The products are small (a few rows,
// a body's coordinates): coefficient-based (lazyProduct), where Eigen's blocked product spent
// most of the step packing its operands.
void projected_jacobian(const Model& model, Data& data) {
  const RelativeTree& tree = *model.relative;
  RelativeWork& w = *data.relative;
  for (std::size_t kb = 0; kb < tree.kept_blocks.size(); ++kb) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(tree.kept_blocks[kb])];
    w.Phis.middleRows(b.row0, b.rows).setZero();
    for (int x : {b.body1, b.body2, b.body3, b.body4}) {
      // (The block's bodies are distinct but for a joint's two on one body; a coupler's are
      // distinct, model.cpp.)
      if (x == kGround || (x == b.body2 && b.body2 == b.body1)) continue;
      const RelativeBody& rb = tree.bodies[static_cast<std::size_t>(x)];
      const Body& body = model.bodies[static_cast<std::size_t>(x)];
      if (rb.free)  // its block of R is the identity
        w.Phis.block(b.row0, rb.col0, b.rows, rb.ncols) += data.Phiq.block(b.row0, body.offset, b.rows, body.ncoord());
      else
        w.Phis.block(b.row0, rb.col0, b.rows, rb.ncols).noalias() +=
            data.Phiq.block(b.row0, body.offset, b.rows, body.ncoord()).lazyProduct(w.R.block(body.offset, rb.col0, body.ncoord(), rb.ncols));
    }
    // A joint placed at its point: its point rows vanish along R up to rounding; exactly zero here.
    if (b.kind == BlockKind::Joint && tree.tree_joint[static_cast<std::size_t>(b.index)] == 2 && b.first == 0) w.Phis.middleRows(b.row0, 3).setZero();
    // Where its rows are nonzero, for the products with Phis (solves.cpp, refresh).
    const auto rows = w.Phis.middleRows(b.row0, b.rows);
    int lo = 0, hi = tree.ns;
    while (lo < hi && rows.col(lo).isZero(0.0)) ++lo;
    while (hi > lo && rows.col(hi - 1).isZero(0.0)) --hi;
    w.span_lo[kb] = lo;
    w.span_hi[kb] = hi;
  }
}

// T = R^T W R + kq Phis^T alpha Phis with W = M + kv C + kq K, by body blocks and the blocks
// of the force elements' and the kept rows' pairs, and R's derivatives (the header); factorised
// after the diagonal scaling of factorize_tangent.
void refresh(const Model& model, Data& data, double t) {
  const RelativeTree& tree = *model.relative;
  RelativeWork& w = *data.relative;
  const StepCoefficients& k = data.state.k;
  force_tangents(model, data, t);
  w.Ts.setZero();
  // Ts += R_i^T X Y_j over the bodies' column ranges (X a block of W, Y = R or its rates) in two
  // products: WR = X Y_j (times), then R_i^T WR (project_rows), so that terms with the same R_i
  // share the second. A placed body's rows of R past its `top` (RelativeBody::own0) are zero
  // outside its own columns: those rows take part over its own columns only. (In a chain of
  // bodies placed at points the ancestors' columns, ever more down the chain, then meet 3 rows
  // instead of all 12 + nq.) (Coefficient-based products: see projected_jacobian. A free body's
  // block of R is the identity: no product on its side.)
  // WR (+)= X Y_j, X = Wb's top-left ni x nj (ni rows of WR), over body j's column range.
  const auto times = [&](int ni, int j, const MatrixXd& Y, bool accumulate) {
    const RelativeBody& rj = tree.bodies[static_cast<std::size_t>(j)];
    const Body& bj = model.bodies[static_cast<std::size_t>(j)];
    const int nj = bj.ncoord();
    const auto X = w.Wb.topLeftCorner(ni, nj);
    auto WR = w.WR.topLeftCorner(ni, rj.ncols);
    if (rj.free) {  // (only with Y = R: a free body's R_dot is zero)
      if (accumulate) WR += X;
      else WR = X;
      return;
    }
    const int t = std::min(rj.top, nj), no = rj.col0 + rj.ncols - rj.own0;
    if (accumulate) WR.noalias() += X.leftCols(t).lazyProduct(Y.block(bj.offset, rj.col0, t, rj.ncols));
    else WR.noalias() = X.leftCols(t).lazyProduct(Y.block(bj.offset, rj.col0, t, rj.ncols));
    if (nj > t && no > 0) WR.rightCols(no).noalias() += X.rightCols(nj - t).lazyProduct(Y.block(bj.offset + t, rj.own0, nj - t, no));
  };
  // Ts(i's columns, j's columns) += R_i^T WR.
  const auto project_rows = [&](int i, int j) {
    const RelativeBody& ri = tree.bodies[static_cast<std::size_t>(i)];
    const RelativeBody& rj = tree.bodies[static_cast<std::size_t>(j)];
    const Body& bi = model.bodies[static_cast<std::size_t>(i)];
    const int ni = bi.ncoord();
    const auto WR = w.WR.topLeftCorner(ni, rj.ncols);
    auto Ts = w.Ts.block(ri.col0, rj.col0, ri.ncols, rj.ncols);
    if (ri.free) {
      Ts += WR;
      return;
    }
    const int t = std::min(ri.top, ni), no = ri.col0 + ri.ncols - ri.own0;
    Ts.noalias() += w.R.block(bi.offset, ri.col0, t, ri.ncols).transpose().lazyProduct(WR.topRows(t));
    if (ni > t && no > 0)
      Ts.bottomRows(no).noalias() += w.R.block(bi.offset + t, ri.own0, ni - t, no).transpose().lazyProduct(WR.bottomRows(ni - t));
  };
  const auto add = [&](int i, int j) {
    times(model.bodies[static_cast<std::size_t>(i)].ncoord(), j, w.R, false);
    project_rows(i, j);
  };
  // The absolute tangent's iterate-dependent terms (FORMULATION.md 9), projected: the kept rows'
  // second derivatives with the multipliers (without them the free bodies' frame rows, whose
  // Hessian is the multiplier times the identity, made Newton diverge on the benchmark's crank
  // at 150 rad/s and h = 1 ms) and the modal masses' derivative at the iterate's accelerations.
  // Into the n x n work data.T, then by the blocks where they can be nonzero: a body's own block
  // with its block of W (one product), the pairs' below.
  if (!tree.hessian_pairs.empty()) {
    for (const auto& [i, j] : tree.hessian_pairs) {
      const Body& bi = model.bodies[static_cast<std::size_t>(i)];
      const Body& bj = model.bodies[static_cast<std::size_t>(j)];
      data.T.block(bi.offset, bj.offset, bi.ncoord(), bj.ncoord()).setZero();
      data.T.block(bj.offset, bi.offset, bj.ncoord(), bi.ncoord()).setZero();
    }
    if (tree.kept_rows > 0) add_constraint_hessian(model, data, data.state.lambda, k.kq, data.T);
    if (tree.flexible) add_modal_acceleration_tangent(model, data, k.kq, data.T);
  }
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    const int o = b.offset, nb = b.ncoord();
    auto Wb = w.Wb.topLeftCorner(nb, nb);
    Wb = data.bodies[i].M + k.kv * data.C.block(o, o, nb, nb) + k.kq * data.K.block(o, o, nb, nb);
    body_stiffening_rate_tangents(b, data.bodies[i], data.state.q.segment(o + 12, b.nq), data.state.qd.segment(o + 12, b.nq), k.kv, Wb);
    if (tree.hessian_self[i]) Wb += data.T.block(o, o, nb, nb);
    add(static_cast<int>(i), static_cast<int>(i));
  }
  for (const auto& [i, j] : tree.pairs) {
    const Body& bi = model.bodies[static_cast<std::size_t>(i)];
    const Body& bj = model.bodies[static_cast<std::size_t>(j)];
    const int oi = bi.offset, ni = bi.ncoord(), oj = bj.offset, nj = bj.ncoord();
    w.Wb.topLeftCorner(ni, nj) = k.kv * data.C.block(oi, oj, ni, nj) + k.kq * data.K.block(oi, oj, ni, nj);
    add(i, j);
    w.Wb.topLeftCorner(nj, ni) = k.kv * data.C.block(oj, oi, nj, ni) + k.kq * data.K.block(oj, oi, nj, ni);
    add(j, i);
  }
  for (const auto& [i, j] : tree.hessian_pairs) {
    if (i == j) continue;
    const Body& bi = model.bodies[static_cast<std::size_t>(i)];
    const Body& bj = model.bodies[static_cast<std::size_t>(j)];
    w.Wb.topLeftCorner(bi.ncoord(), bj.ncoord()) = data.T.block(bi.offset, bj.offset, bi.ncoord(), bj.ncoord());
    add(i, j);
    w.Wb.topLeftCorner(bj.ncoord(), bi.ncoord()) = data.T.block(bj.offset, bi.offset, bj.ncoord(), bi.ncoord());
    add(j, i);
  }
  // (Phis is the current iterate's: step() computed it; zero off the kept rows.) Block by kept
  // block over the columns where its rows are nonzero (projected_jacobian): a body's frame rows
  // see its own frame only, a joint's rotation rows the two bodies' frames and modes.
  for (std::size_t kb = 0; kb < tree.kept_blocks.size(); ++kb) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(tree.kept_blocks[kb])];
    const auto rows = w.Phis.middleRows(b.row0, b.rows);
    const int lo = w.span_lo[kb], hi = w.span_hi[kb];
    if (lo == hi) continue;
    auto PA = w.PA.block(b.row0, lo, b.rows, hi - lo);
    PA.noalias() = data.alpha.segment(b.row0, b.rows).asDiagonal() * rows.middleCols(lo, hi - lo);
    PA *= k.kq;
    w.Ts.block(lo, lo, hi - lo, hi - lo).noalias() += rows.middleCols(lo, hi - lo).transpose().lazyProduct(PA);
  }
  if (w.exact_tangent) {
    // What the projections weigh by (project): the tangent so far, R^T W R and the constraints'
    // terms, symmetric up to the force elements' own; the terms below are Newton's only (they
    // are not symmetric and scale with the rates: the gyroscopic one with h Omega).
    w.Tm = w.Ts;
    w.metric_stale = true;
    // The rates' dependence on s through R: q_dot = R s_dot and q_ddot = R s_ddot + R_dot s_dot
    // with R_dot linear in s_dot, so kq dq_ddot/ds = R + 2 kv R_dot + kq Ra and kq dq_dot/ds =
    // kv R + kq R_dot: the gyroscopic coupling R^T (2 kv M + kq C) R_dot and the curvature in the
    // accelerations kq R^T M Ra (M is block diagonal; C couples the force elements' pairs).
    // (M's terms in one product: M (2 kv R_dot + kq Ra); C's, where C is not zero, with R_dot.)
    for (std::size_t i = 0; i < model.bodies.size(); ++i) {
      const RelativeBody& rb = tree.bodies[i];
      if (rb.free) continue;
      const Body& b = model.bodies[i];
      const int o = b.offset, nb = b.ncoord(), bi = static_cast<int>(i);
      w.Z.block(o, rb.col0, nb, rb.ncols) = (2 * k.kv) * w.Rd.block(o, rb.col0, nb, rb.ncols) + k.kq * w.Ra.block(o, rb.col0, nb, rb.ncols);
      auto Wb = w.Wb.topLeftCorner(nb, nb);
      Wb = data.bodies[i].M;
      times(nb, bi, w.Z, false);
      if (!data.C.block(o, o, nb, nb).isZero(0.0)) {
        Wb = k.kq * data.C.block(o, o, nb, nb);
        times(nb, bi, w.Rd, true);
      }
      project_rows(bi, bi);
    }
    for (const auto& [i, j] : tree.pairs) {
      const Body& bi = model.bodies[static_cast<std::size_t>(i)];
      const Body& bj = model.bodies[static_cast<std::size_t>(j)];
      const int oi = bi.offset, ni = bi.ncoord(), oj = bj.offset, nj = bj.ncoord();
      if (!data.C.block(oi, oj, ni, nj).isZero(0.0) && !tree.bodies[static_cast<std::size_t>(j)].free) {
        w.Wb.topLeftCorner(ni, nj) = k.kq * data.C.block(oi, oj, ni, nj);
        times(ni, j, w.Rd, false);
        project_rows(i, j);
      }
      if (!data.C.block(oj, oi, nj, ni).isZero(0.0) && !tree.bodies[static_cast<std::size_t>(i)].free) {
        w.Wb.topLeftCorner(nj, ni) = k.kq * data.C.block(oj, oi, nj, ni);
        times(nj, i, w.Rd, false);
        project_rows(j, i);
      }
    }
    // The curvature of q(s) weighted by the absolute residual force F = M q_ddot - Q + Phi_q^T
    // lambda (w.g holds the first two, assemble_residual): kq sum_k (dR/ds_k)^T F. The
    // multipliers without the iterate's penalty forces alpha Phi, as the constraint Hessian above
    // (FORMULATION.md 9): with them, far from the solution (the predictor), Newton on the
    // benchmark's flexible slider-crank took 6 to 8 iterations instead of 3 or 4 and stopped
    // converging at 0.031 s.
    w.force = w.g;
    for (int bi : tree.kept_blocks) {
      const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
      for (int x : {b.body1, b.body2, b.body3, b.body4}) {
        if (x == kGround || (x == b.body2 && b.body2 == b.body1)) continue;
        const Body& body = model.bodies[static_cast<std::size_t>(x)];
        w.force.segment(body.offset, body.ncoord()).noalias() +=
            data.Phiq.block(b.row0, body.offset, b.rows, body.ncoord()).transpose() * data.state.lambda.segment(b.row0, b.rows);
      }
    }
    relative_curvature(model, data, k.kq, w.Ts);
  }
  const auto d = w.Ts.diagonal().array().abs();
  w.scale = (d > 0).select(d.sqrt().inverse(), 1.0);
  w.lu.compute(w.scale.asDiagonal() * w.Ts * w.scale.asDiagonal());
  ++data.stats.factorizations;
}

// Generalized-alpha in s, as the absolute step has it in q (scheme_coefficients.cpp): with the
// pseudo-acceleration a of s, s_dot = c1 s + sd_hat and s_ddot = c2 s + sdd_hat.
StepCoefficients alpha_coefficients(const AlphaParameters& p, double h) {
  StepCoefficients k;
  k.h = k.h_prev = h;
  k.c1 = p.gamma / (p.beta * h);
  k.c2 = (1 - p.alpha_m) / ((1 - p.alpha_f) * p.beta * h * h);
  k.kv = k.c1 / k.c2;
  k.kq = 1 / k.c2;
  return k;
}

// The start of generalized-alpha (start_generalized_alpha of the absolute step): a_0 stands for
// the acceleration at t_0 + (alpha_m - alpha_f) h, taken from one trapezoidal step that is then
// undone, a_0 = s_ddot_0 + (alpha_m - alpha_f) (s_ddot_1 - s_ddot_0).
void start_alpha(const Model& model, Data& data, double h) {
  RelativeWork& w = *data.relative;
  const AlphaParameters p = AlphaParameters::from_spectral_radius(model.settings.spectral_radius);
  const double delta = p.alpha_m - p.alpha_f;
  w.a = w.sdd;
  if (delta == 0) return;  // rho_inf = 1: a_n = s_ddot_n, the trapezoidal rule
  save_state(data, data.start);
  w.start_s = w.s;
  w.start_sd = w.sd;
  w.start_sdd = w.sdd;
  const auto undo = [&] {
    data.scheme.start_step = false;
    restore_state(data.start, data);
    w.s = w.start_s;
    w.sd = w.start_sd;
    w.sdd = w.start_sdd;
    w.have_previous = false;
    // The absolute state is the one these s describe again: no new sync at the next step.
    w.q_last = data.state.q;
    w.qd_last = data.state.qd;
    w.t_last = data.state.t;
  };
  data.scheme.start_step = true;
  try {
    relative_step(model, data, h);
  } catch (...) {
    undo();
    throw;
  }
  w.a = w.start_sdd + delta * (w.sdd - w.start_sdd);
  undo();
  --data.stats.steps;  // not a step of the run
}

// The iterate's rates and accelerations (affine in s through the scheme), its absolute state and
// the model's evaluation there; with `tangent`, also what only a tangent rebuilt at this iterate
// reads (R's rate and curvature, with the exact tangent).
void evaluate_at_s(const Model& model, Data& data, double t1, bool tangent) {
  RelativeWork& w = *data.relative;
  const StepCoefficients& k = data.state.k;
  w.sd = k.c1 * w.s + w.sd_hat;
  w.sdd = k.c2 * w.s + w.sdd_hat;
  relative_kinematics(model, data, true, tangent && w.exact_tangent);
  evaluate(model, data, t1);
}

// w.f = kq R^T [M q_ddot - Q + Phi_q^T (lambda + alpha Phi)] at the evaluated iterate.
void assemble_residual(const Model& model, Data& data) {
  RelativeWork& w = *data.relative;
  State& st = data.state;
  data.lambda_eff = st.lambda + data.alpha.cwiseProduct(data.Phi);
  // (The constraint forces through Phi_q R on the kept rows: the dropped rows' multipliers
  // are zero, and the product over all of the dense Phi_q cost as much as the rest.)
  if (model.relative->kept_rows > 0) projected_jacobian(model, data);
  mass_times(model, data, st.qdd, w.g);
  w.g -= data.Q;
  // R^T g by bodies over R's pattern (RelativeBody::own0), not over all of the n x ns R.
  w.f.setZero();
  for (int bi : model.relative->order) {
    const RelativeBody& rb = model.relative->bodies[static_cast<std::size_t>(bi)];
    const Body& b = model.bodies[static_cast<std::size_t>(bi)];
    const int o = b.offset, nb = b.ncoord();
    if (rb.free) {
      w.f.segment(rb.col0, nb) += w.g.segment(o, nb);
      continue;
    }
    const int t = std::min(rb.top, nb), no = rb.col0 + rb.ncols - rb.own0;
    w.f.segment(rb.col0, rb.ncols).noalias() += w.R.block(o, rb.col0, t, rb.ncols).transpose() * w.g.segment(o, t);
    if (nb > t && no > 0) w.f.segment(rb.own0, no).noalias() += w.R.block(o + t, rb.own0, nb - t, no).transpose() * w.g.segment(o + t, nb - t);
  }
  add_phis_t(model, w, data.lambda_eff, 1.0, w.f);
  w.f *= st.k.kq;
}

// The Newton direction with the kept rows' multipliers solved for at once (the absolute step's
// newton_direction, exact), for iterations that contract slowly once the tangent refreshes are
// spent. The passes shrink the linearised violation by 1 / (1 + kq alpha s) along an eigenvector
// of S = Phis Ts^-1 Phis^T of eigenvalue s: slowly where kept rows are nearly redundant (the case
// of projection.cpp, here in Newton: with 30 modes of the slider-crank's consistent rod the
// increments shrank by 0.99 an iteration and stood at 4e-11 against the tolerance 1e-10 after
// 30 iterations). ds = ds0 + Y mu with Y = Ts^-1 Phis^T and S mu = Phi - Phis ds0 meets the
// kept rows; S (symmetrised: Ts is not symmetric where R's derivatives enter it) by the pivoted
// Cholesky of exact_multipliers.cpp, rows redundant up to round-off keeping a zero multiplier,
// and the solve refined with its residual. On entry w.ds = Ts^-1 w.f; on return too, w.f with
// Phis^T mu added and w.sigma with mu / kq, so that the passes can go on from there (on what
// rows dropped as redundant leave).
void exact_direction(const Model& model, Data& data) {
  RelativeWork& w = *data.relative;
  const int k = static_cast<int>(w.kept.size());
  constexpr int refinements = 3;
  const int rank = factor_kept_multipliers(w, data, false, true);
  const auto S = w.projS.topLeftCorner(k, k);
  const double kq = data.state.k.kq;
  for (int round = 0; round <= refinements; ++round) {
    phis_times(model, w, w.ds, w.c);
    w.c = (data.Phi - w.c).cwiseProduct(w.keep);
    const double left = w.c.size() > 0 ? w.c.cwiseAbs().maxCoeff() / model.length : 0.0;
    // The first solve whatever the violation left: along nearly redundant rows a violation below
    // the tolerance still moves s by more than Newton's (on the 1002-DOF rod with 30 modes,
    // 1e-12 model lengths left moved s by 1e-11 an iteration, shrinking by 0.955).
    if ((round > 0 && left < model.settings.tolerance) || !std::isfinite(left)) break;
    for (int i = 0; i < k; ++i) w.proj_c(i) = w.c(w.kept[static_cast<std::size_t>(i)]);
    pivoted_cholesky_solve(S, w.proj_order, rank, w.proj_c, w.proj_w, w.proj_mu);
    w.ds.noalias() += w.projY.leftCols(k) * w.proj_mu.head(k);
    w.r.setZero();
    for (int i = 0; i < k; ++i) w.r(w.kept[static_cast<std::size_t>(i)]) = w.proj_mu(i);
    add_phis_t(model, w, w.r, 1.0, w.f);
    w.sigma += w.r / kq;
  }
}

}  // namespace

void relative_residual(const Model& model, Data& data, double t) {
  evaluate_at_s(model, data, t, true);
  assemble_residual(model, data);
}

void relative_tangent(const Model& model, Data& data, double t) { refresh(model, data, t); }

void relative_begin_step(const Model& model, Data& data, double h) {
  const SolverSettings& s = model.settings;
  RelativeWork& w = *data.relative;
  State& st = data.state;
  // A state this formulation did not produce (initialize, restore_state): take s from it.
  if (!(st.t == w.t_last) || st.q != w.q_last || st.qd != w.qd_last) relative_sync(model, data);
  // (The start step of generalized-alpha is a trapezoidal one.)
  const bool alpha = s.integrator == Integrator::GeneralizedAlpha && !data.scheme.start_step;
  if (alpha && !w.have_previous) start_alpha(model, data, h);
  const AlphaParameters ap = AlphaParameters::from_spectral_radius(alpha ? s.spectral_radius : 1.0);
  st.k = alpha ? alpha_coefficients(ap, h) : trapezoidal_coefficients(h);
  const StepCoefficients& k = st.k;
  const double h2 = h * h;
  w.s0 = w.s;
  w.sd0 = w.sd;
  w.sdd0 = w.sdd;
  if (alpha) {
    // A new step size: a's lead over s_ddot is rescaled with h (set_step_coefficients).
    if (w.have_previous && h != w.h_prev && w.h_prev > 0) w.a = w.sdd0 + (h / w.h_prev) * (w.a - w.sdd0);
    // w.f: a_{n+1} - s_{n+1} / (beta h^2) (set_step_predictors' base; w.f is free until the loop).
    const double bh2 = ap.beta * h2;
    w.f = (-1.0 / bh2) * w.s0 - (h / bh2) * w.sd0 - ((0.5 - ap.beta) / ap.beta) * w.a;
    w.sd_hat = w.sd0 + (h * (1 - ap.gamma)) * w.a + (h * ap.gamma) * w.f;
    w.sdd_hat = ((1 - ap.alpha_m) / (1 - ap.alpha_f)) * w.f + (ap.alpha_m / (1 - ap.alpha_f)) * w.a -
                (ap.alpha_f / (1 - ap.alpha_f)) * w.sdd0;
  } else {
    w.sd_hat = -(k.c1 * w.s0 + w.sd0);
    w.sdd_hat = -(k.c2 * w.s0 + (4.0 / h) * w.sd0 + w.sdd0);
  }
  // The absolute step's predictor (ali3p.cpp), in s.
  if (w.have_previous) {
    const double r = h / w.h_prev;
    w.s.noalias() += h * w.sd0 + (0.25 * (2 + r) * h2) * w.sdd0 - (0.25 * r * h2) * w.sdd_prev;
  } else {
    w.s.noalias() += h * w.sd0 + (0.5 * h2) * w.sdd0;
  }
  w.sdd_prev = w.sdd0;
  penalty_weights(model, data, data.W, s.penalty * k.c2, data.alpha);
  data.alpha.array() *= w.keep.array();
  st.lambda.array() *= w.keep.array();
}

void relative_step(const Model& model, Data& data, double h) {
  const SolverSettings& s = model.settings;
  const NewtonPolicy& p = s.policy.newton;
  RelativeWork& w = *data.relative;
  State& st = data.state;
  relative_begin_step(model, data, h);
  const bool alpha = s.integrator == Integrator::GeneralizedAlpha && !data.scheme.start_step;
  const AlphaParameters ap = AlphaParameters::from_spectral_radius(alpha ? s.spectral_radius : 1.0);
  const StepCoefficients& k = st.k;
  const double h2 = h * h, t1 = st.t + h;
  double inc = 0, prev_inc = 0, viol = 0, left = 0;
  bool refresh_now = true, converged = false;
  bool exact = false;            // exact multipliers in the direction (exact_direction)
  bool exact_since_now = false;  // switched at this iteration: no rate from the last increment
  int refreshes = 0, it = 0;
  for (it = 1; it <= s.max_iterations; ++it) {
    evaluate_at_s(model, data, t1, refresh_now);
    viol = violation(model, data);
    if (!std::isfinite(viol) || !st.q.allFinite())
      throw SolverError(t1, viol, "Newton did not converge at t = " + fmt(t1) + " s (relative formulation): the state is not finite. " + ge_beam_failure_hint(model, w.q_last, data.state.q) + "Try a smaller step (solver.step = " + fmt(0.5 * h) + ")");
    if (it > 1) st.lambda += data.alpha.cwiseProduct(data.Phi);
    assemble_residual(model, data);
    const bool refreshed = refresh_now;
    if (refresh_now) {
      // What the first tangent alone may take: Data::first_tangent_of_step.
      data.first_tangent_of_step = refreshes == 0;
      refresh(model, data, t1);
      data.first_tangent_of_step = false;
      refresh_now = false;
      ++refreshes;
    }
    // Newton direction with augmented-Lagrangian passes on the linearised kept rows, or with
    // the kept rows' multipliers solved for at once.
    solve(w, data, w.f, w.ds);
    w.sigma.setZero();
    const int passes = it == 1 ? 1 : p.multiplier_passes;
    if (exact) exact_direction(model, data);
    for (int pass = 0;; ++pass) {
      phis_times(model, w, w.ds, w.c);
      w.c = (data.Phi - w.c).cwiseProduct(w.keep);
      left = w.c.size() > 0 ? w.c.cwiseAbs().maxCoeff() / model.length : 0.0;
      if (pass == passes || left < s.tolerance) break;
      w.r = data.alpha.cwiseProduct(w.c);
      w.sigma += w.r;
      add_phis_t(model, w, w.r, k.kq, w.f);
      solve(w, data, w.f, w.ds);
    }
    st.lambda += w.sigma;
    w.s -= w.ds;
    prev_inc = inc;
    inc = scaled(w, w.ds);
    if (!std::isfinite(inc))
      throw SolverError(t1, inc, "Newton did not converge at t = " + fmt(t1) + " s (relative formulation): the tangent is singular. " + ge_beam_failure_hint(model, w.q_last, data.state.q) + "Check the joints' axes and the bodies' masses");
    const double theta = it >= 2 && prev_inc > 0 && !refreshed && !exact_since_now ? inc / prev_inc : 1.0;
    exact_since_now = false;
    const double error_left = it == 1 ? inc : (theta < 1 ? inc * theta / (1 - theta) : std::numeric_limits<double>::infinity());
    if ((error_left < s.newton_tolerance || inc < 0.1 * s.newton_tolerance) && left < s.tolerance &&
        viol < p.violation_factor * s.tolerance) {
      converged = true;
      break;
    }
    // The predictor's tangent far from this iterate (its penalty term built with the predictor's
    // Phi_q, the absolute step's predictor_far, FORMULATION.md 9): rebuilt here. On the
    // benchmark's crank (150 rad/s, h = 1 ms) iterations 2 and 3 otherwise did not contract.
    if (it == 1 && s.penalty * inc > p.predictor_tangent) refresh_now = true;
    if (it >= 2 && inc > p.slow_contraction * prev_inc && refreshes < p.max_refreshes) refresh_now = true;
    // Slow with the refreshes spent: the multipliers are solved for exactly from now on.
    else if (it >= 2 && inc > p.slow_contraction * prev_inc && !exact) exact = exact_since_now = true;
  }
  data.stats.newton_iterations += it > s.max_iterations ? s.max_iterations : it;
  data.stats.last_iterations = it;
  st.last_iterations = it;
  data.stats.last_increment = inc;
  if (!converged)
    throw SolverError(t1, std::max(inc, viol),
                      "Newton did not converge at t = " + fmt(t1) + " s after " + std::to_string(s.max_iterations) +
                          " iterations (relative formulation): scaled increment " + fmt(inc) + " (tolerance " +
                          fmt(s.newton_tolerance) + "), kept constraint violation " + fmt(viol) +
                          " of the model length. " + ge_beam_failure_hint(model, w.q_last, data.state.q) +
                          detail::newton_remedies(s, h));

  // Final state, multipliers and projections (R for them; the next step's first iteration
  // rebuilds the tangent with R's rate and curvature at its own iterate).
  w.sd = k.c1 * w.s + w.sd_hat;
  w.sdd = k.c2 * w.s + w.sdd_hat;
  relative_kinematics(model, data, true, false);
  update_bodies(model, data);
  update_markers(model, data);
  evaluate_constraints(model, data, t1);
  st.lambda += data.alpha.cwiseProduct(data.Phi);
  data.stats.last_violation = violation(model, data);
  data.stats.last_velocity_violation = 0;
  data.stats.last_acceleration_violation = 0;
  if (model.relative->kept_rows > 0) {
    projected_jacobian(model, data);
    data.stats.last_velocity_violation = relative_project(model, data, w.sd, data.Phit, h);
    if (!(data.stats.last_velocity_violation < s.tolerance))
      throw SolverError(t1, data.stats.last_velocity_violation,
                        "the velocity projection did not converge at t = " + fmt(t1) + " s (relative formulation); try a smaller step (solver.step = " + fmt(0.5 * h) + ")");
    // The acceleration bias at the projected rates: gamma + Phi_q R_dot s_dot.
    w.sdd.setZero();
    relative_kinematics(model, data, false);
    update_body_rates(model, data);
    update_marker_rates(model, data);
    evaluate_constraint_biases(model, data, t1);
    constraint_times(model, data, st.qdd, w.sigma);  // (project() works in r and c)
    w.sigma += data.gamma;
    w.sdd = k.c2 * w.s + w.sdd_hat;
    data.stats.last_acceleration_violation = relative_project(model, data, w.sdd, w.sigma, h2);
    relative_kinematics(model, data, false);
    update_bodies(model, data);
    update_markers(model, data);
  }
  // Generalized-alpha's recurrence advanced with the projected accelerations (finish_step_scheme).
  if (alpha)
    w.a = ((1 - ap.alpha_f) / (1 - ap.alpha_m)) * w.sdd + (ap.alpha_f / (1 - ap.alpha_m)) * w.sdd0 -
          (ap.alpha_m / (1 - ap.alpha_m)) * w.a;
  data.reaction_lambda = st.lambda;
  detail::commit_friction(model, data, h);
  st.t = t1;
  st.have_previous = true;
  w.have_previous = true;
  w.h_prev = h;
  ++data.stats.steps;
  update_angle_references(model, data);
  w.q_last = st.q;
  w.qd_last = st.qd;
  w.t_last = st.t;
}

}  // namespace ffr::runtime
