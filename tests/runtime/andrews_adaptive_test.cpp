// Adaptive steps on Andrews' squeezing mechanism (andrews_model.hpp) against the IVP Test Set's
// published reference at t = 0.03 (F. Mazzia, C. Magherini, Test Set for IVP Solvers, release
// 2.3, problem "andrews"; E. Hairer & G. Wanner, Solving ODEs II, VII.7): the error at the end
// within the bound the tolerance's definition gives, falling in proportion to rtol, in fewer
// steps than the fixed step that reaches the same error.
//
// The definition (error per unit step, FORMULATION.md section 9): each coordinate's local
// errors over the run add up to at most atol + rtol |q| (in metres: frame vectors times the
// model length L). The error at the end is then at most that sum times the mechanism's own
// amplification G of an error made along the way, G measured here independently of the
// controller (amplification below). In angles (a frame vector's component moves by the angle):
// at most G rtol (1 + s) with s = max |q| in those units over L (atol is rtol L by default).
#include "andrews_model.hpp"
#include "support.hpp"

#include "ffr/runtime/step_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace ffr::runtime;

namespace {

constexpr double kEnd = 0.03;

struct Outcome {
  double error;  ///< largest angle error at t = 0.03 [rad]
  std::int64_t steps;
};

double angle_error(const Model& model, const Data& data, const double* reference = test::kAndrewsReference) {
  double worst = 0;
  for (int j = 0; j < 7; ++j) {
    // Joints of the outputs, in the order of the reference (andrews_model.hpp).
    const int joint = model.outputs[static_cast<std::size_t>(j)].joint;
    const double angle = test::kAndrewsInitial[j] + joint_coordinate(model, data, joint, JointCoordinate::Angle);
    worst = std::max(worst, std::abs(angle - reference[j]));
  }
  return worst;
}

Model fixed_model(double h) {
  char solver[96];
  std::snprintf(solver, sizeof solver, R"({"end": 0.03, "step": %.17g})", h);
  return test::model_from(test::andrews_json(solver));
}

Outcome fixed(double h) {
  const Model model = fixed_model(h);
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  return {angle_error(model, data), step_count(model)};
}

// The Test Set asks for the state at t = 0.03: one output interval, the whole run.
Outcome adaptive(double rtol, const char* scheme = "") {
  char solver[200];
  std::snprintf(solver, sizeof solver, R"({"end": 0.03, "step": "auto", "rtol": %.17g, "output_interval": 0.03%s})", rtol, scheme);
  const Model model = test::model_from(test::andrews_json(solver));
  Data data(model);
  initialize(model, data);
  StepControl control(model, data);
  for (std::int64_t k = 1; k <= output_count(model); ++k) advance_to(model, data, control, output_time(model, k));
  std::printf("andrews rtol %.0e%s: %lld accepted, %lld rejected, %lld Newton failures\n", rtol, scheme,
              static_cast<long long>(control.accepted), static_cast<long long>(control.rejected),
              static_cast<long long>(control.newton_failures));
  return {angle_error(model, data), control.accepted + control.rejected + control.newton_failures};
}

// Largest difference of the integrated bodies' coordinates in the controller's units over L
// (positions / L, frame vectors as they are).
double coordinate_gap(const Model& model, const VectorXd& a, const VectorXd& b) {
  double worst = 0;
  for (const Body& body : model.bodies) {
    for (int i = 0; i < 12; ++i) {
      const double unit = i < 3 ? 1.0 / model.length : 1.0;
      worst = std::max(worst, std::abs(a(body.offset + i) - b(body.offset + i)) * unit);
    }
  }
  return worst;
}

struct Amplification {
  double G = 0;      ///< mean over the run of the end error per unit error made at a time
  double scale = 0;  ///< s: largest |q| in the controller's units over L at the branch points
};

// The mechanism's amplification of an error made at time s, independent of the controller: the
// fixed-step solution (h = 1e-5) is branched at s, one branch taking the next step as two of
// h/2; the two then differ by about that step's local error, in the direction local errors
// take. Both go on with h to t = 0.03; G(s) = (largest angle difference at the end) / (largest
// coordinate difference after the branching step). Error per unit step spreads the tolerance
// evenly over the run, so the end error is at most the tolerance times the mean of G(s) over
// the run: sampled at the middles of ten equal intervals.
Amplification measure_amplification() {
  const double h = 2e-5;
  const Model model = fixed_model(h);
  Amplification out;
  const std::int64_t n = step_count(model);
  constexpr int kPoints = 10;
  for (int k = 0; k < kPoints; ++k) {
    const std::int64_t branch = (2 * k + 1) * n / (2 * kPoints);
    Data a(model);
    initialize(model, a);
    for (std::int64_t i = 0; i < branch; ++i) step(model, a);
    Data b = a;
    for (const Body& body : model.bodies) {
      for (int i = 0; i < 12; ++i) out.scale = std::max(out.scale, std::abs(a.state.q(body.offset + i)) * (i < 3 ? 1.0 / model.length : 1.0));
    }
    step(model, a, h);
    step(model, b, 0.5 * h);
    step(model, b, 0.5 * h);
    const double made = coordinate_gap(model, a.state.q, b.state.q);
    for (std::int64_t i = branch + 1; i < n; ++i) {
      step(model, a, h);
      step(model, b, h);
    }
    double end_reference[7];
    for (int j = 0; j < 7; ++j) {
      const int joint = model.outputs[static_cast<std::size_t>(j)].joint;
      end_reference[j] = test::kAndrewsInitial[j] + joint_coordinate(model, b, joint, JointCoordinate::Angle);
    }
    const double G = angle_error(model, a, end_reference) / made;
    std::printf("error made at t = %.4f s: %.2e; at the end %.2e (G = %.2f)\n", static_cast<double>(branch) * h, made,
                angle_error(model, a, end_reference), G);
    out.G += G / kPoints;
  }
  return out;
}

const Amplification& amplification() {
  static const Amplification amp = measure_amplification();
  return amp;
}

}  // namespace

