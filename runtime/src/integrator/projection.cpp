// Mass-orthogonal projections of velocities and accelerations (ALI3-P).
//
// The projected x minimises 1/2 (x - x*)^T W (x - x*) subject to Phi_q x + b = 0, with
// W = M + h/2 C + h^2/4 K the metric of the last factorisation. It is solved by the augmented
// Lagrangian iteration that reuses the factorised T = W + h^2/4 alpha Phi_q^T Phi_q:
//   x <- x - T^{-1} [W (x - x*) + h^2/4 Phi_q^T (sigma + alpha c(x))],  sigma <- sigma + alpha c(x)
// With a fresh T the first pass is exactly Cuadrado's single projection; further passes drive the
// violation to round-off (also with redundant constraints, where Phi_q is rank-deficient).
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "dense_products.hpp"

namespace ffr::runtime {
namespace {

constexpr int kMaxProjection = 40;

// One projection with the current factorisation; x is left projected (or as far as it got).
// Only the rows of the unknowns (the first data.na) take part: the others, among driven bodies,
// hold by construction, and data.c stays zero there.
double project_once(const Model& model, Data& data, VectorXd& x, const VectorXd& bias, double unit) {
  const double h4 = data.scheme.k.kq;
  const double target = 1e-2 * model.settings.tolerance;
  const int na = data.na;
  data.sigma.setZero();
  constraint_times(model, data, x, data.c);
  data.c.head(na) += bias.head(na);
  double res = data.c.head(na).cwiseAbs().maxCoeff() * unit;
  const double res0 = res;
  for (int k = 0; k < kMaxProjection && res > target; ++k) {
    // x = x* at the first pass (project sets vstar = x): W (x - x*) is zero then.
    if (k == 0) {
      data.r.head(data.nf).setZero();
    } else {
      data.tmp = x - data.vstar;
      detail::times(data.W, data.nf, data.nf, data.tmp, data.r, false);
    }
    data.c = h4 * (data.sigma + data.alpha.cwiseProduct(data.c));
    add_constraint_forces(model, data, data.c, data.r);
    solve_tangent(data, data.r, data.dq);
    x -= data.dq;
    constraint_times(model, data, x, data.c);
    data.c.head(na) += bias.head(na);
    data.sigma += data.alpha.cwiseProduct(data.c);
    const double prev = res;
    res = data.c.head(na).cwiseAbs().maxCoeff() * unit;
    if (!(res < 1e3 * std::max(res0, target))) return res;  // diverging: stale factorisation
    if (k > 3 && res > 0.5 * prev) break;                    // stagnating at round-off
  }
  return res;
}

// Projects x (saved first) and, if a stale factorisation cannot do it, refreshes the tangent at
// the current state and starts again.
double project(const Model& model, Data& data, VectorXd& x, const VectorXd& bias, double time_scale, double t) {
  const double unit = time_scale / model.length;
  data.vstar = x;
  double res = project_once(model, data, x, bias, unit);
  if (res > model.settings.tolerance && data.tangent_fresh_step == false) {
    x = data.vstar;
    refresh_tangent(model, data, t, data.lambda);
    data.tangent_fresh_step = true;
    data.vstar = x;
    res = project_once(model, data, x, bias, unit);
  }
  return res;
}

}  // namespace

double project_velocities(const Model& model, Data& data, double t) {
  const double h = data.scheme.k.h;
  return project(model, data, data.qd, data.Phit, h, t);
}

double project_accelerations(const Model& model, Data& data, double t) {
  const double h = data.scheme.k.h;
  // gamma depends on the (projected) velocities; q, and with it the Jacobian, has not changed
  // since the final evaluation of the step.
  update_body_rates(model, data);
  update_marker_rates(model, data);
  evaluate_constraint_biases(model, data, t);
  return project(model, data, data.qdd, data.gamma, h * h, t);
}

}  // namespace ffr::runtime
