// The generalized-alpha step ("integrator": "generalized_alpha", scheme_coefficients.cpp):
// - second-order convergence for rho_inf = 0, 0.5, 0.9, 1 on a compound pendulum against an
//   independent oracle written here (the pendulum's one-degree-of-freedom equation
//   I_O theta'' = m g d cos(theta) integrated by classical Runge-Kutta at a far smaller step);
// - rho_inf = 1 gives the trapezoidal rule's states (the benchmark's flexible slider-crank);
// - the numerical damping of a single linear mode (a spring-mass) per step against the
//   amplification matrix of Chung & Hulbert, built from their equations (alpha_amplification.hpp).
#include "alpha_amplification.hpp"
#include "support.hpp"

#include "models.hpp"  // tools/models: the benchmark's slider-crank

#include "ffr/formats/synthetic.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

std::string scheme_keys(double rho) {
  if (rho < 0) return "";
  char buf[96];
  std::snprintf(buf, sizeof buf, R"(, "integrator": "generalized_alpha", "spectral_radius": %.17g)", rho);
  return buf;
}

// The compound pendulum of support.hpp and its oracle.
constexpr double kIyy = test::kPendulumIyy, kMass = test::kPendulumMass, kD = test::kPendulumD, kG = test::kPendulumG;

std::string pendulum(double h, double end, double rho, double w0 = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, R"({"end": %.17g, "step": %.17g, "newton_tolerance": 1e-14%s})", end, h, scheme_keys(rho).c_str());
  return test::compound_pendulum_json(buf, w0);
}

double pendulum_oracle(double end, double* rate = nullptr, double w0 = 0) { return test::compound_pendulum_oracle(end, w0, rate); }

double pendulum_angle(double h, double end, double rho) {
  const Model model = test::model_from(pendulum(h, end, rho));
  Data data(model);
  initialize(model, data);
  const auto n = step_count(model);
  for (std::int64_t i = 0; i < n; ++i) step(model, data);
  return joint_coordinate(model, data, 0, JointCoordinate::Angle);
}

// The accelerations and the joint's force at the end against the oracle: the bar's frame vector
// u = (cos theta, 0, -sin theta) has u'' = theta'' (-sin, 0, -cos) - theta'^2 (cos, 0, -sin) with
// theta'' = m g d cos(theta) / I_O; the hinge holds the bar with R = m (d u'' - g), which the
// multipliers give as the constraint force Phi_q^T lambda on the bar's position coordinates.
struct EndErrors {
  double angle, acceleration, force;
};

EndErrors pendulum_errors(double h, double end, double rho, double w0) {
  const Model model = test::model_from(pendulum(h, end, rho, w0));
  Data data(model);
  initialize(model, data);
  const auto n = step_count(model);
  for (std::int64_t i = 0; i < n; ++i) step(model, data);
  double om = 0;
  const double th = pendulum_oracle(end, &om, w0);
  const double thdd = kMass * kG * kD * std::cos(th) / (kIyy + kMass * kD * kD);
  const Eigen::Vector3d udd = thdd * Eigen::Vector3d(-std::sin(th), 0, -std::cos(th)) - om * om * Eigen::Vector3d(std::cos(th), 0, -std::sin(th));
  const Eigen::Vector3d R = kMass * (kD * udd - Eigen::Vector3d(0, 0, -kG));
  VectorXd force = VectorXd::Zero(model.ncoord);
  add_constraint_forces(model, data, data.state.lambda, force);
  const int o = model.bodies[0].offset;
  // (The sign of Phi_q^T lambda is the equations' convention: M q'' + Phi_q^T lambda = Q.)
  return {std::abs(joint_coordinate(model, data, 0, JointCoordinate::Angle) - th),
          (data.state.qdd.segment<3>(o + 3) - udd).cwiseAbs().maxCoeff(), (force.segment<3>(o) + R).cwiseAbs().maxCoeff()};
}

}  // namespace

TEST(GeneralizedAlpha, SecondOrderForEverySpectralRadius) {
  const double end = 1.0;
  const double ref = pendulum_oracle(end);
  for (const double rho : {0.0, 0.5, 0.9, 1.0}) {
    double e[3];
    const double hs[3] = {5e-4, 2.5e-4, 1.25e-4};
    for (int k = 0; k < 3; ++k) e[k] = std::abs(pendulum_angle(hs[k], end, rho) - ref);
    const double p1 = std::log2(e[0] / e[1]), p2 = std::log2(e[1] / e[2]);
    std::printf("rho_inf %.1f: angle errors %.3e %.3e %.3e at h = 0.5, 0.25, 0.125 ms: orders %.3f %.3f\n", rho, e[0], e[1], e[2], p1, p2);
    EXPECT_NEAR(p1, 2.0, 0.1) << "rho_inf " << rho;
    EXPECT_NEAR(p2, 2.0, 0.1) << "rho_inf " << rho;
    EXPECT_LT(e[2], 2e-7);
  }
}