TEST(Andrews, GeometryClosesAndFixedStepsConvergeToTheReference) {
  EXPECT_LT(test::andrews_closure_gap(), 1e-12);  // the geometry read from the test set is one mechanism
  const Outcome a = fixed(2e-5), b = fixed(1e-5);
  std::printf("fixed steps: error %.3e at h = 2e-5, %.3e at 1e-5 (ratio %.2f)\n", a.error, b.error, a.error / b.error);
  EXPECT_LT(b.error, 1e-3);
  EXPECT_NEAR(a.error / b.error, 4.0, 0.6);  // second order towards the published solution
}

TEST(Andrews, AdaptiveStepsWithinToleranceInFewerStepsThanAFixedStep) {
  const Amplification& amp = amplification();
  std::printf("amplification G = %.2f, scale s = %.2f: the bound is %.2f rtol\n", amp.G, amp.scale, amp.G * (1 + amp.scale));
  ASSERT_GT(amp.G, 0.0);
  double previous = 0;
  for (const double rtol : {1e-4, 1e-5, 1e-6}) {
    const Outcome a = adaptive(rtol);
    Outcome f{};
    double h = 1e-4;
    for (; h > 1e-7; h *= 0.5) {
      f = fixed(h);
      if (f.error <= a.error) break;
    }
    std::printf("rtol %.0e: error %.2e rad (%.2f rtol) in %lld adaptive steps (rejected ones included); a fixed step needs h = %.3g s (%lld steps, error %.2e)\n",
                rtol, a.error, a.error / rtol, static_cast<long long>(a.steps), h, static_cast<long long>(f.steps), f.error);
    EXPECT_LT(a.error, amp.G * (1 + amp.scale) * rtol);
    EXPECT_LE(f.error, a.error);
    EXPECT_LT(a.steps, f.steps);
    // In proportion to rtol: a tenth of the tolerance, a tenth of the error (within a factor 1.5
    // either way: the end error is a sum of signed contributions, not their bound).
    if (previous > 0) {
      EXPECT_GT(a.error, previous / 15);
      EXPECT_LT(a.error, previous / (10 / 1.5));
    }
    previous = a.error;
  }
}

// The same definition and bound with generalized-alpha (the amplification is the mechanism's).
TEST(Andrews, GeneralizedAlphaAdaptiveStepsWithinTolerance) {
  const Amplification& amp = amplification();
  for (const double rtol : {1e-4, 1e-5}) {
    const Outcome a = adaptive(rtol, R"(, "integrator": "generalized_alpha", "spectral_radius": 0.8)");
    std::printf("generalized-alpha 0.8, rtol %.0e: error %.2e rad (%.2f rtol) in %lld steps\n", rtol, a.error, a.error / rtol,
                static_cast<long long>(a.steps));
    EXPECT_LT(a.error, amp.G * (1 + amp.scale) * rtol);
  }
}
