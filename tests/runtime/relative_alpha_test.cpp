// Generalized-alpha in the relative formulation ("formulation": "relative" with "integrator":
// "generalized_alpha"; relative/step.cpp), checked as the absolute step's scheme is
// (generalized_alpha_test.cpp):
// - second order for rho_inf = 0, 0.5, 0.9 on the compound pendulum (one joint angle) against the
//   independent oracle of support.hpp (its one-degree-of-freedom equation by classical RK4);
// - rho_inf = 1 gives the relative trapezoidal step's states (a pendulum chain of five links);
// - the numerical damping of one linear mode per step (a mass on a prismatic joint held by a
//   spring: one slide coordinate) against the amplification matrix of Chung & Hulbert
//   (alpha_amplification.hpp);
// - the four-bar (a loop: one cut joint, kept rows, projections) against the absolute
//   formulation's generalized-alpha at the same rho_inf: two second-order discretisations of the
//   same equations, so their difference falls as h^2.
#include "formulation_models.hpp"  // tools/bench/formulations
#include "alpha_amplification.hpp"
#include "support.hpp"

#include "ffr/runtime/relative.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

std::string alpha_keys(double rho) {
  char buf[96];
  std::snprintf(buf, sizeof buf, R"("integrator": "generalized_alpha", "spectral_radius": %.17g)", rho);
  return buf;
}

double pendulum_angle(double h, double end, double rho) {
  char buf[256];
  std::snprintf(buf, sizeof buf, R"({"formulation": "relative", "end": %.17g, "step": %.17g, "newton_tolerance": 1e-14, %s})", end, h,
                alpha_keys(rho).c_str());
  const Model model = test::model_from(test::compound_pendulum_json(buf));
  EXPECT_TRUE(model.relative);
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  return joint_coordinate(model, data, 0, JointCoordinate::Angle);
}

// The model text with generalized-alpha keys in its "solver" object.
std::string with_alpha(std::string json, double rho) {
  const std::string key = "\"solver\": {";
  json.insert(json.find(key) + key.size(), alpha_keys(rho) + ", ");
  return json;
}

}  // namespace

// (At 0.25 s: the angle's leading h^2 error changes sign near 1 s for these rho_inf in relative
// coordinates, where the next order would show instead.)
TEST(RelativeAlpha, SecondOrderForEverySpectralRadius) {
  const double end = 0.25;
  const double ref = test::compound_pendulum_oracle(end);
  for (const double rho : {0.0, 0.5, 0.9, 1.0}) {
    double e[3];
    const double hs[3] = {5e-4, 2.5e-4, 1.25e-4};
    for (int k = 0; k < 3; ++k) e[k] = std::abs(pendulum_angle(hs[k], end, rho) - ref);
    const double p1 = std::log2(e[0] / e[1]), p2 = std::log2(e[1] / e[2]);
    std::printf("relative, rho_inf %.1f: angle errors %.3e %.3e %.3e at h = 0.5, 0.25, 0.125 ms: orders %.3f %.3f\n", rho, e[0], e[1],
                e[2], p1, p2);
    EXPECT_NEAR(p1, 2.0, 0.25) << "rho_inf " << rho;
    EXPECT_NEAR(p2, 2.0, 0.25) << "rho_inf " << rho;
    EXPECT_LT(e[2], 1e-7);
  }
}

TEST(RelativeAlpha, SpectralRadiusOneIsTheTrapezoidalRule) {
  const std::string json = formulations::pendulum_chain_json(5, 1e-3, 0.5, "relative");
  Model trap = test::model_from(json);
  trap.settings.newton_tolerance = 1e-15;
  Model alpha = test::model_from(with_alpha(json, 1.0));
  alpha.settings.newton_tolerance = 1e-15;
  ASSERT_TRUE(trap.relative && alpha.relative);
  const test::SideBySide r = test::step_side_by_side(trap, alpha);
  std::printf("relative, rho_inf = 1 against the trapezoidal rule: states apart by %.2e at most (scaled; the motion %.2e)\n", r.apart,
              r.motion);
  EXPECT_GT(r.motion, 0.1);
  EXPECT_LT(r.apart, 1e-9);
}

