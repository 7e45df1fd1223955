// Adaptive steps ("step": "auto", step_control.cpp):
// - the flexible slider-crank of the IVP Test Set (B. Simeon 1996; F. Mazzia, C. Magherini,
//   F. Iavernaro, Test Set for IVP Solvers, release 2.3, problem "Slider crank", published
//   reference at t = 0.1, as in slider_crank_test.cpp) within the requested tolerance, with fewer
//   steps than the fixed step that reaches the same error;
// - a compound pendulum against the independent oracle of generalized_alpha_test.cpp (its
//   one-degree-of-freedom equation by RK4), trapezoidal and generalized-alpha;
// - a step whose Newton fails is halved and retried; one that cannot be taken names the time;
// - the outputs are at the requested times;
// - the settings' bad values are refused with the file and field.
#include "simeon_crank.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "models.hpp"  // tools/models: the benchmark's slider-crank

#include "ffr/runtime/step_control.hpp"
#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

// The Test Set's slider-crank with its initial values (simeon_crank.hpp).
std::string crank_json(double h) { return test::simeon_crank_json(h); }

struct CrankState {
  double q1, q2;  ///< the rod's lateral modal coordinates: q1 is its midpoint deflection [m]
  std::int64_t steps;
};

// Test Set reference at t = 0.1.
constexpr double kRefQ1 = 0.1893192899613509e-3, kRefQ2 = 0.2375751249879174e-4;

CrankState crank_state(const Model& model, const Data& data, std::int64_t steps) {
  const int o = model.bodies[1].offset + 12;
  return {data.state.q(o), data.state.q(o + 1), steps};
}

CrankState crank_fixed(const test::TempDir& dir, double h) {
  const Model model = test::model_from(crank_json(h), dir.path);
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  return crank_state(model, data, step_count(model));
}

Model adaptive(Model m, double rtol, double atol, double output_interval) {
  m.settings.adaptive = true;
  m.settings.rtol = rtol;
  m.settings.atol = atol;
  m.settings.output_interval = output_interval;
  m.settings.step = 1e-2 * output_interval;
  return m;
}

CrankState crank_adaptive(const test::TempDir& dir, double rtol, double atol) {
  const Model model = adaptive(test::model_from(crank_json(1e-3), dir.path), rtol, atol, 0.01);
  Data data(model);
  initialize(model, data);
  StepControl control(model, data);
  for (std::int64_t k = 1; k <= output_count(model); ++k) {
    advance_to(model, data, control, output_time(model, k));
    EXPECT_EQ(data.state.t, output_time(model, k));  // the steps land on the output times
  }
  std::printf("rtol %.0e: %lld steps accepted, %lld rejected, %lld Newton failures\n", rtol,
              static_cast<long long>(control.accepted), static_cast<long long>(control.rejected),
              static_cast<long long>(control.newton_failures));
  // Every step taken counts, the rejected ones too.
  return crank_state(model, data, control.accepted + control.rejected + control.newton_failures);
}

// The compound pendulum of support.hpp and its oracle.
double pendulum_oracle(double end) { return test::compound_pendulum_oracle(end); }

std::string pendulum_json(const std::string& extra) {
  return test::compound_pendulum_json(R"({"end": 1.0, "step": "auto", "rtol": 1e-6, "atol": 1e-7, "output_interval": 0.05)" + extra + "}");
}

