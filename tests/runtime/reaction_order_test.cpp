// The order of accuracy of a joint reaction (FORMULATION.md 13) against an analytic one.
//
// Source: a rigid pendulum (mass m, centre of mass at L from its hinge, own inertia I about it)
// released horizontal from rest; by Newton's law along the arm the hinge pulls the body towards
// itself with N = m (g cos(theta) + L theta_dot^2), theta measured from the downward vertical,
// and I_O theta_ddot = -m g L sin(theta), I_O = I + m L^2 (any mechanics text, e.g. J. L.
// Meriam, L. G. Kraige, "Engineering Mechanics: Dynamics", ch. 6). theta(t) by a classical
// Runge-Kutta integration written here with a step small enough to be exact to round-off.
#include "ffr/runtime/outputs.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace ffr::runtime;

namespace {

constexpr double kG = 9.81, kM = 1.0, kL = 1.0, kI = 0.01;

// theta, theta_dot at t of the pendulum released at theta = pi/2 from rest (RK4, step 1e-5 s).
Eigen::Vector2d exact_swing(double t_end) {
  const double IO = kI + kM * kL * kL;
  auto f = [&](const Eigen::Vector2d& x) { return Eigen::Vector2d(x(1), -kM * kG * kL * std::sin(x(0)) / IO); };
  Eigen::Vector2d x(M_PI / 2, 0);
  const int n = static_cast<int>(std::lround(t_end / 1e-5));
  const double h = t_end / n;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d k1 = f(x), k2 = f(x + h / 2 * k1), k3 = f(x + h / 2 * k2), k4 = f(x + h * k3);
    x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return x;
}

struct Pull {
  double reaction;  // the joint reaction's pull along the arm (data.reaction_lambda)
  double newton;    // the same from the step's own multipliers (data.state.lambda)
};

// The hinge's pull on the body along the arm at t_end, run with step h.
Pull runtime_pull(double h, double t_end) {
  char json[2048];
  std::snprintf(json, sizeof json, R"({
  "gravity": [0, -9.81, 0],
  "bodies": [{"name": "arm", "type": "rigid", "mass": %.17g, "com": [%.17g, 0, 0],
              "inertia": [[%.17g, 0, 0], [0, %.17g, 0], [0, 0, %.17g]]}],
  "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "arm", "at": [0, 0, 0], "axis": [0, 0, 1]}],
  "solver": {"end": %.17g, "step": %.17g}
})",
                kM, kL, kI, kI, kI, t_end, h);
  const Model model = test::model_from(json);
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const Body& b = model.bodies[0];
  const Eigen::Vector3d r0 = data.state.q.segment<3>(b.offset);
  const Eigen::Matrix3d A = data.bodies[0].A;
  const Eigen::Vector3d u = (r0 + A * Eigen::Vector3d(kL, 0, 0)).normalized();  // hinge (origin) to the centre of mass
  Pull p;
  p.reaction = -joint_reaction(model, data, 0).head<3>().dot(u);
  const Eigen::VectorXd kept = data.reaction_lambda;
  data.reaction_lambda = data.state.lambda;
  p.newton = -joint_reaction(model, data, 0).head<3>().dot(u);
  data.reaction_lambda = kept;
  return p;
}

}  // namespace

// At t = 1 s (past the bottom, rising on the other side: a pull of 5.08 N), steps 4, 2 and 1 ms:
// the reaction's error falls as h^2 (measured 2.1e-3, 5.4e-4, 1.3e-4 N). The step's own
// multipliers (Newton's, which balance the accelerations before their projection) are first
// order (7.2e-2, 3.6e-2, 1.8e-2 N): the reaction adds the acceleration projection's kq sigma
// (FORMULATION.md 9, 13); printed, not asserted.
TEST(ReactionOrder, PendulumArmPullIsSecondOrder) {
  const double t = 1.0;
  const Eigen::Vector2d x = exact_swing(t);
  const double N = kM * (kG * std::cos(x(0)) + kL * x(1) * x(1));
  double e_prev = NAN, n_prev = NAN;
  for (const double h : {4e-3, 2e-3, 1e-3}) {
    const Pull p = runtime_pull(h, t);
    const double e = std::abs(p.reaction - N), en = std::abs(p.newton - N);
    std::printf("h = %g s: pull %.10f N (exact %.10f): reaction error %.3e (ratio %.2f), step multipliers' error %.3e (ratio %.2f)\n",
                h, p.reaction, N, e, e_prev / e, en, n_prev / en);
    if (!std::isnan(e_prev)) {
      EXPECT_GT(e_prev / e, 3.5);  // second order: 4 a halving
    }
    e_prev = e;
    n_prev = en;
  }
  EXPECT_LT(e_prev, 1e-3 * N);
}
