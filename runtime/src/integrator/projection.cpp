// Mass-orthogonal projections of velocities and accelerations (ALI3-P).
//
// The projected x minimises 1/2 (x - x*)^T W (x - x*) subject to Phi_q x + b = 0, with
// W = M + h/2 C + h^2/4 K the metric of the last factorisation. It is solved by the augmented
// Lagrangian iteration that reuses the factorised tangent T:
//   x <- x - T^{-1} [W (x - x*) + h^2/4 Phi_q^T (sigma + alpha c(x))],  sigma <- sigma + alpha c(x)
// When T is the metric alone, W + h^2/4 alpha Phi_q^T Phi_q, each pass minimises the augmented
// Lagrangian exactly and only the multipliers lag (the first pass is Cuadrado's single
// projection). The step's tangent also holds the constraints' second derivatives (and a flexible
// body's modal acceleration term), which W does not: the passes are then a modified Newton
// iteration on the same equations, whose fixed point is still the W-projection but which has to
// be iterated until x itself has converged, not only the constraint residual. (With a large
// penalty the residual drops below the tolerance at the first pass while x is still off in the
// directions the constraints leave free: on Andrews' mechanism with penalty 1e6 that stopped the
// acceleration projection after one pass, 1e3 rad/s^2 off, and the angles ended 5e-2 rad off at
// h = 1e-5 s, where the default penalty gives 3e-4; andrews_options_test.cpp.)
//
// Accepted when the constraint residual is at the tolerance and the estimated error of x, in
// the units of the Newton tolerance (FORMULATION.md 9), is below it.
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "dense_products.hpp"
#include "tangent_blocks.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace ffr::runtime {
namespace {

struct Projected {
  double residual;  ///< constraint residual left (model lengths, times the time scale)
  double error;     ///< estimated error of x left (scaled, times the time scale)
  bool converged;
};

// One projection with the current factorisation; x is left projected (or as far as it got).
// Only the rows of the unknowns (the first data.na) take part: the others, among driven bodies,
// hold by construction, and data.c stays zero there.
//
// time_scale (h for velocities, h^2 for accelerations) turns x into position units: an error e
// of the velocities (accelerations) moves the next step's positions by about h e (h^2 e), so the
// projection is held to the Newton tolerance in those units.
Projected project_once(const Model& model, Data& data, VectorXd& x, const VectorXd& bias, double time_scale) {
  const SolverSettings& s = model.settings;
  const ProjectionPolicy& p = s.policy.projection;
  const double h4 = data.state.k.kq;  // h^2/4 for the trapezoidal rule
  const double unit = time_scale / model.length;
  const double target = p.residual_fraction * s.tolerance;
  const double inf = std::numeric_limits<double>::infinity();
  const int na = data.na;
  data.sigma.setZero();
  constraint_times(model, data, x, data.c);
  data.c.head(na) += bias.head(na);
  double res = na > 0 ? data.c.head(na).cwiseAbs().maxCoeff() * unit : 0.0;
  // x* satisfies the constraints already: it is its own projection.
  if (res <= target) return {res, 0.0, true};
  double prev_dx = inf, prev_res = res, error = inf;
  int growing = 0;
  for (int k = 0; k < p.max_passes; ++k) {
    // x = x* at the first pass (project sets vstar = x): W (x - x*) is zero then.
    if (k == 0) {
      data.r.head(data.nf).setZero();
    } else {
      data.tmp = x - data.vstar;
      // Over the tangent blocks where that pays (tangent_blocks.hpp): W is zero outside them.
      const Eigen::Index ld = data.W.rows();
      if (data.tangent_blocks_pay) {
        data.r.head(data.nf).setZero();
        detail::for_each_tangent_block(model, data, true, [&](int r0, int nr, int c0, int nc) {
          detail::times(data.W.data() + c0 * ld + r0, ld, nr, nc, data.tmp.data() + c0, data.r.data() + r0, true);
        });
      } else {
        detail::times(data.W, data.nf, data.nf, data.tmp, data.r, false);
      }
    }
    data.c = h4 * (data.sigma + data.alpha.cwiseProduct(data.c));
    add_constraint_forces(model, data, data.c, data.r);
    solve_tangent(data, data.r, data.dq);
    x -= data.dq;
    constraint_times(model, data, x, data.c);
    data.c.head(na) += bias.head(na);
    data.sigma += data.alpha.cwiseProduct(data.c);
    res = data.c.head(na).cwiseAbs().maxCoeff() * unit;
    const double dx = scaled_norm(model, data.dq) * time_scale;
    if (!std::isfinite(res) || !std::isfinite(dx)) return {res, inf, false};
    // The error left after this pass, from the contraction of the passes (as Newton's, Hairer &
    // Wanner, Solving ODEs II, IV.8); the first pass has nothing to compare with.
    const double theta = k >= 1 ? dx / prev_dx : inf;
    error = theta < 1 ? dx * theta / (1 - theta) : inf;
    if (dx < p.round_off_fraction * s.newton_tolerance) error = std::min(error, dx);
    // The residual is done at the target, or where it stalls at round-off below the tolerance.
    const bool residual_done = res < target || (k >= 3 && res > 0.5 * prev_res && res < s.tolerance);
    if (residual_done && error < s.newton_tolerance) return {res, error, true};
    growing = theta >= 1 ? growing + 1 : 0;
    if (growing >= 2 || !(res < 1e3 * std::max(prev_res, target))) return {res, error, false};  // diverging
    prev_dx = dx;
    prev_res = res;
  }
  return {res, error, false};
}

// The W-projection solved directly (exact_multipliers.cpp), for when the passes stall. With the
// metric alone factorised, F = W + kq Phi_a^T alpha Phi_a (factorize_metric), the projection
// satisfies F (x - x*) = -Phi_a^T mu, mu = kq (sigma + alpha c*), c* = Phi_a x* + b: x = x* - Y mu
// with S mu = c*. S is as ill-conditioned as the rows are nearly redundant, so the solve is
// refined with its residual (a few rounds with the same factor).
Projected project_exact(const Model& model, Data& data, VectorXd& x, const VectorXd& bias, double time_scale) {
  const SolverSettings& s = model.settings;
  const int na = data.na, nf = data.nf;
  const double unit = time_scale / model.length;
  const double target = s.policy.projection.residual_fraction * s.tolerance;
  const double inf = std::numeric_limits<double>::infinity();
  constexpr int refinements = 3;
  constraint_times(model, data, x, data.c);
  data.c.head(na) += bias.head(na);
  double res = na > 0 ? data.c.head(na).cwiseAbs().maxCoeff() * unit : 0.0;
  if (res <= target) return {res, 0.0, true};
  factor_exact_multipliers(data);
  const double kq = data.state.k.kq;
  data.sigma.head(na) = -data.alpha.head(na).cwiseProduct(data.c.head(na));  // sigma as the passes define it
  for (int round = 0; round <= refinements && res > target; ++round) {
    solve_exact_multipliers(data, data.c);
    data.sigma.head(na) += data.proj_mu.head(na) / kq;
    x.head(nf).noalias() -= data.projY.topLeftCorner(nf, na) * data.proj_mu.head(na);
    constraint_times(model, data, x, data.c);
    data.c.head(na) += bias.head(na);
    res = na > 0 ? data.c.head(na).cwiseAbs().maxCoeff() * unit : 0.0;
    if (!std::isfinite(res)) return {res, inf, false};
  }
  return {res, 0.0, res < s.tolerance};
}

// Projects x (saved first). If the factorisation at hand does not converge, the tangent is
// rebuilt at the current state (when it was built at an earlier one), then replaced by the
// metric alone, with which the passes are the exact augmented-Lagrangian iteration; if they
// still do not converge, the projection is solved directly with the metric (project_exact).
double project(const Model& model, Data& data, VectorXd& x, const VectorXd& bias, double time_scale, double t,
               const char* what, bool must_converge) {
  data.vstar = x;
  Projected r = project_once(model, data, x, bias, time_scale);
  if (!r.converged && !data.tangent_fresh_step) {
    x = data.vstar;
    refresh_tangent(model, data, t, data.state.lambda);
    data.tangent_fresh_step = true;
    r = project_once(model, data, x, bias, time_scale);
  }
  if (!r.converged && !data.tangent_metric_only) {
    x = data.vstar;
    factorize_metric(model, data);
    r = project_once(model, data, x, bias, time_scale);
  }
  if (!r.converged) {
    x = data.vstar;
    r = project_exact(model, data, x, bias, time_scale);
  }
  if (!r.converged && !must_converge) return std::numeric_limits<double>::infinity();
  if (!r.converged) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "the %s projection did not converge at t = %.9g s (constraint residual %.3g, estimated error %.3g, "
                  "tolerances %.3g and %.3g): try a smaller step, or a smaller penalty",
                  what, t, r.residual, r.error, model.settings.tolerance, model.settings.newton_tolerance);
    throw SolverError(t, r.residual, buf);
  }
  return r.residual;
}

}  // namespace

double project_velocities(const Model& model, Data& data, double t, bool must_converge) {
  const double h = data.state.k.h;
  return project(model, data, data.state.qd, data.Phit, h, t, "velocity", must_converge);
}

double project_accelerations(const Model& model, Data& data, double t) {
  const double h = data.state.k.h;
  // gamma depends on the (projected) velocities; q, and with it the Jacobian, has not changed
  // since the final evaluation of the step.
  update_body_rates(model, data);
  update_marker_rates(model, data);
  evaluate_constraint_biases(model, data, t);
  const double res = project(model, data, data.state.qdd, data.gamma, h * h, t, "acceleration", true);
  // The projection's multipliers: at its fixed point W (q_dd - q_dd*) + kq Phi_q^T sigma = 0, so
  // lambda + kq sigma balances the projected accelerations (to the h/2 C + h^2/4 K of W).
  data.reaction_lambda = data.state.lambda + data.state.k.kq * data.sigma;
  return res;
}

}  // namespace ffr::runtime
