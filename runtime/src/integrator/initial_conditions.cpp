// Consistent initial conditions (FORMULATION.md section 10).
//
// Positions: the configuration closest to the given one in the kinetic-energy metric M that
// satisfies every constraint at the start time, by the same augmented-Lagrangian Newton as the
// integrator (so redundant constraints are fine). Velocities: the M-orthogonal projection of the
// given ones. Accelerations and multipliers: M a + Phi_q^T lambda = Q, Phi_q a + gamma = 0,
// by augmented-Lagrangian iterations.
#include "../forces/forces.hpp"
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "ffr/runtime/statics.hpp"
#include "../number_text.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace ffr::runtime {
namespace {

constexpr int kMaxAssembly = 200;

// How much dearer a change of the modal coordinates is than a change of the frame coordinates
// in the first attempt of the initial projections (see assemble_positions below).
constexpr double kElasticWeight = 1e12;

// W = the block-diagonal mass matrix, plus elastic_weight times the diagonal of each flexible
// body's modal block; the rows' penalties data.alpha = alpha_factor times W along each row,
// T = W + t_factor Phi_q^T diag(alpha) Phi_q, factorised.
void factor_metric(const Model& model, Data& data, double alpha_factor, double t_factor, double elastic_weight = 0) {
  data.W.setZero();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    data.W.block(b.offset, b.offset, b.ncoord(), b.ncoord()) = data.bodies[i].M;
    for (int k = 0; k < b.nq; ++k) {
      const int j = b.offset + 12 + k;
      data.W(j, j) *= 1.0 + elastic_weight;
    }
  }
  penalty_weights(model, data, data.W, alpha_factor, data.alpha);
  data.T = data.W;
  add_penalty_tangent(model, data, data.alpha, t_factor, data.T);
  factorize_tangent(data);
  data.tangent_metric_only = true;
}

// Largest change of a body's frame (origin, or frame vectors times the model length).
std::string largest_change(const Model& model, const VectorXd& a, const VectorXd& b, const char* unit) {
  double best = -1;
  std::string who;
  for (const Body& body : model.bodies) {
    const int o = body.offset;
    const double d = std::max((a.segment<3>(o) - b.segment<3>(o)).norm(),
                              (a.segment<9>(o + 3) - b.segment<9>(o + 3)).cwiseAbs().maxCoeff() * model.length);
    if (d > best) {
      best = d;
      who = body.name;
    }
  }
  return fmt(best) + " " + unit + " (body '" + who + "')";
}

// The augmented-Lagrangian Newton of the positions in the metric W of factor_metric, from the
// given configuration. Returns the final violation (relative to the model length).
double assemble_in_metric(const Model& model, Data& data, const VectorXd& given, double t0, double elastic_weight,
                          int& it) {
  const double kappa = model.settings.penalty;
  const double tol = model.settings.tolerance;
  data.state.q = given;
  update_bodies(model, data);
  mass_matrices(model, data);
  update_markers(model, data);
  evaluate_constraints(model, data, t0);
  data.state.lambda.setZero();
  double viol = data.Phi.cwiseAbs().maxCoeff() / model.length, inc = 0;
  for (it = 0; it < kMaxAssembly; ++it) {
    // The metric is the mass matrix at the given configuration; the tangent is refreshed each pass.
    factor_metric(model, data, kappa, 1.0, elastic_weight);
    if (it > 0) data.state.lambda += data.alpha.cwiseProduct(data.Phi);
    data.lambda_eff = data.state.lambda + data.alpha.cwiseProduct(data.Phi);
    data.tmp = data.state.q - given;
    data.r.noalias() = data.W * data.tmp;
    add_constraint_forces(model, data, data.lambda_eff, data.r);
    solve_tangent(data, data.r, data.dq);
    data.state.q -= data.dq;
    inc = scaled_norm(model, data.dq);
    update_bodies(model, data);
    update_markers(model, data);
    evaluate_constraints(model, data, t0);
    viol = data.Phi.cwiseAbs().maxCoeff() / model.length;
    if (!std::isfinite(viol)) break;
    if (viol < 1e-3 * tol && inc < tol) break;
  }
  return viol;
}

// Rigid first: a flexible body's modal coordinates and velocities keep their given values
// (zero by default) when moving the frames alone can satisfy the joints and motions; only
// otherwise do the bodies deform. The plain kinetic-energy metric would spread the correction
// over frame and modal coordinates and start the body vibrating in its stiffest modes (a
// Craig-Bampton rod on a 1500 rpm crank got 1.5 units of modal velocity in a constraint mode).
void assemble_positions(const Model& model, Data& data, double t0, std::vector<std::string>& notes) {
  const VectorXd given = data.state.q;
  update_bodies(model, data);
  mass_matrices(model, data);
  update_markers(model, data);
  evaluate_constraints(model, data, t0);
  const double tol = model.settings.tolerance;
  double viol = data.Phi.cwiseAbs().maxCoeff() / model.length;
  if (viol < 1e-3 * tol) return;
  int it = 0;
  viol = assemble_in_metric(model, data, given, t0, kElasticWeight, it);
  // The weighted metric is worse conditioned and may stall just above the tolerance: finish in
  // the plain metric from there (a round-off-sized correction), or from the given
  // configuration if the frames alone could not do it.
  if (!(viol < 1e-3 * tol)) {
    const VectorXd start = viol < 1e-6 ? VectorXd(data.state.q) : given;
    viol = assemble_in_metric(model, data, start, t0, 0.0, it);
  }
  if (!(viol < tol))
    throw SolverError(t0, viol,
                      "the initial configuration cannot be assembled: the joints and motions leave a violation of " +
                          fmt(viol) + " of the model length after " + std::to_string(it) + " iterations");
  const double change = (data.state.q - given).cwiseAbs().maxCoeff();
  if (change > 1e-9) notes.push_back("initial positions adjusted to satisfy the joints and motions: largest change " +
                                     largest_change(model, data.state.q, given, "m"));
}

