#pragma once
// A model's Data set to a chosen state, for the tests that compare a derivative (Jacobian, bias,
// tangent) with central differences of what the runtime evaluates at nearby states.
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "ffr/runtime/runtime.hpp"

#include "central_differences.hpp"

#include <memory>
#include <random>

namespace ffr::runtime::test {

struct StateProbe {
  Model model;
  std::unique_ptr<Data> data;
  VectorXd q, qd, qdd;  ///< the state the derivatives are taken at

  /// Data for `model`, and a state near its initial one: coordinates moved by up to 0.05, rates
  /// and accelerations uniform in [-1, 1] (seeded: every run the same).
  void start(Model m, unsigned seed) {
    model = std::move(m);
    data = std::make_unique<Data>(model);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    q = data->state.q;
    qd = data->state.qd;
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      q(i) += 0.05 * u(rng);
      qd(i) = u(rng);
    }
    qdd = VectorXd::NullaryExpr(q.size(), [&](Eigen::Index) { return u(rng); });
  }
  /// Sets the state and brings the bodies and markers up to date with it.
  void set(const VectorXd& a, const VectorXd& b, const VectorXd& c) {
    data->state.q = a;
    data->state.qd = b;
    data->state.qdd = c;
    update_bodies(model, *data);
    update_markers(model, *data);
  }
  /// The constraints at coordinates `a` (the probe's rates and accelerations) and `time`.
  VectorXd constraints(const VectorXd& a, double time) {
    set(a, qd, qdd);
    evaluate_constraints(model, *data, time);
    return data->Phi;
  }
  /// The constraint Hessian weighted by `lam` (add_constraint_hessian) at the probe's state and
  /// `time`, and its oracle: central differences of the constraint forces Phi_q^T lam.
  struct Hessians {
    MatrixXd H, Hfd;
  };
  Hessians constraint_hessians(const VectorXd& lam, double time) {
    auto force = [&](const VectorXd& a) {
      constraints(a, time);
      VectorXd g = VectorXd::Zero(model.ncoord);
      add_constraint_forces(model, *data, lam, g);
      return g;
    };
    Hessians r;
    r.Hfd = central_differences(force, q, 1e-6);
    set(q, qd, qdd);
    evaluate_constraints(model, *data, time);
    r.H = MatrixXd::Zero(model.ncoord, model.ncoord);
    add_constraint_hessian(model, *data, lam, 1.0, r.H);
    return r;
  }
};

}  // namespace ffr::runtime::test