// A 1 kg body on a prismatic joint along x, held by a spring along x (k = 1e4 N/m: omega = 100
// rad/s), released 0.1 m from the spring's rest length; its one relative coordinate is the slide
// (zero at the start). The spring's ground end is 1 km away, so that the overshoot of the first
// steps at omega h = 100 keeps it along +x (linear). After each step its state (d, v, a) written in the eigenvectors of Chung &
// Hulbert's amplification matrix must shrink by the matrix's eigenvalue of largest modulus.
TEST(RelativeAlpha, DampingOfOneModePerStepIsTheAnalyticAmplification) {
  const double omega = 100.0, d_start = 0.1;
  for (const double rho : {0.0, 0.5, 0.9}) {
    for (const double Omega : {0.5, 2.0, 100.0}) {
      const double h = Omega / omega;
      char buf[1024];
      std::snprintf(buf, sizeof buf, R"({
  "bodies": [{"name": "mass", "type": "rigid", "mass": 1.0, "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]], "position": [1.1, 0, 0]}],
  "joints": [{"name": "slide", "type": "prismatic", "body1": "ground", "body2": "mass", "at": [1.1, 0, 0], "axis": [1, 0, 0]}],
  "forces": [{"type": "spring_damper", "body1": "ground", "at1": [-1000, 0, 0], "body2": "mass", "at2": [1.1, 0, 0], "k": 1e4, "length0": 1001.0}],
  "solver": {"formulation": "relative", "end": %.17g, "step": %.17g, "newton_tolerance": 1e-11, %s}
})",
                    40 * h, h, alpha_keys(rho).c_str());
      const Model model = test::model_from(buf);
      ASSERT_TRUE(model.relative);
      ASSERT_EQ(model.relative->ns, 1);
      Data data(model);
      initialize(model, data);
      const RelativeWork& w = *data.relative;
      const test::ModeDecay m = test::measure_mode_decay(
          rho, omega, h, step_count(model), [&] { step(model, data); },
          [&] { return Eigen::Vector3cd(w.s(0) + d_start, w.sd(0), w.a(0)); });
      const double spectral = m.spectral, worst = m.worst;
      const int checked = m.checked;
      std::printf("relative, rho_inf %.1f, omega h %4.1f: spectral radius %.6f; the slide's component decays by it to %.1e in each of %d steps\n",
                  rho, Omega, spectral, worst, checked);
      EXPECT_GE(checked, 3);
      EXPECT_LT(worst, 1e-6) << "rho_inf " << rho << ", omega h " << Omega;
      if (Omega == 100.0) {
        EXPECT_NEAR(spectral, rho, 0.06);
      }
    }
  }
}

TEST(RelativeAlpha, FourBarAgreesWithTheAbsoluteFormulationToSecondOrder) {
  const double rho = 0.8, end = 0.5;
  double diff[2];
  const double hs[2] = {1e-3, 5e-4};
  for (int k = 0; k < 2; ++k) {
    const Model rel = test::model_from(with_alpha(formulations::four_bar::json(hs[k], end, "relative"), rho));
    const Model abs = test::model_from(with_alpha(formulations::four_bar::json(hs[k], end, "absolute"), rho));
    ASSERT_TRUE(rel.relative);
    ASSERT_FALSE(abs.relative);
    Data a(rel), b(abs);
    initialize(rel, a);
    initialize(abs, b);
    diff[k] = 0;
    for (std::int64_t i = 0; i < step_count(rel); ++i) {
      step(rel, a);
      step(abs, b);
      diff[k] = std::max(diff[k], std::abs(joint_coordinate(rel, a, 0, JointCoordinate::Angle) -
                                           joint_coordinate(abs, b, 0, JointCoordinate::Angle)));
    }
  }
  const double order = std::log2(diff[0] / diff[1]);
  std::printf("four-bar, rho_inf %.1f: crank angle relative - absolute at most %.3e, %.3e rad at h = 1, 0.5 ms: order %.2f\n", rho,
              diff[0], diff[1], order);
  EXPECT_LT(diff[1], 1e-4);
  EXPECT_GT(order, 1.7);
}

// A copied Data is a branch of the simulation: it carries the relative workspace's step state (the
// generalized-alpha pseudo-accelerations, the joint coordinates) as its own. Two copies stepped in
// turn must each follow the states of one copy stepped alone; a workspace shared between copies
// would mix their step states.
TEST(RelativeAlpha, CopiedDataStepsOnItsOwn) {
  Model model = test::model_from(with_alpha(formulations::pendulum_chain_json(5, 1e-3, 0.2, "relative"), 0.8));
  model.settings.newton_tolerance = 1e-14;
  ASSERT_TRUE(model.relative);
  Data start(model);
  initialize(model, start);
  for (int i = 0; i < 20; ++i) step(model, start);
  Data alone = start, x = start, y = start;
  ASSERT_NE(&*x.relative, &*start.relative);
  for (int i = 0; i < 20; ++i) step(model, alone);
  for (int i = 0; i < 20; ++i) {
    step(model, x);
    step(model, y);
  }
  EXPECT_GT(scaled_norm(model, alone.state.q - start.state.q), 1e-3);
  EXPECT_EQ(scaled_norm(model, x.state.q - alone.state.q), 0.0);
  EXPECT_EQ(scaled_norm(model, y.state.q - alone.state.q), 0.0);
}