std::string model_error(const std::string& json) {
  try {
    test::model_from(json);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

// The crank is driven, so the crank and slider follow its rigid kinematics to within the rod's
// deformation; what the integrator has to get right is the rod's vibration. The errors are those
// of its lateral modes (q1 is the midpoint deflection, 0.19 mm at t = 0.1), measured against this
// model's own converged solution, Richardson-extrapolated from fixed steps of 10 and 5 us,
// which is itself checked against the Test Set's published values (to the 3e-4 and 1e-3 of
// slider_crank_test.cpp). The tolerance's definition (error per unit step, FORMULATION.md
// section 9) sums each coordinate's local errors over the run to at most atol + rtol |q|, a
// modal amplitude measured as the displacement L / y_scale times it: in the amplitude's own
// units at most rtol y_scale (1 + max |y| / y_scale) with the default atol = rtol L. The rod's
// vibration, driven and lightly damped, does not amplify errors: the end error is within that.
TEST(AdaptiveSteps, SliderCrankWithinToleranceInFewerStepsThanAFixedStep) {
  test::TempDir dir("adaptive_crank");
  test::write_sid_file(test::simeon_rod_sid(), dir / "rod.sid.h5");
  const CrankState c2 = crank_fixed(dir, 1e-5), c1 = crank_fixed(dir, 5e-6);
  const double ref1 = (4 * c1.q1 - c2.q1) / 3, ref2 = (4 * c1.q2 - c2.q2) / 3;
  std::printf("Richardson reference: q1 %.9e (test set %.9e), q2 %.9e (test set %.9e); fixed 5 us off by %.1e, %.1e\n", ref1,
              kRefQ1, ref2, kRefQ2, c1.q1 - ref1, c1.q2 - ref2);
  EXPECT_NEAR(ref1 / kRefQ1, 1.0, 3e-4);
  EXPECT_NEAR(ref2 / kRefQ2, 1.0, 1e-3);
  const Model probe = test::model_from(crank_json(1e-3), dir.path);
  const Body& rod = probe.bodies[1];
  const auto error = [&](const CrankState& s) {
    return std::max(std::abs(s.q1 - ref1) / rod.y_scale(0), std::abs(s.q2 - ref2) / rod.y_scale(1));
  };
  const double size = std::max(std::abs(ref1) / rod.y_scale(0), std::abs(ref2) / rod.y_scale(1));
  double previous = 0;
  for (const double rtol : {1e-5, 1e-6, 1e-7}) {
    const CrankState a = crank_adaptive(dir, rtol, -1);  // atol: the default, rtol times the model length
    // The fixed step that reaches the same error: halved from 0.5 ms until it does.
    CrankState f{};
    double h = 5e-4;
    for (; h > 1e-6; h *= 0.5) {
      f = crank_fixed(dir, h);
      if (error(f) <= error(a)) break;
    }
    std::printf("rtol %.0e: error %.2e y_scale (%.2f rtol) in %lld adaptive steps (rejected ones included); a fixed step needs h = %.3g s (%lld steps, error %.2e)\n",
                rtol, error(a), error(a) / rtol, static_cast<long long>(a.steps), h, static_cast<long long>(f.steps), error(f));
    EXPECT_LT(error(a), rtol * (1 + size));
    EXPECT_LE(error(f), error(a));
    // The crank turns at a constant rate: the rod's demand on the step is nearly uniform, and the
    // adaptive steps gain over the halved fixed step only what the halving overshoots.
    EXPECT_LT(a.steps, f.steps);
    if (previous > 0) {
      EXPECT_GT(error(a), previous / 15);
      EXPECT_LT(error(a), previous / (10 / 1.5));
    }
    previous = error(a);
  }
}

TEST(AdaptiveSteps, PendulumAgainstTheOracleForBothSchemes) {
  const double ref = pendulum_oracle(1.0);
  for (const std::string& extra : {std::string(), std::string(R"(, "integrator": "generalized_alpha", "spectral_radius": 0.5)")}) {
    const Model model = test::model_from(pendulum_json(extra));
    Data data(model);
    initialize(model, data);
    StepControl control(model, data);
    advance_to(model, data, control, model.settings.end);
    const double err = std::abs(joint_coordinate(model, data, 0, JointCoordinate::Angle) - ref);
    std::printf("pendulum%s: angle error %.2e after %lld steps (%lld rejected)\n", extra.empty() ? " (trapezoidal)" : " (generalized-alpha 0.5)",
                err, static_cast<long long>(control.accepted), static_cast<long long>(control.rejected));
    EXPECT_LT(err, 1e-4);  // measured 1.1e-7 and 1.4e-7 at rtol 1e-6, atol 1e-7 (error per unit step)
    EXPECT_EQ(data.state.t, 1.0);
  }
}

// With max_iterations 2 a long first step cannot converge (a pendulum released from rest
// swinging by 0.3 rad in its first step): the step is halved until Newton converges, and the
// result is still the oracle's.
TEST(AdaptiveSteps, NewtonFailureHalvesTheStep) {
  const Model model = test::model_from(pendulum_json(R"(, "max_iterations": 2)"));
  Data data(model);
  initialize(model, data);
  StepControl control(model, data);
  control.h_next = 0.25;
  advance_to(model, data, control, model.settings.end);
  const double err = std::abs(joint_coordinate(model, data, 0, JointCoordinate::Angle) - pendulum_oracle(1.0));
  std::printf("%lld Newton failures, %lld rejected, %lld accepted; angle error %.2e\n", static_cast<long long>(control.newton_failures),
              static_cast<long long>(control.rejected), static_cast<long long>(control.accepted), err);
  EXPECT_GT(control.newton_failures, 0);
  EXPECT_LT(err, 1e-4);
}

// Two drives of the crank at odds (a second hub joint whose motion a C-API input holds while
// the first turns the crank, as in driven_bodies_test.cpp): no step can be taken, the step is
// halved down to the minimum, and the error names the time and the cause.
TEST(AdaptiveSteps, AStepThatCannotBeTakenNamesTheTime) {
  test::TempDir dir("adaptive_disagree");
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 4));
  test::write_sid_file(chain.sid, dir / "rod.sid.h5");
  std::string json = bench::slider_crank_json("rod.sid.h5", 1e-3, 0.05, 20.0);
  json.insert(json.find("\"joints\": [") + 11, R"({"name": "hub2", "type": "revolute", "body1": "ground", "body2": "crank", "at": [0, 0, 0], "axis": [0, 0, 1]},)");
  json.insert(json.find("\"motions\": [") + 12, R"({"joint": "hub2", "table": {"t": [0, 1], "value": [0, 20]}},)");
  const Model model = adaptive(test::model_from(json, dir.path), 1e-6, -1, 0.01);
  Data data(model);
  initialize(model, data);
  StepControl control(model, data);
  advance_to(model, data, control, 0.01);  // the two agree
  data.motion_external[0] = 1;  // hub2 held from here on
  data.motion_value[0] = Eigen::Vector3d(20.0 * data.state.t, 0, 0);
  try {
    advance_to(model, data, control, 0.02);
    FAIL() << "two drives at odds ran on";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    std::printf("%s\n", msg.c_str());
    EXPECT_NE(msg.find("fell below the minimum"), std::string::npos) << msg;
    EXPECT_NE(msg.find("t = 0.01 s"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Newton did not converge"), std::string::npos) << msg;  // the cause named
    EXPECT_NEAR(data.state.t, 0.01, 1e-9);  // the last accepted state (steps below 1e-11 s still passed)
  }
}

TEST(AdaptiveSteps, SimulateRecordsTheRequestedTimes) {
  const Model model = test::model_from(pendulum_json(""));
  Data data(model);
  initialize(model, data);
  Recorder rec(model, step_count(model) + 2);
  const RunInfo info = simulate(model, data, rec);
  ASSERT_EQ(rec.rows(), 21);
  for (std::int64_t k = 0; k < 21; ++k) EXPECT_NEAR(rec.times()(k), 0.05 * static_cast<double>(k), 1e-15) << k;
  EXPECT_GT(info.steps, 20);
}

TEST(AdaptiveSteps, BadSettingsAreRefusedWithTheField) {
  const auto refused = [](const std::string& solver, const std::string& field, const std::string& what) {
    const std::string json = std::string(R"({"bodies": [{"name": "b", "type": "rigid", "mass": 1, "inertia": [[1,0,0],[0,1,0],[0,0,1]]}],
      "solver": )") + solver + "}";
    const std::string msg = model_error(json);
    EXPECT_NE(msg.find("solver" + field), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  };
  refused(R"({"end": 1, "step": 0.1, "integrator": "generalized_alpha", "spectral_radius": 1.5})", ".spectral_radius", "[0, 1]");
  refused(R"({"end": 1, "step": 0.1, "integrator": "generalized_alpha", "spectral_radius": -0.1})", ".spectral_radius", "[0, 1]");
  refused(R"({"end": 1, "step": 0.1, "integrator": "generalized_alpha"})", "", "spectral_radius");
  refused(R"({"end": 1, "step": 0.1, "spectral_radius": 0.5})", ".spectral_radius", "generalized_alpha");
  refused(R"({"end": 1, "step": 0.1, "integrator": "bdf"})", ".integrator", "unknown integrator");
  refused(R"({"end": 1, "step": "fast"})", ".step", "\"auto\"");
  refused(R"({"end": 1, "step": "auto", "rtol": -1e-6})", ".rtol", "positive");
  refused(R"({"end": 1, "step": "auto", "atol": 0})", ".atol", "positive");
  refused(R"({"end": 1, "step": "auto", "output_every": 2})", ".output_every", "output_interval");
  refused(R"({"end": 1, "step": "auto", "output_interval": 2})", ".output_interval", "longer than the run");
  refused(R"({"end": 1, "step": "auto", "rtl": 1e-6})", ".rtl", "unknown field");
  refused(R"({"end": 1, "step": 0.1, "rtol": 1e-6})", ".rtol", "\"auto\"");
}
