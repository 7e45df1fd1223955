// One ALI3-P step: Newton on the trapezoidal-rule dynamics at t+h with the augmented
// Lagrangian update of the multipliers, then the velocity and acceleration projections.
//
//   q_dot = 2/h q + qd_hat,  q_ddot = 4/h^2 q + qdd_hat       (trapezoidal rule)
//   f(q) = h^2/4 [M q_ddot + Phi_q^T (lambda + alpha Phi) - Q] = 0,
//   lambda <- lambda + alpha Phi(q) at each new iterate (the update must use the new Phi: with the
//   previous one the coupled iteration oscillates instead of contracting by M / (M + penalty))
//   tangent  M + h/2 C + h^2/4 (K + alpha Phi_q^T Phi_q)
#include "ffr/runtime/beam.hpp"
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "ffr/runtime/relative.hpp"
#include "../forces/forces.hpp"
#include "../number_text.hpp"
#include "newton_remedies.hpp"

#include <cmath>
#include <limits>

namespace ffr::runtime {
namespace {

// The coordinate with the largest weighted increment dq (scaled_norm), as "body 'name',
// coordinate", and that size.
std::string worst_coordinate(const Model& model, const Data& data, double& size) {
  size = -1;
  std::string out = "none";
  for (int j = 0; j < data.nf; ++j) {
    const double v = std::abs(data.dq(j)) * model.increment_weight(j);
    if (!(v > size) && !std::isnan(v)) continue;
    size = v;
    for (const Body& b : model.bodies) {
      if (j < b.offset || j >= b.offset + b.ncoord()) continue;
      const int k = j - b.offset;
      const char* axis = "xyz";
      std::string c = k < 3    ? std::string("position ") + axis[k]
                      : k < 12 ? std::string("frame vector ") + "uvw"[(k - 3) / 3] + " component " + axis[(k - 3) % 3]
                      : b.beam ? beam_coordinate_name(k - 12)
                      : b.plate ? plate_coordinate_name(*b.plate, k - 12)
                               : "modal coordinate " + std::to_string(k - 12);
      out = "body '" + b.name + "', " + c;
    }
    if (std::isnan(v)) break;
  }
  return out;
}

// The constraint row with the largest violation among the unknowns' rows, named by what it
// belongs to (a joint, a motion, a body's frame), and that violation in model lengths.
std::string worst_row(const Model& model, const Data& data, double& size) {
  size = -1;
  int row = -1;
  for (int i = 0; i < data.na; ++i) {
    const double v = std::abs(data.Phi(i)) / model.length;
    if (v > size || std::isnan(v)) {
      size = v;
      row = i;
      if (std::isnan(v)) break;
    }
  }
  if (row < 0) return "none";
  for (const ConstraintBlock& b : model.blocks) {
    if (row < b.row0 || row >= b.row0 + b.rows) continue;
    const std::string r = " (its row " + std::to_string(row - b.row0 + b.first) + ")";
    switch (b.kind) {
      case BlockKind::RigidBody: return "the frame of body '" + model.bodies[static_cast<std::size_t>(b.index)].name + "'" + r;
      case BlockKind::Joint: return "joint '" + model.joints[static_cast<std::size_t>(b.index)].name + "'" + r;
      case BlockKind::Motion:
        return "the motion of joint '" + model.joints[static_cast<std::size_t>(model.motions[static_cast<std::size_t>(b.index)].joint)].name + "'";
      case BlockKind::Coupler: return "coupler '" + model.couplers[static_cast<std::size_t>(b.index)].name + "'";
    }
  }
  return "row " + std::to_string(row);
}

// What a Newton failure says: when, after how many iterations, which coordinate still moved
// most and which constraint is violated most (the equations to look at), and what to try.
std::string newton_failure(const Model& model, const Data& data, double t, int it, double inc, double viol,
                           const std::string& why) {
  double dq = 0, phi = 0;
  const std::string coord = worst_coordinate(model, data, dq);
  const std::string row = worst_row(model, data, phi);
  return "Newton did not converge at t = " + fmt(t) + " s after " + std::to_string(it) + " iterations" + why +
         ": the largest remaining correction is in " + coord + " (" + fmt(dq) +
         " of the model length; scaled increment " + fmt(inc) + ", tolerance " + fmt(model.settings.newton_tolerance) +
         "), the largest constraint violation in " + row + " (" + fmt(phi) + " of the model length, tolerance " +
         fmt(model.settings.policy.newton.violation_factor * model.settings.tolerance) + "). " +
         ge_beam_failure_hint(model, data.q0, data.state.q) + detail::newton_remedies(model.settings, data.state.k.h) + ", or check that body's mass and " +
         "that joint's axes and points";
}

// The acceptance and tangent-refresh rules are the settings' StepPolicy (step_policy.hpp). The
// measurements behind their defaults, on the benchmark's slider-crank (a crank at 150 rad/s,
// h = 1 ms): the second multiplier pass takes the linearised violation from ~1e-12 to ~1e-15
// of the model length; rebuilding the predictor's tangent at the second iterate (predictor_tangent)
// took iterations 2 to 4 from contracting by only 0.1 to 0.5 (4.45 iterations and 1.50 tangents
// a step, projections of 5 to 11 passes) to convergence at the third; there kappa ~ 2.4e3 to
// 6.2e3 and inc ~ 2e-8 to 6e-8, so the error left after the second iterate is ~1e-12 to 1e-11
// and kappa_life accepts it there instead of at a third iteration.

// The Newton direction dq at the current iterate, with the multipliers driven towards the
// linearised constraints Phi - Phi_q dq = 0 by augmented-Lagrangian passes that reuse the
// factorised tangent (no new evaluation):
//   sigma += alpha (Phi - Phi_q dq),  dq = T^-1 (f + h^2/4 (Phi_q^T + G) sigma),  lambda += sigma,
// G = -dQ/dlambda the multipliers' load on stiffening interfaces (add_interface_multiplier_forces),
// so the passes solve Newton's equations in q and lambda together.
// Without them the multipliers lag one penalty update per Newton iteration, which converges
// only linearly where the penalty is weak against the tangent (a loop closed through an
// elastic body). One pass costs a solve and two products with Phi_q, far less than an
// iteration; on the benchmark's slider-crank it takes Newton from 7.0 to 4.5 iterations per
// step (more passes gained nothing more then; see NewtonPolicy::multiplier_passes for the second). At most
// `passes` passes. Returns the linearised violation left at q - dq, in model lengths.
//
// exact: the multipliers solved for at once instead (exact_multipliers.cpp), for iterations that
// contract slowly once the tangent refreshes are spent: the passes converge slowly along nearly
// redundant constraint directions, and so, through the multipliers they leave, does Newton.
double newton_direction(const Model& model, Data& data, int passes, bool exact) {
  const double h4 = data.state.k.kq;
  solve_tangent(data, data.f, data.dq);
  data.sigma.setZero();
  double left = 0;
  if (exact) {
    // dq = T^-1 (f + Phi_a^T mu) with Phi_a dq = Phi: S mu = Phi - Phi_a T^-1 f.
    const int na = data.na, nf = data.nf;
    constraint_times(model, data, data.dq, data.c);
    data.c = data.Phi - data.c;
    factor_exact_multipliers(data);
    solve_exact_multipliers(data, data.c);
    data.dq.head(nf).noalias() += data.projY.topLeftCorner(nf, na) * data.proj_mu.head(na);
    data.sigma.head(na) = data.proj_mu.head(na) / h4;
    constraint_times(model, data, data.dq, data.c);
    data.c = data.Phi - data.c;
    left = data.c.cwiseAbs().maxCoeff() / model.length;
    data.state.lambda += data.sigma;
    return left;
  }
  for (int pass = 0;; ++pass) {
    constraint_times(model, data, data.dq, data.c);
    data.c = data.Phi - data.c;
    left = data.c.cwiseAbs().maxCoeff() / model.length;
    if (pass == passes || left < model.settings.tolerance) break;
    data.sigma += data.alpha.cwiseProduct(data.c);
    data.r = data.f;
    // c (constraint-sized, recomputed at the next pass) holds the forces' multipliers: tmp is
    // coordinate-sized, and resizing it here made the step allocate and factor_exact_multipliers'
    // solves into it write past its end.
    data.c = h4 * data.sigma;
    add_constraint_forces(model, data, data.c, data.r);
    // The multipliers also load the flexible bodies' interfaces, which stiffens them (the
    // equations' derivative in lambda, FORMULATION.md 7).
    detail::add_interface_multiplier_forces(model, data, data.c, data.r);
    solve_tangent(data, data.r, data.dq);
  }
  data.state.lambda += data.sigma;
  return left;
}

// The rows among driven bodies and the ground hold by construction unless two of them
// prescribe the same body differently (two motions, or a second joint, at odds); no unknown can
// mend that, so it is reported as what it is. They depend on the driven bodies alone: once a
// step is enough.
void check_drives(const Model& model, const Data& data, double t) {
  int block = -1;
  const double v = driven_violation(model, data, block);
  if (!(v < model.settings.policy.newton.violation_factor * model.settings.tolerance)) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(block)];
    const auto name = [&](int body) { return body == kGround ? std::string("ground") : model.bodies[static_cast<std::size_t>(body)].name; };
    std::string what = b.kind == BlockKind::Joint    ? "joint '" + model.joints[static_cast<std::size_t>(b.index)].name + "'"
                       : b.kind == BlockKind::Motion ? "the motion of joint '" + model.joints[static_cast<std::size_t>(model.motions[static_cast<std::size_t>(b.index)].joint)].name + "'"
                       : b.kind == BlockKind::Coupler ? "coupler '" + model.couplers[static_cast<std::size_t>(b.index)].name + "'"
                                                     : "the frame of '" + name(b.body1) + "'";
    throw SolverError(t, v,
                      what + " between '" + name(b.body1) + "' and '" + name(b.body2) + "' is violated by " + fmt(v) +
                          " of the model length at t = " + std::to_string(t) +
                          " s: the joints and motions that drive these bodies from the ground disagree");
  }
}

}  // namespace