// The accelerations are second order as well, for every rho_inf, early in the run (20 to 80
// steps) where a start error has not yet decayed, with the start a_0 = q_ddot_0 + delta
// (q_ddot_1 - q_ddot_0) (start_generalized_alpha). Measured with a_0 = q_ddot_0 instead: 3
// (rho 0) and 1.9 (rho 0.5) times these errors. The joint force (the multipliers) is first order
// for every rho_inf, the trapezoidal rule's too (FORMULATION.md section 9: Newton's multipliers
// balance the accelerations before their projection); checked as such.
TEST(GeneralizedAlpha, AccelerationsSecondOrderForEverySpectralRadius) {
  const double end = 0.02;  // 20 to 80 steps: where a start error would still show
  for (const double rho : {0.0, 0.5, 0.9, 1.0}) {
    EndErrors e[3];
    const double hs[3] = {1e-3, 5e-4, 2.5e-4};
    for (int k = 0; k < 3; ++k) e[k] = pendulum_errors(hs[k], end, rho, 5.0);  // started at 5 rad/s: q''' != 0
    const double pa1 = std::log2(e[0].acceleration / e[1].acceleration), pa2 = std::log2(e[1].acceleration / e[2].acceleration);
    const double pf1 = std::log2(e[0].force / e[1].force), pf2 = std::log2(e[1].force / e[2].force);
    std::printf("rho_inf %.1f: acceleration errors %.3e %.3e %.3e (orders %.3f %.3f), force errors %.3e %.3e %.3e (orders %.3f %.3f)\n", rho,
                e[0].acceleration, e[1].acceleration, e[2].acceleration, pa1, pa2, e[0].force, e[1].force, e[2].force, pf1, pf2);
    EXPECT_NEAR(pa1, 2.0, 0.15) << "rho_inf " << rho;
    EXPECT_NEAR(pa2, 2.0, 0.15) << "rho_inf " << rho;
    EXPECT_GT(pf1, 0.9) << "rho_inf " << rho;
    EXPECT_GT(pf2, 0.9) << "rho_inf " << rho;
  }
}

TEST(GeneralizedAlpha, SpectralRadiusOneIsTheTrapezoidalRule) {
  test::TempDir dir("galpha_crank");
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 10));
  bench::add_section_inertia(chain.sid, 0.008, 0.008);
  test::write_sid_file(chain.sid, dir / "rod.sid.h5");
  const std::string json = bench::slider_crank_json("rod.sid.h5", 1e-3, 0.1, 150.0);
  Model trap = test::model_from(json, dir.path);
  trap.settings.newton_tolerance = 1e-15;
  Model alpha = trap;
  alpha.settings.integrator = Integrator::GeneralizedAlpha;
  alpha.settings.spectral_radius = 1.0;
  const test::SideBySide r = test::step_side_by_side(trap, alpha);
  std::printf("rho_inf = 1 against the trapezoidal rule: states apart by %.2e at most (scaled; the motion %.2e)\n", r.apart, r.motion);
  EXPECT_GT(r.motion, 0.1);
  EXPECT_LT(r.apart, 1e-10);
}

// A 1 kg body on a spring (k = 1e4 N/m along x, through its centre of mass: omega = 100 rad/s),
// released 0.1 m from its rest length. The spring's ground end is 1 km away, so that even the
// first steps' overshoot at omega h = 100 keeps it along +x (linear). Its state after each step, written in the eigenvectors
// of Chung & Hulbert's amplification matrix, must shrink by the matrix's eigenvalues: the
// principal pair by the per-step damping |lambda_1| (the spectral radius for omega h >= 1),
// checked at every step.
TEST(GeneralizedAlpha, DampingOfOneModePerStepIsTheAnalyticAmplification) {
  const double omega = 100.0, x_rest = 1.0;
  for (const double rho : {0.0, 0.5, 0.9}) {
    for (const double Omega : {0.5, 2.0, 100.0}) {
      const double h = Omega / omega;
      char buf[1024];
      std::snprintf(buf, sizeof buf, R"({
  "bodies": [{"name": "mass", "type": "rigid", "mass": 1.0, "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]], "position": [1.1, 0, 0]}],
  "forces": [{"type": "spring_damper", "body1": "ground", "at1": [-1000, 0, 0], "body2": "mass", "at2": [1.1, 0, 0], "k": 1e4, "length0": 1001.0}],
  "solver": {"end": %.17g, "step": %.17g, "newton_tolerance": 1e-11%s},
  "outputs": [{"name": "e", "type": "energy"}]
})",
                    40 * h, h, scheme_keys(rho).c_str());
      const Model model = test::model_from(buf);
      Data data(model);
      initialize(model, data);
      // d, v, a of the x coordinate: a is the scheme's pseudo-acceleration (Chung & Hulbert's a).
      const test::ModeDecay m = test::measure_mode_decay(
          rho, omega, h, step_count(model), [&] { step(model, data); },
          [&] { return Eigen::Vector3cd(data.state.q(0) - x_rest, data.state.qd(0), data.state.a(0)); });
      const double spectral = m.spectral, worst = m.worst;
      const int checked = m.checked;
      std::printf("rho_inf %.1f, omega h %4.1f: spectral radius %.6f; the state's component decays by it to %.1e in each of %d steps\n",
                  rho, Omega, spectral, worst, checked);
      EXPECT_GE(checked, 3);
      EXPECT_LT(worst, 1e-6) << "rho_inf " << rho << ", omega h " << Omega;
      // The damping is there: far above 1/h the spectral radius tends to rho_inf (0.048, 0.537 and
      // 0.928 at omega h = 100).
      if (Omega == 100.0) {
        EXPECT_NEAR(spectral, rho, 0.06);
      }
    }
  }
}
