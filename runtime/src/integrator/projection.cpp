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

namespace ffr::runtime {
namespace {

constexpr int kMaxProjection = 60;

double project(const Model& model, Data& data, VectorXd& x, const VectorXd& bias, double time_scale) {
  const double h = model.settings.step;
  const double h4 = 0.25 * h * h;
  const double unit = time_scale / model.length;
  data.vstar = x;
  data.sigma.setZero();
  constraint_times(model, data, x, data.c);
  data.c += bias;
  double res = data.c.cwiseAbs().maxCoeff() * unit;
  for (int k = 0; k < kMaxProjection && res > model.settings.tolerance * 1e-2; ++k) {
    data.tmp = x - data.vstar;
    data.r.noalias() = data.W * data.tmp;
    data.c = h4 * (data.sigma + data.alpha * data.c);
    add_constraint_forces(model, data, data.c, data.r);
    data.dq = data.lu.solve(data.r);
    x -= data.dq;
    constraint_times(model, data, x, data.c);
    data.c += bias;
    data.sigma += data.alpha * data.c;
    const double prev = res;
    res = data.c.cwiseAbs().maxCoeff() * unit;
    if (res > 0.9 * prev && k > 2) break;  // stagnated at round-off
  }
  return res;
}

}  // namespace

double project_velocities(const Model& model, Data& data, double t) {
  const double h = model.settings.step;
  return project(model, data, data.qd, data.Phit, h);
}

double project_accelerations(const Model& model, Data& data, double t) {
  const double h = model.settings.step;
  // gamma depends on the (projected) velocities.
  update_bodies(model, data);
  update_markers(model, data);
  evaluate_constraints(model, data, t);
  return project(model, data, data.qdd, data.gamma, h * h);
}

}  // namespace ffr::runtime