void step(const Model& model, Data& data) { step(model, data, model.settings.step); }

void step(const Model& model, Data& data, double h) {
  if (data.relative) return relative_step(model, data, h);  // FORMULATION.md 18
  const SolverSettings& s = model.settings;
  const NewtonPolicy& p = s.policy.newton;
  if (s.integrator == Integrator::GeneralizedAlpha && !data.state.have_previous && !data.scheme.start_step)
    start_generalized_alpha(model, data, h);
  // The scheme (scheme.hpp): q_dot = c1 q + qd_hat, q_ddot = c2 q + qdd_hat; the trapezoidal rule
  // has c1 = 2/h, c2 = 4/h^2, kq = 1/c2 = h^2/4.
  set_step_coefficients(model, data, h);
  const StepCoefficients& k = data.state.k;
  const double h2 = h * h, t1 = data.state.t + h;
  data.q0 = data.state.q;
  data.qd0 = data.state.qd;
  data.qdd0 = data.state.qdd;
  set_step_predictors(model, data);
  // Predictor of the trapezoidal solution q + h qd + h^2/4 (qdd + qdd_next) with qdd_next
  // extrapolated from the last two accelerations (O(h^4) error instead of O(h^3): for a frame
  // turning by omega h per step the first iterate violates the constraints ~(omega h)^4, not
  // ~(omega h)^3); the frame vectors are then replaced by turned frames (predict_frames). The
  // multipliers start from the last step's: extrapolating them is unstable
  // with redundant constraints, whose multipliers are free in the null space of Phi_q^T (each
  // step's round-off there was doubled by 2 lambda_n - lambda_n-1 and grew without bound: the
  // benchmark's planar slider-crank failed after 0.62 s, SliderCrank.RedundantMultipliersStayBounded).
  // (With a step r times the last, qdd_next = qdd + r (qdd - qdd_prev).)
  if (data.state.have_previous) {
    const double r = h / k.h_prev;
    data.state.q.noalias() += h * data.qd0 + (0.25 * (2 + r) * h2) * data.qdd0 - (0.25 * r * h2) * data.state.qdd_prev;
  } else {
    data.state.q.noalias() += h * data.qd0 + (0.5 * h2) * data.qdd0;
  }
  predict_frames(model, data);
  data.state.qdd_prev = data.qdd0;
  data.lambda0 = data.state.lambda;
  // The step's penalties, before the first iterate's lambda + alpha Phi uses them: whoever
  // factorised last (the initial conditions, a projection) may have left other ones.
  penalty_weights(model, data, data.W, s.penalty * k.c2, data.alpha);

  // Tangent policy. Without reuse, the tangent is rebuilt at the first iteration of every step;
  // with reuse, only when the last step needed many iterations. In both cases an iteration that
  // contracts slowly gets a fresh tangent (at most max_refreshes a step). The constraints' second
  // derivatives use the multipliers lambda, not lambda + alpha Phi: at the predictor the
  // constraints are violated by O(h^3) and the penalised multipliers swing far off.
  bool refactor = !data.tangent_valid || !s.reuse_jacobian || data.state.last_iterations > p.reuse_max_iterations;
  ++data.state.kappa_age;
  bool fresh_before = false;  // the last update was made with a tangent built at its iterate
  bool constraints_only = false;  // the next refresh keeps W (see predictor_tangent)
  int refreshes = 0;
  data.tangent_fresh_step = false;
  double inc = 0, prev_inc = 0, viol = 0;
  int it = 0;
  bool converged = false;
  bool exact = false;           // exact multipliers in the direction (newton_direction)
  bool exact_since_now = false; // switched at this iteration: no rate from the last increment
  for (it = 1; it <= s.max_iterations; ++it) {
    data.state.qd = k.c1 * data.state.q + data.qd_hat;
    data.state.qdd = k.c2 * data.state.q + data.qdd_hat;
    drive_bodies(model, data, t1);
    // After the first iterate the driven bodies, their markers and the rows among them are
    // those of t1 already (drive_bodies gives them the same values at every iterate).
    evaluate(model, data, t1, it == 1 ? Scope::All : Scope::Unknowns);
    viol = data.Phi.cwiseAbs().maxCoeff() / model.length;
    if (!std::isfinite(viol)) throw SolverError(t1, viol, newton_failure(model, data, t1, it, inc, viol, " (the state is not finite)"));
    if (it == 1) check_drives(model, data, t1);
    // Augmented-Lagrangian update with the new iterate (from the second pass on: the first uses
    // the previous step's multipliers), then the penalised force lambda + alpha Phi.
    if (it > 1) data.state.lambda += data.alpha.cwiseProduct(data.Phi);
    data.lambda_eff = data.state.lambda + data.alpha.cwiseProduct(data.Phi);
    mass_times(model, data, data.state.qdd, data.f);
    data.f -= data.Q;
    add_constraint_forces(model, data, data.lambda_eff, data.f);
    data.f *= k.kq;
    bool refreshed_now = refactor;
    if (refactor) {
      if (constraints_only) {
        refresh_constraint_tangent(model, data, data.state.lambda);
      } else {
        // The predictor's tangent of a step like the last one, which rebuilt it at the second
        // iterate: its accelerations 4/h^2 q + qdd_hat carry 4/h^2 times the predictor's error
        // (on the benchmark's crank ~0.6 mm, i.e. ~2e3 m/s^2, as large as the accelerations
        // themselves), so the modal acceleration block is left to the rebuild. Measured there:
        // 2.18 Newton iterations a step without it, 2.19 with (and 2.46 when the constraint
        // Hessian is left out as well, which is therefore kept).
        // What the first tangent alone may take: Data::first_tangent_of_step.
        data.first_tangent_of_step = refreshes == 0;
        refresh_tangent(model, data, t1, data.state.lambda, !(it == 1 && data.state.predictor_far));
        data.first_tangent_of_step = false;
      }
      data.tangent_fresh_step = true;
      refactor = constraints_only = false;
      ++refreshes;
    }
    const int passes = it == 1 ? 1 : p.multiplier_passes;
    double left = newton_direction(model, data, passes, exact);
    double next_inc = scaled_norm(model, data.dq);
    // A tangent built at an earlier iterate under which the increment more than doubles is not
    // used: its update is discarded and the direction recomputed with a tangent built here.
    // (Applied, it can throw the iterate so far that no later tangent recovers: a Craig-Bampton
    // rod started at 1500 rpm with h = 1 ms went from a scaled increment of 0.017 to 11, then
    // diverged.) At the first iterate the tangent can only be one kept from an earlier step
    // (reuse_jacobian); it is dropped when its increment is one that would have made the
    // predictor's own tangent stale (stale_tangent): with the benchmark's crank at 150 rad/s,
    // applying it threw the second iterate 7 scaled units off, from which Newton diverged to a
    // non-finite state (SliderCrank.ReusedTangentFallsBackWhenTheCrankTurnsFast).
    const bool stale = it >= 2 ? !(next_inc < p.rejected_growth * inc) : s.penalty * next_inc > p.stale_tangent;
    if (!refreshed_now && refreshes < p.max_refreshes && stale) {
      data.state.lambda -= data.sigma;
      // (At the first iterate as the usual refresh there: without the modal acceleration
      // block after a step that found its predictor far off.)
      refresh_tangent(model, data, t1, data.state.lambda, !(it == 1 && data.state.predictor_far));
      data.tangent_fresh_step = true;
      refreshed_now = true;
      ++refreshes;
      left = newton_direction(model, data, passes, exact);
      next_inc = scaled_norm(model, data.dq);
    }
    data.state.q -= data.dq;
    prev_inc = inc;
    inc = next_inc;
    if (!std::isfinite(inc)) throw SolverError(t1, inc, newton_failure(model, data, t1, it, inc, viol, " (the tangent is singular)"));
    // Converged when the error left after this update is below newton_tolerance: for a contracting
    // iteration (rate theta = inc / prev_inc < 1) it is at most inc theta / (1 - theta)
    // (Hairer & Wanner, Solving ODEs II, IV.8), and the constraints left by the update are
    // the linearised violation (plus O(inc^2)).
    // theta only measures the rate when both increments came from the same tangent.
    const double theta = it >= 2 && prev_inc > 0 && !refreshed_now && !exact_since_now ? inc / prev_inc : 1.0;
    exact_since_now = false;
    // A tangent kept from an earlier step (reuse_jacobian) gives no such bound from one update:
    // built where the constraints' Jacobian was another, its penalty term stiffens directions
    // that are free now, and the increments there understate the error by as much. Its iterates
    // are accepted on the measured contraction alone.
    const double inf = std::numeric_limits<double>::infinity();
    const bool own_tangent = data.tangent_fresh_step;
    const double error_left = it == 1 ? (own_tangent ? inc : inf) : (theta < 1 ? inc * theta / (1 - theta) : inf);
    // The bound on viol (the violation of the iterate this update started from) also covers what
    // that estimate misses at the second iterate, where the first increment came from the
    // predictor and its contraction can understate the rate of the next ones: on the geometrically
    // exact beam's pendulum the estimate was below 1e-12 while the third increment was 1e-10 to
    // 2e-10, and accepting the second iterate on its own measured violation instead left the
    // states 4.4e-8 (scaled) from Newton's run to round-off within 0.2 s
    // (BeamGeometricallyExact.NewtonToleranceBoundsTheAcceptedState).
    if (fresh_before && !refreshed_now && prev_inc > 0) {
      data.state.newton_kappa = inc / (prev_inc * prev_inc);
      data.state.kappa_age = 0;
    }
    fresh_before = refreshed_now && it >= 2;
    if ((error_left < s.newton_tolerance || (own_tangent && inc < s.newton_tolerance)) && left < s.tolerance &&
        viol < p.violation_factor * s.tolerance) {
      converged = true;
      break;
    }
    // Right after a fresh tangent (kappa_life): the violation the update leaves is the
    // linearised one plus O(inc^2), which stands for the check on viol (the violation before it).
    if (fresh_before && data.state.kappa_age <= p.kappa_life && 2 * data.state.newton_kappa * inc * inc < s.newton_tolerance &&
        left < s.tolerance && inc * inc < s.tolerance) {
      converged = true;
      break;
    }
    // The predictor's tangent, far from this iterate: rebuild its constraint terms here (W, the
    // masses and force tangents, moved by O(increment) only).
    if (it == 1 && refreshed_now) {
      data.state.predictor_far = s.penalty * inc > p.predictor_tangent;
      if (data.state.predictor_far) refactor = constraints_only = true;
    }
    // Slow with the refreshes spent: the multipliers are solved for exactly from now on.
    if (it >= 2 && inc > p.slow_contraction * prev_inc && refreshes >= p.max_refreshes && !exact) {
      exact = exact_since_now = true;
    }
    if (it >= 2 && inc > p.slow_contraction * prev_inc && refreshes < p.max_refreshes) {
      refactor = true;
      // A stale tangent (reused from an earlier step) may already have thrown the iterate and
      // the multipliers far off: start the step again from the predictor.
      if (!data.tangent_fresh_step) {
        data.state.q = data.q0;
        data.state.q.noalias() += h * data.qd0 + (0.5 * h2) * data.qdd0;
        data.state.lambda = data.lambda0;
        inc = 0;
      }
    }
  }
  data.stats.newton_iterations += it > s.max_iterations ? s.max_iterations : it;
  data.stats.last_iterations = it;
  data.state.last_iterations = it;
  data.stats.last_increment = inc;
  if (!converged) throw SolverError(t1, std::max(inc, viol), newton_failure(model, data, t1, s.max_iterations, inc, viol, ""));

  // Final state and projections.
  data.state.qd = k.c1 * data.state.q + data.qd_hat;
  data.state.qdd = k.c2 * data.state.q + data.qdd_hat;
  drive_bodies(model, data, t1);
  update_bodies(model, data, Scope::Unknowns);
  update_markers(model, data, Scope::Unknowns);
  evaluate_constraints(model, data, t1, Scope::Unknowns);
  data.state.lambda += data.alpha.cwiseProduct(data.Phi);
  data.stats.last_violation = data.Phi.cwiseAbs().maxCoeff() / model.length;
  data.stats.last_velocity_violation = project_velocities(model, data, t1);
  data.stats.last_acceleration_violation = project_accelerations(model, data, t1);
  finish_step_scheme(model, data);
  detail::commit_friction(model, data, h);  // the markers are those of the final state
  data.state.t = t1;
  data.state.have_previous = true;
  ++data.stats.steps;
  update_angle_references(model, data);
}

}  // namespace ffr::runtime
