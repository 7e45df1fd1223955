// The relative step's tangent (FORMULATION.md 18) against central differences of its own
// residual, Newton's iterations with and without the derivatives of R = dq/ds, and the motion
// they leave unchanged.
//
// Reference: the residual f(s) = kq R^T [M q_ddot - Q + Phi_q^T (lambda + alpha Phi)] of
// relative_step with s_dot, s_ddot affine in s through the scheme (relative_residual, the
// multipliers fixed), differenced in s: an oracle that needs no derivative of the code. The
// tangent with R's derivatives must match it up to the absolute formulation's own tangent (the
// flexible bodies' blocks, FORMULATION.md 9, which are not this test's subject), and Newton
// from the step's predictor must then converge quadratically.
#include "formulation_models.hpp"  // tools/bench/formulations
#include "models.hpp"               // tools/models
#include "relative_rod_rotor.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/formats/sid_io.hpp"
#include "ffr/runtime/relative.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

struct TangentCheck {
  double err = 0, err_old = 0;             ///< |T - J| / |J| (diagonally scaled), with and without R's derivatives
  double rate = 0, rate_old = 0;           ///< Newton's contraction at its last increment above rounding
  int iterations = 0, iterations_old = 0;  ///< Newton iterations to a scaled increment below 1e-12
};

double scaled_size(const RelativeWork& w, const Eigen::VectorXd& ds) { return ds.cwiseAbs().cwiseProduct(w.weight).maxCoeff(); }

// Newton on f(s) = 0 at fixed multipliers (the tangent rebuilt at every iterate): the scaled
// increments; the last iterate is left in w.s.
std::vector<double> newton(const Model& model, Data& data, double t1, bool exact, int iterations) {
  RelativeWork& w = *data.relative;
  w.exact_tangent = exact;
  std::vector<double> inc;
  for (int it = 0; it < iterations; ++it) {
    relative_residual(model, data, t1);
    relative_tangent(model, data, t1);
    const Eigen::VectorXd ds = w.Ts.partialPivLu().solve(w.f);
    w.s -= ds;
    inc.push_back(scaled_size(w, ds));
  }
  return inc;
}

// From copies of data (not advanced): Newton from the predictor of a step of h with and without
// R's derivatives; then near the solution (where f and the penalty forces are small, so that
// the differences are not lost to rounding) the tangent against central differences of f, the
// block of the relative coordinates [skip0, skip0 + nskip) with themselves left out.
TangentCheck check_tangent(const Model& model, const Data& data0, double h, int skip0 = 0, int nskip = 0) {
  TangentCheck c;
  for (const bool exact : {false, true}) {
    Data data = data0;
    relative_begin_step(model, data, h);
    const std::vector<double> inc = newton(model, data, data.state.t + h, exact, 8);
    int n = 0;
    while (n < static_cast<int>(inc.size()) && inc[static_cast<std::size_t>(n)] > 1e-12) ++n;
    double rate = 0;
    for (std::size_t i = 1; i < inc.size(); ++i)
      if (inc[i] > 1e-13) rate = inc[i] / inc[i - 1];
    (exact ? c.iterations : c.iterations_old) = n + 1;
    (exact ? c.rate : c.rate_old) = rate;
  }
  Data data = data0;
  relative_begin_step(model, data, h);
  const double t1 = data.state.t + h;
  newton(model, data, t1, true, 3);
  RelativeWork& w = *data.relative;
  const int ns = static_cast<int>(w.s.size());
  const Eigen::VectorXd s0 = w.s;
  Eigen::MatrixXd J(ns, ns);
  for (int j = 0; j < ns; ++j) {
    const double eps = 1e-6 / w.weight(j);
    w.s = s0;
    w.s(j) += eps;
    relative_residual(model, data, t1);
    const Eigen::VectorXd fp = w.f;
    w.s(j) = s0(j) - eps;
    relative_residual(model, data, t1);
    J.col(j) = (fp - w.f) / (2 * eps);
  }
  w.s = s0;
  relative_residual(model, data, t1);
  // Diagonal scaling (as the step factorises it), so that every coordinate counts alike.
  const Eigen::VectorXd d = J.diagonal().cwiseAbs().cwiseSqrt().cwiseInverse();
  Eigen::MatrixXd Js = d.asDiagonal() * J * d.asDiagonal();
  Js.block(skip0, skip0, nskip, nskip).setZero();
  for (const bool exact : {true, false}) {
    w.exact_tangent = exact;
    relative_tangent(model, data, t1);
    Eigen::MatrixXd Ts = d.asDiagonal() * w.Ts * d.asDiagonal();
    Ts.block(skip0, skip0, nskip, nskip).setZero();
    (exact ? c.err : c.err_old) = (Ts - Js).norm() / Js.norm();
  }
  return c;
}

// The housed rotor on Simeon's rod (relative_rod_rotor.hpp) spun up to `speed` rad/s over 0.05 s
// and held: Newton's iterations a step over the last 0.01 s of 0.06 s, and the tangent checked
// at the end (the rod's own block, the absolute formulation's flexible-body tangent, left out).
struct RotorRun {
  double iterations = 0;
  TangentCheck tangent;
};

RotorRun run_rotor(double h, double speed, bool exact, const std::filesystem::path& dir) {
  const Model model = test::model_from(test::rod_rotor_json(h, "relative", speed, 0.05, 0.06), dir);
  Data data(model);
  initialize(model, data);
  data.relative->exact_tangent = exact;
  const std::int64_t n = step_count(model), last = static_cast<std::int64_t>(std::llround(0.01 / h));
  std::int64_t it0 = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    if (i == n - last) it0 = data.stats.newton_iterations;
    step(model, data);
  }
  RotorRun r;
  r.iterations = static_cast<double>(data.stats.newton_iterations - it0) / static_cast<double>(last);
  const RelativeBody& rod = model.relative->bodies[0];
  r.tangent = check_tangent(model, data, h, rod.col0, rod.ncols);
  return r;
}

}  // namespace

