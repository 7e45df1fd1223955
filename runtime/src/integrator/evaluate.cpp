// Shared evaluation and the tangent of the ALI3-P Newton iteration.
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"

#include <cmath>
#include <limits>

namespace ffr::runtime {

void evaluate(const Model& model, Data& data, double t) {
  update_bodies(model, data);
  update_markers(model, data);
  mass_matrices(model, data);
  generalized_forces(model, data, t);
  evaluate_constraints(model, data, t);
}

void refresh_tangent(const Model& model, Data& data, double t, const VectorXd& lam) {
  const double h = model.settings.step;
  force_tangents(model, data, t);
  data.W.noalias() = (0.5 * h) * data.C;
  data.W.noalias() += (0.25 * h * h) * data.K;
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    data.W.block(b.offset, b.offset, b.ncoord(), b.ncoord()) += data.bodies[i].M;
  }
  refresh_constraint_tangent(model, data, lam);
}

void refresh_constraint_tangent(const Model& model, Data& data, const VectorXd& lam) {
  const double h = model.settings.step;
  // The rows' penalties data.alpha were set by step() at its start.
  data.T = data.W;
  add_penalty_tangent(model, data, data.alpha, 0.25 * h * h, data.T);
  // The constraint forces' own derivative, with the multipliers of the current iterate.
  add_constraint_hessian(model, data, lam, 0.25 * h * h, data.T);
  factorize_tangent(data);
  data.tangent_valid = true;
  ++data.stats.factorizations;
}

void factorize_tangent(Data& data) {
  for (Eigen::Index i = 0; i < data.T.rows(); ++i) {
    const double d = std::abs(data.T(i, i));
    data.scale(i) = d > 0 ? 1.0 / std::sqrt(d) : 1.0;
  }
  data.lu.compute(data.scale.asDiagonal() * data.T * data.scale.asDiagonal());
}

void solve_tangent(Data& data, const VectorXd& rhs, VectorXd& out) {
  ++data.stats.solves;
  // A singular tangent gives a non-finite direction, which the callers report.
  if (!data.lu.ok()) {
    out.setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  out = data.scale.cwiseProduct(rhs);
  data.lu.solve_in_place(out);
  out.array() *= data.scale.array();
}

double scaled_norm(const Model& model, const VectorXd& dq) {
  double s = 0;
  for (const Body& b : model.bodies) {
    const int o = b.offset;
    s = std::max(s, dq.segment<3>(o).cwiseAbs().maxCoeff() / model.length);
    s = std::max(s, dq.segment<9>(o + 3).cwiseAbs().maxCoeff());
    for (int k = 0; k < b.nq; ++k) s = std::max(s, std::abs(dq(o + 12 + k)) / b.y_scale(k));
  }
  return s;
}

}  // namespace ffr::runtime
