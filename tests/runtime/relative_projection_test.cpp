// The relative formulation's projections (relative/projection.cpp) where their passes crawl:
// the benchmark's slider-crank (tools/bench/formulations, crank driven at 150 rad/s) whose rod is
// the consistent-mass rod of 34 points with 30 modes. The planar mechanism modelled in 3-D holds
// the rod's out-of-plane rotations at both of its nodes, which its stiff torsion and out-of-plane
// modes alone can tell apart: the kept rows are nearly redundant, the passes shrink the residual
// slowly along them, and the velocity projection used to stop at its pass limit at
// t = 0.03 ... 0.07 s (h = 1 ms, both inertia routes).
//
// No outside reference for this motion: the absolute formulation, whose projections solve the
// same case directly (projection.cpp, exact_multipliers.cpp), is the reference, as in
// relative_formulation_test.cpp. The two are two discretisations of the same equations: at the
// same step they differ by the integrator's error, which shrinks as h^2 (the trapezoidal rule).
// The relative steps, direct projections included, allocate nothing (counting_new.cpp).
#include "fe_bodies.hpp"
#include "models.hpp"
#include "support.hpp"

#include "formulation_models.hpp"  // tools/bench/formulations

#include "ffr/formats/sid_io.hpp"
#include "ffr/runtime/relative.hpp"

#include "counting_new.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

struct CrankRun {
  Eigen::MatrixXd slider;  ///< per step: the slider's x [m] and the rod's first modal coordinate
  double worst_velocity_violation = 0, worst_acceleration_violation = 0;
  long allocations = 0;  ///< in the steps after the first
};

CrankRun run(const std::filesystem::path& dir, double h, double end, const char* formulation) {
  const Model model = test::model_from(formulations::with_formulation(bench::slider_crank_json("rod.sid.h5", h, end, 150.0), formulation), dir);
  if (std::string(formulation) == "relative") {
    EXPECT_TRUE(model.relative && model.relative->bodies[1].point);
    EXPECT_EQ(model.bodies[1].nq, 30);
  }
  Data data(model);
  initialize(model, data);
  const auto n = step_count(model);
  CrankRun r;
  r.slider.resize(n, 2);
  const Body& rod = model.bodies[1];
  const Body& slider = model.bodies[2];
  long before = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    if (i == 1) before = counted_allocations();  // (the first step takes the coordinates from the initialized state)
    step(model, data);
    r.slider(i, 0) = data.state.q(slider.offset);
    r.slider(i, 1) = data.state.q(rod.offset + 12);
    r.worst_velocity_violation = std::max(r.worst_velocity_violation, data.stats.last_velocity_violation);
    r.worst_acceleration_violation = std::max(r.worst_acceleration_violation, data.stats.last_acceleration_violation);
  }
  r.allocations = counted_allocations() - before;
  return r;
}

TEST(RelativeProjection, ThirtyModeSliderCrankMatchesAbsolute) {
  test::TempDir dir("relative_projection");
  ffr::formats::write_sid(bench::consistent_rod(bench::rod_params(34, 30)).sid, dir / "rod.sid.h5");
  const double end = 0.1;  // past the failures at 0.03 ... 0.07 s
  double dx[2], dy[2];
  int i = 0;
  for (const double h : {1e-3, 2.5e-4}) {
    const CrankRun a = run(dir.path, h, end, "absolute"), r = run(dir.path, h, end, "relative");
    EXPECT_LT(r.worst_velocity_violation, 1e-12);
    EXPECT_LT(r.worst_acceleration_violation, 1e-12);
    EXPECT_EQ(r.allocations, 0);
    dx[i] = (a.slider.col(0) - r.slider.col(0)).cwiseAbs().maxCoeff();
    dy[i] = (a.slider.col(1) - r.slider.col(1)).cwiseAbs().maxCoeff() / a.slider.col(1).cwiseAbs().maxCoeff();
    std::printf("30-mode slider-crank h = %g: worst |x_slider absolute - relative| %.3e m, first modal coordinate apart by %.2e of its "
                "largest; projections' worst residuals %.1e (velocity), %.1e (acceleration)\n",
                h, dx[i], dy[i], r.worst_velocity_violation, r.worst_acceleration_violation);
    ++i;
  }
  // The slider travels 0.3 m; the discretisations' difference shrinks with the step, by at
  // least a quarter of the h^2 rate over the factor 4 (not monotonically in between: at
  // h = 0.5 ms the slider's is 2.1e-6 m, the modal one 1.8e-2; the highest modes, omega h > 1,
  // are resolved at neither end).
  EXPECT_LT(dx[1], 1e-6);
  EXPECT_LT(dx[1], 0.25 * dx[0]);
  EXPECT_LT(dy[1], 0.25 * dy[0]);
  EXPECT_LT(dy[1], 1e-2);
}