// A planar chain of five rigid links falling from the horizontal (rates up to about 10 rad/s
// at 0.3 s): every term of the tangent is R's or the rigid bodies' exact one.
TEST(RelativeTangent, ChainAgainstCentralDifferences) {
  const double h = 1e-3;
  const Model model = test::model_from(formulations::pendulum_chain_json(5, h, 0.3, "relative"));
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const TangentCheck c = check_tangent(model, data, h);
  std::printf("chain: tangent error %.2e (without R's derivatives %.2e); Newton %d iterations, last rate %.2e (%d, %.2e)\n", c.err,
              c.err_old, c.iterations, c.rate, c.iterations_old, c.rate_old);
  // Measured: 4.1e-10 against 3.1e-3 without; Newton 3 iterations (rate 2.5e-5, quadratic)
  // against 5 (rate 3.5e-2, linear).
  EXPECT_LT(c.err, 1e-8);
  EXPECT_GT(c.err_old, 1e-4);
  EXPECT_LT(c.iterations, c.iterations_old);
  EXPECT_LT(c.rate, 1e-3);
}

// The rotor at 1000 and 2000 rad/s in its housing on the rod's tip node, h = 0.25, 0.5 and 1 ms:
// the gyroscopic coupling of the spin into the housing's frame (R_dot, relative size h Omega)
// and the curvature terms (h^2 Omega^2 / 4).
TEST(RelativeTangent, HousedRotorOnAFlexibleNode) {
  test::TempDir dir("relative_tangent_rotor");
  test::write_sid_file(test::rod_with_tip_rotations(), dir / "rod.sid.h5");
  for (const double h : {2.5e-4, 5e-4, 1e-3}) {
    for (const double speed : {1000.0, 2000.0}) {
      const RotorRun a = run_rotor(h, speed, true, dir.path);
      const RotorRun b = run_rotor(h, speed, false, dir.path);
      const TangentCheck& c = a.tangent;
      std::printf("h = %g ms, %g rad/s: tangent error %.2e (without R's derivatives %.2e); Newton from the predictor %d "
                  "iterations, last rate %.2e (%d, %.2e); iterations a step in the run %.2f (%.2f)\n",
                  h * 1e3, speed, c.err, c.err_old, c.iterations, c.rate, c.iterations_old, c.rate_old, a.iterations, b.iterations);
      EXPECT_LT(c.err, 0.1 * c.err_old) << h << " " << speed;
      EXPECT_LE(c.iterations, c.iterations_old) << h << " " << speed;
      if (h == 1e-3) {
        EXPECT_LT(a.iterations, b.iterations) << speed;
      }
    }
  }
}

// The tangent changes Newton's path, not its solution: the washing test's rotor (400 rad/s,
// 0.2 s, h = 0.25 ms) with and without R's derivatives ends in the same state up to the Newton
// tolerance.
TEST(RelativeTangent, MotionUnchanged) {
  test::TempDir dir("relative_tangent_motion");
  test::write_sid_file(test::rod_with_tip_rotations(), dir / "rod.sid.h5");
  const Model model = test::model_from(test::rod_rotor_json(2.5e-4, "relative"), dir.path);
  Eigen::VectorXd q[2];
  double iterations[2];
  for (const bool exact : {true, false}) {
    Data data(model);
    initialize(model, data);
    data.relative->exact_tangent = exact;
    for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
    q[exact] = data.state.q;
    iterations[exact] = static_cast<double>(data.stats.newton_iterations) / static_cast<double>(data.stats.steps);
  }
  const double d = (q[1] - q[0]).cwiseAbs().maxCoeff();
  std::printf("motion with and without R's derivatives: %.2e apart (largest coordinate); iterations a step %.2f (%.2f)\n", d,
              iterations[1], iterations[0]);
  EXPECT_LT(d, 1e-7);
}

// The formulation benchmark's flexible slider-crank (tools/bench/formulations: a free-free rod of
// 10 modes, the crank driven at 150 rad/s, h = 1 ms): the rod placed at its node on the crank pin
// (a body placed at a point by a marker on its own node), the slider joint cut.
TEST(RelativeTangent, FlexibleSliderCrank) {
  test::TempDir dir("relative_tangent_crank");
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 10));
  bench::add_section_inertia(chain.sid, 0.008, 0.008);
  ffr::formats::write_sid(chain.sid, dir / "rod.sid.h5");
  const double h = 1e-3;
  const Model model = test::model_from(formulations::with_formulation(bench::slider_crank_json("rod.sid.h5", h, 0.2, 150.0), "relative"), dir.path);
  Data data(model);
  initialize(model, data);
  for (int i = 0; i < 25; ++i) {
    step(model, data);
    if (i % 5 != 4) continue;
    const TangentCheck c = check_tangent(model, data, h);
    std::printf("crank t = %.3f: tangent error %.2e (without R's derivatives %.2e); Newton %d iterations, last rate %.2e (%d, %.2e)\n",
                data.state.t, c.err, c.err_old, c.iterations, c.rate, c.iterations_old, c.rate_old);
    // Measured: 2.6e-9 to 1.6e-8 against 3.2e-6 to 9.5e-6; 3 or 4 iterations against 5. (With
    // the penalty forces alpha Phi in the curvature's F, 6 to 8 iterations: FORMULATION.md 18.)
    EXPECT_LT(c.err, 0.01 * c.err_old) << data.state.t;
    EXPECT_LT(c.iterations, c.iterations_old) << data.state.t;
  }
}