std::vector<std::string> consistent_state(const Model& model, Data& data) {
  std::vector<std::string> notes;
  const double h = model.settings.step;
  const double t0 = model.settings.start;
  data.state.t = t0;
  data.state.k = trapezoidal_coefficients(h);  // the projections' metric below (scheme.hpp)
  data.state.qdd.setZero();
  data.state.have_previous = false;
  data.stats = Stats{};
  std::fill(data.state.friction.begin(), data.state.friction.end(), FrictionState{});
  // Every body is moved into place, the driven ones too; they follow their drives afterwards.
  set_unknowns(model, data, false);
  // Angles of driven joints are unwrapped around their targets from the start.
  for (std::size_t m = 0; m < model.motions.size(); ++m)
    if (model.motions[m].coordinate == JointCoordinate::Angle)
      data.state.angle_ref[model.motions[m].joint] = motion_target(model, data, static_cast<int>(m), t0)(0);

  assemble_positions(model, data, t0, notes);
  update_angle_references(model, data);

  // Velocities: M-orthogonal projection (metric M, as the step's projections use W at h -> 0).
  update_bodies(model, data);
  mass_matrices(model, data);
  update_markers(model, data);
  evaluate_constraints(model, data, t0);
  const VectorXd given = data.state.qd;
  // Rigid first, as for the positions, then the plain metric from there (or from the given
  // velocities if the frames alone could not satisfy the joints and motions).
  factor_metric(model, data, model.settings.penalty * 4.0 / (h * h), 0.25 * h * h, kElasticWeight);
  data.tangent_fresh_step = true;  // the metric is M here: no refresh with C and K
  // (Not converging here is no error: the plain metric below is the fallback.)
  double vres = project_velocities(model, data, t0, false);
  if (vres > 1e-2 * model.settings.tolerance) {
    if (!(vres < 1e-6)) data.state.qd = given;
    factor_metric(model, data, model.settings.penalty * 4.0 / (h * h), 0.25 * h * h);
    vres = project_velocities(model, data, t0);
  }
  if (vres > model.settings.tolerance)
    throw SolverError(t0, vres, "the initial velocities cannot be made consistent with the joints and motions");
  const double dv = (data.state.qd - given).cwiseAbs().maxCoeff();
  // Below this the change is the rounding of the given numbers, not worth a note.
  if (dv > 1e-8 * std::max(1.0, given.cwiseAbs().maxCoeff()))
    notes.push_back("initial velocities adjusted to satisfy the joints and motions: largest change " +
                    largest_change(model, data.state.qd, given, "m/s"));

  // Accelerations and multipliers. The stiffening forces depend on the accelerations, hence the
  // outer fixed-point passes.
  for (int pass = 0; pass < 3; ++pass) {
    evaluate(model, data, t0);
    factor_metric(model, data, model.settings.penalty, 1.0);
    data.state.lambda.setZero();
    double res = 0;
    for (int k = 0; k < 100; ++k) {
      // (M + alpha Phi_q^T Phi_q) a = Q - Phi_q^T (lambda + alpha gamma);  lambda += alpha (Phi_q a + gamma)
      data.r = data.Q;
      data.c = -(data.state.lambda + data.alpha.cwiseProduct(data.gamma));
      add_constraint_forces(model, data, data.c, data.r);
      solve_tangent(data, data.r, data.state.qdd);
      constraint_times(model, data, data.state.qdd, data.c);
      data.c += data.gamma;
      data.state.lambda += data.alpha.cwiseProduct(data.c);
      res = data.c.cwiseAbs().maxCoeff() * h * h / model.length;
      if (res < 1e-3 * model.settings.tolerance) break;
    }
  }
  // A direction of motion without inertia that no joint holds (a massless degree of freedom
  // held only by force elements) leaves the metric singular: the step would start from a
  // non-finite state and fail naming nothing.
  if (!data.state.qdd.allFinite() || !data.state.lambda.allFinite())
    throw SolverError(t0, std::numeric_limits<double>::quiet_NaN(),
                      "the initial accelerations at t = " + fmt(t0) +
                          " s are not finite: the mass matrix with the joints' constraints is singular (a motion without "
                          "inertia that no joint holds, such as a body whose mass lies on a line, held only by force "
                          "elements); give the body inertia there or a joint that holds that motion");
  detail::commit_friction(model, data, 0.0);  // the friction dampers' power at the start
  data.reaction_lambda = data.state.lambda;
  data.forget_tangents();  // none kept from the settling's
  set_unknowns(model, data, true);
  return notes;
}

}  // namespace

std::vector<std::string> initialize(const Model& model, Data& data) {
  std::vector<std::string> notes = consistent_state(model, data);
  const SolverSettings& s = model.settings;
  if (!s.static_analysis && !s.initial_equilibrium) return notes;
  // Settled at rest (statics.hpp), then the accelerations and multipliers made consistent
  // again there (the positions hold the constraints already; the velocities are zero).
  for (auto& n : settle_statically(model, data)) notes.push_back(std::move(n));
  for (auto& n : consistent_state(model, data)) notes.push_back(std::move(n));
  return notes;
}

}  // namespace ffr::runtime