// Newton's iterations on the same mechanism (relative/step.cpp, exact_direction): past
// t = 0.1 s the slow direction was Newton's own. Its passes act only on a linearised violation
// above the tolerance; along the nearly redundant rows a violation below it still moved s by
// more than Newton's tolerance, shrinking by 0.96 to 0.99 an iteration, and the relative steps
// stopped after 30 iterations: at t = 0.141 s with this 102-DOF rod and at 0.145 to 0.173 s with
// the 1002-DOF one (h = 1 ms, the benchmark's 0.2 s). With the multipliers solved for at once
// when the tangent refreshes are spent, both run to the end. Over 0.2 s the slider's own
// discretisation error does not shrink as h^2 at these steps (the highest modes, omega h > 1,
// keep ringing under the trapezoidal rule: the absolute runs at 1, 0.5, 0.25, 0.125 and
// 0.0625 ms differ by 1e-5 to 3e-5 m), so the check is that the formulations agree far within
// it: their difference under a tenth of the absolute run's change from h = 1 ms to 0.25 ms,
// and the rod's first modal coordinate, which does converge, closer by a factor 4 at the
// smaller step.
TEST(RelativeNewton, ThirtyModeSliderCrankRunsPastTheStall) {
  for (const int points : {34, 334}) {
    test::TempDir dir("relative_newton");
    ffr::formats::write_sid(bench::consistent_rod(bench::rod_params(points, 30)).sid, dir / "rod.sid.h5");
    const double end = 0.2, h = 1e-3;
    const CrankRun a1 = run(dir.path, h, end, "absolute"), r1 = run(dir.path, h, end, "relative");
    const CrankRun a4 = run(dir.path, h / 4, end, "absolute"), r4 = run(dir.path, h / 4, end, "relative");
    EXPECT_EQ(r1.allocations, 0);
    EXPECT_EQ(r4.allocations, 0);
    double own = 0;  // the absolute run's change in the slider's x from h to h / 4, at h's steps
    for (Eigen::Index k = 0; k < a1.slider.rows(); ++k) own = std::max(own, std::abs(a1.slider(k, 0) - a4.slider(4 * k + 3, 0)));
    const double dx1 = (a1.slider.col(0) - r1.slider.col(0)).cwiseAbs().maxCoeff();
    const double dx4 = (a4.slider.col(0) - r4.slider.col(0)).cwiseAbs().maxCoeff();
    const double dy1 = (a1.slider.col(1) - r1.slider.col(1)).cwiseAbs().maxCoeff() / a1.slider.col(1).cwiseAbs().maxCoeff();
    const double dy4 = (a4.slider.col(1) - r4.slider.col(1)).cwiseAbs().maxCoeff() / a4.slider.col(1).cwiseAbs().maxCoeff();
    std::printf("30-mode slider-crank, rod of %d DOF, to %g s: |x_slider absolute - relative| %.2e m (h = 1 ms), %.2e m (0.25 ms), "
                "the absolute's change between the two steps %.2e m; first modal coordinate apart by %.2e, %.2e of its largest\n",
                3 * points, end, dx1, dx4, own, dy1, dy4);
    EXPECT_LT(dx1, 0.1 * own);
    EXPECT_LT(dx4, 0.1 * own);
    EXPECT_LT(dy4, 0.25 * dy1);
    EXPECT_LT(dy4, 1e-2);
  }
}

}  // namespace
