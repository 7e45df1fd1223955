// Adaptive steps on Andrews' squeezing mechanism (andrews_model.hpp) against the IVP Test Set's
// published reference at t = 0.03 (F. Mazzia, C. Magherini, Test Set for IVP Solvers, release
// 2.3, problem "andrews"; E. Hairer & G. Wanner, Solving ODEs II, VII.7): within the requested
// tolerance, in fewer steps than the fixed step that reaches the same error.
#include "andrews_model.hpp"
#include "support.hpp"

#include "ffr/runtime/step_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace ffr::runtime;

namespace {

struct Outcome {
  double error;  ///< largest angle error at t = 0.03 [rad]
  std::int64_t steps;
};

double angle_error(const Model& model, Data& data) {
  double worst = 0;
  for (int j = 0; j < 7; ++j) {
    // Joints of the outputs, in the order of the reference (andrews_model.hpp).
    const int joint = model.outputs[static_cast<std::size_t>(j)].joint;
    const double angle = test::kAndrewsInitial[j] + joint_coordinate(model, data, joint, JointCoordinate::Angle);
    worst = std::max(worst, std::abs(angle - test::kAndrewsReference[j]));
  }
  return worst;
}

Outcome fixed(double h) {
  char solver[96];
  std::snprintf(solver, sizeof solver, R"({"end": 0.03, "step": %.17g})", h);
  const Model model = test::model_from(test::andrews_json(solver));
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  return {angle_error(model, data), step_count(model)};
}

Outcome adaptive(double rtol, const char* scheme = "") {
  char solver[200];
  std::snprintf(solver, sizeof solver, R"({"end": 0.03, "step": "auto", "rtol": %.17g, "output_interval": 0.003%s})", rtol, scheme);
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

}  // namespace

TEST(Andrews, GeometryClosesAndFixedStepsConvergeToTheReference) {
  EXPECT_LT(test::andrews_closure_gap(), 1e-12);  // the geometry read from the test set is one mechanism
  const Outcome a = fixed(2e-5), b = fixed(1e-5);
  std::printf("fixed steps: error %.3e at h = 2e-5, %.3e at 1e-5 (ratio %.2f)\n", a.error, b.error, a.error / b.error);
  EXPECT_LT(b.error, 1e-3);
  EXPECT_NEAR(a.error / b.error, 4.0, 0.6);  // second order towards the published solution
}

// rtol bounds each step's local error; the error at t = 0.03 is its accumulation over a run in
// which beta turns by 15.9 rad (measured: 1.9e-2 and 3.0e-3 rad at rtol 1e-5 and 1e-6, falling
// like rtol^(2/3) as a second-order scheme under local error control does).
TEST(Andrews, AdaptiveStepsWithinToleranceInFewerStepsThanAFixedStep) {
  double previous = 0;
  for (const double rtol : {1e-5, 1e-6}) {
    const Outcome a = adaptive(rtol);
    Outcome f{};
    double h = 1e-4;
    for (; h > 1e-7; h *= 0.5) {
      f = fixed(h);
      if (f.error <= a.error) break;
    }
    std::printf("rtol %.0e: error %.2e rad in %lld adaptive steps (rejected ones included); a fixed step needs h = %.3g s (%lld steps, error %.2e)\n",
                rtol, a.error, static_cast<long long>(a.steps), h, static_cast<long long>(f.steps), f.error);
    EXPECT_LT(a.error, 2e3 * rtol);
    EXPECT_LE(f.error, a.error);
    EXPECT_LT(a.steps, f.steps);
    if (previous > 0) EXPECT_LT(a.error, previous / 4);
    previous = a.error;
  }
}

TEST(Andrews, GeneralizedAlphaAdaptiveStepsReachTheReference) {
  const Outcome a = adaptive(1e-6, R"(, "integrator": "generalized_alpha", "spectral_radius": 0.8)");
  std::printf("generalized-alpha 0.8, rtol 1e-6: error %.2e rad in %lld steps\n", a.error, static_cast<long long>(a.steps));
  EXPECT_LT(a.error, 1e-2);
}
