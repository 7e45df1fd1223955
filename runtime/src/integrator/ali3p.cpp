// One ALI3-P step: Newton on the trapezoidal-rule dynamics at t+h with the augmented
// Lagrangian update of the multipliers, then the velocity and acceleration projections.
//
//   q_dot = 2/h q + qd_hat,  q_ddot = 4/h^2 q + qdd_hat       (trapezoidal rule)
//   f(q) = h^2/4 [M q_ddot + Phi_q^T (lambda + alpha Phi) - Q] = 0,
//   lambda <- lambda + alpha Phi(q) at each new iterate (the update must use the new Phi: with the
//   previous one the coupled iteration oscillates instead of contracting by M / (M + penalty))
//   tangent  M + h/2 C + h^2/4 (K + alpha Phi_q^T Phi_q)
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"

#include <cmath>
#include <cstdio>

namespace ffr::runtime {
namespace {

std::string newton_failure(double t, int it, double inc, double viol) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "Newton did not converge at t = %.9g s after %d iterations (scaled increment %.3g, "
                "constraint violation %.3g of the model length)",
                t, it, inc, viol);
  return buf;
}

}  // namespace

void step(const Model& model, Data& data) {
  const SolverSettings& s = model.settings;
  const double h = s.step, h2 = h * h, t1 = data.t + h;
  data.q0 = data.q;
  data.qd0 = data.qd;
  data.qdd0 = data.qdd;
  data.qd_hat = -(2.0 / h) * data.q0 - data.qd0;
  data.qdd_hat = -(4.0 / h2) * data.q0 - (4.0 / h) * data.qd0 - data.qdd0;
  data.q.noalias() += h * data.qd0 + (0.5 * h2) * data.qdd0;
  data.lambda0 = data.lambda;

  bool refactor = !data.tangent_valid || !s.reuse_jacobian;
  data.tangent_fresh_step = false;
  double inc = 0, prev_inc = 0, viol = 0;
  int it = 0;
  bool converged = false;
  for (it = 1; it <= s.max_iterations; ++it) {
    data.qd = (2.0 / h) * data.q + data.qd_hat;
    data.qdd = (4.0 / h2) * data.q + data.qdd_hat;
    evaluate(model, data, t1);
    viol = data.Phi.cwiseAbs().maxCoeff() / model.length;
    if (!std::isfinite(viol)) throw SolverError(t1, viol, newton_failure(t1, it, inc, viol) + ": the state is not finite");
    // Augmented-Lagrangian update with the new iterate (from the second pass on: the first uses
    // the previous step's multipliers), then the penalised force lambda + alpha Phi.
    if (it > 1) data.lambda += data.alpha * data.Phi;
    data.lambda_eff = data.lambda + data.alpha * data.Phi;
    mass_times(model, data, data.qdd, data.f);
    data.f -= data.Q;
    add_constraint_forces(model, data, data.lambda_eff, data.f);
    data.f *= 0.25 * h2;
    if (refactor) {
      refresh_tangent(model, data, t1);
      refactor = false;
      data.tangent_fresh_step = true;
    }
    data.dq = data.lu.solve(data.f);
    data.q -= data.dq;
    prev_inc = inc;
    inc = scaled_norm(model, data.dq);
    if (!std::isfinite(inc)) throw SolverError(t1, inc, newton_failure(t1, it, inc, viol) + ": singular tangent");
    if (std::getenv("FFR_DEBUG")) std::fprintf(stderr, "  it %d inc %.3e viol %.3e f %.3e lam %.3e\n", it, inc, viol, data.f.cwiseAbs().maxCoeff(), data.lambda.cwiseAbs().maxCoeff());
    if (inc < s.tolerance && viol < s.tolerance) {
      converged = true;
      break;
    }
    // A stale tangent that contracts slowly is refreshed, and the step restarted from the
    // predictor: the stale iterations may have pushed the multipliers far off, where the
    // tangent (without the constraints' second derivatives) converges poorly.
    if (!data.tangent_fresh_step && it >= 2 && inc > 0.25 * prev_inc) {
      refactor = true;
      data.q = data.q0;
      data.q.noalias() += h * data.qd0 + (0.5 * h2) * data.qdd0;
      data.lambda = data.lambda0;
      inc = 0;
    }
  }
  data.stats.newton_iterations += it > s.max_iterations ? s.max_iterations : it;
  data.stats.last_iterations = it;
  data.stats.last_increment = inc;
  if (!converged) throw SolverError(t1, std::max(inc, viol), newton_failure(t1, s.max_iterations, inc, viol));

  // Final state and projections.
  data.qd = (2.0 / h) * data.q + data.qd_hat;
  data.qdd = (4.0 / h2) * data.q + data.qdd_hat;
  update_bodies(model, data);
  update_markers(model, data);
  evaluate_constraints(model, data, t1);
  data.lambda += data.alpha * data.Phi;
  data.stats.last_violation = data.Phi.cwiseAbs().maxCoeff() / model.length;
  { if (!std::getenv("NOVEL")) { if (!std::getenv("NOVEL")) { if (!std::getenv("NOVEL")) data.stats.last_velocity_violation = project_velocities(model, data, t1); } } }
  { if (!std::getenv("NOACC")) { if (!std::getenv("NOACC")) { if (!std::getenv("NOACC")) data.stats.last_acceleration_violation = project_accelerations(model, data, t1); } } }
  data.t = t1;
  ++data.stats.steps;
  update_angle_references(model, data);
  // Many iterations mean the tangent no longer fits: refresh it at the next step.
  if (it > 4) data.tangent_valid = false;
}

}  // namespace ffr::runtime
