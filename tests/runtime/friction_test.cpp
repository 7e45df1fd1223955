// Friction dampers: Coulomb friction along the line of two points, regularised or with a series
// spring (Jenkins element).
//
// References: J. P. Den Hartog, "Mechanical Vibrations" (4th ed., 1956), section 8.2 and
// "Forced vibration with Coulomb damping" (the free Coulomb oscillator: the half period is that
// of the undamped spring-mass, each extreme is 2F/k smaller in magnitude than the one before,
// and the mass stops at the first extreme where |k x| <= F); for the series spring, an
// independent reference in this file: the two-state Jenkins element (elastic spring k_s in
// series with a Coulomb slider) integrated by the classical explicit Runge-Kutta method at a
// step a hundredth of the runtime's.
#include "support.hpp"

#include "ffr/runtime/step_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// A 1 kg mass on a prismatic joint along x, its centre at x0 (the spring of k to the ground at
// x = -1 is unstretched at x = 0), and a friction damper `friction` (its JSON keys after the
// ends) from the ground at x = -2.
std::string oscillator(double x0, double k, const std::string& friction, double end, double h) {
  return R"({"bodies": [{"name": "mass", "type": "rigid", "mass": 1, "com": [)" + num(x0) + R"(, 0, 0],
                  "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]}],
   "joints": [{"name": "slide", "type": "prismatic", "body1": "ground", "body2": "mass", "at": [0, 0, 0], "axis": [1, 0, 0]}],
   "forces": [{"type": "spring_damper", "body1": "ground", "at1": [-1, 0, 0], "body2": "mass", "k": )" + num(k) +
         R"(, "length0": 1},
              {"name": "damper", "type": "friction_damper", "body1": "ground", "at1": [-2, 0, 0], "body2": "mass", )" +
         friction + R"(}],
   "solver": {"end": )" + num(end) + R"(, "step": )" + num(h) + "}}";
}

double position(const Data& data) { return data.state.q(0); }  // the mass's frame origin, x

using test::error_of;
using test::expect_error;

}  // namespace

// Den Hartog's Coulomb oscillator: m = 1 kg, k = 100 N/m, F = 1 N, released at rest from
// x0 = 0.105 m. Extremes 0.105, -0.085, 0.065, -0.045, 0.025, -0.005 (each 2F/k = 0.02 smaller),
// pi/omega = 0.314159 s apart; at -0.005 m, |k x| = 0.5 N <= F: it stays there.
TEST(FrictionDamper, CoulombOscillatorDenHartog) {
  const double k = 100, F = 1, x0 = 0.105, vtol = 1e-4, h = 1e-3;
  const Model model = test::model_from(oscillator(x0, k, R"("force": 1, "velocity_tolerance": 1e-4)", 3.0, h));
  Data data(model);
  initialize(model, data);
  const double E0 = energy(model, data).total();
  std::vector<double> t, x;
  t.push_back(data.state.t);
  x.push_back(position(data));
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    t.push_back(data.state.t);
    x.push_back(position(data));
  }
  // Extremes: samples where the motion turns (the last one, where it stops, found below).
  std::vector<double> te, xe;
  te.push_back(0);
  xe.push_back(x0);
  for (std::size_t i = 1; i + 1 < x.size() && xe.size() < 6; ++i)
    if ((x[i] - x[i - 1]) * (x[i + 1] - x[i]) < 0 && std::abs(x[i]) > 0.01) {
      te.push_back(t[i]);
      xe.push_back(x[i]);
    }
  ASSERT_EQ(xe.size(), 5u);
  const double w = std::sqrt(k);
  for (std::size_t n = 1; n < xe.size(); ++n) {
    const double expected = (n % 2 ? -1 : 1) * (x0 - n * 2 * F / k);
    EXPECT_NEAR(xe[n], expected, 2e-5) << "extreme " << n;
    EXPECT_NEAR(te[n] - te[n - 1], M_PI / w, 1.5 * h) << "half period " << n;
    std::printf("extreme %zu: %.6f m (Den Hartog %.6f), half period %.4f s (%.4f)\n", n, xe[n], expected,
                te[n] - te[n - 1], M_PI / w);
  }
  // Stuck at -0.005 m after the fifth half period (t ~ 1.571 s); it creeps at most at
  // v_tol |k x| / F (the regularisation) until the end.
  const double x_stop = -(x0 - 5 * 2 * F / k);
  const double creep = vtol * k * std::abs(x_stop) / F * (3.0 - 5 * M_PI / w);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] > 5 * M_PI / w + 0.02) {
      ASSERT_NEAR(x[i], x_stop, 2e-5 + creep) << "at t = " << t[i];
    }
  }
  EXPECT_LT(std::abs(k * x.back()), F);
  // The energy balance: what the spring and the mass lost, the damper dissipated (the
  // trapezoidal rule on its power: to the step's accuracy).
  const Energy e = energy(model, data);
  EXPECT_NEAR(e.total() + e.dissipated, E0, 1e-4 * E0);
  std::printf("stuck at %.6f m (Den Hartog %.6f); energy %.6f + dissipated %.6f = %.6f J (start %.6f)\n", x.back(), x_stop,
              e.total(), e.dissipated, e.total() + e.dissipated, E0);
}

namespace {

// The Jenkins element's reference: x'' = -(k x + T)/m with T = k_s (x - s) limited to |T| <= F by
// the slip s, each explicit RK4 stage with the slip of the step's start and the slip updated at
// the end of the step (s moves only while the slider carries F).
struct Jenkins {
  double k, ks, F, m;
  double tension(double x, double s) const { return std::clamp(ks * (x - s), -F, F); }
  // The series spring is unloaded at the start (s = x0).
  void run(double x0, double end, double h, std::vector<double>& xs, double sample_dt) const {
    double x = x0, v = 0, s = x0, t = 0;
    const auto n = static_cast<long>(std::llround(end / h)), every = std::lround(sample_dt / h);
    xs.push_back(x);
    for (long i = 1; i <= n; ++i) {
      auto acc = [&](double xx) { return -(k * xx + tension(xx, s)) / m; };
      const double k1x = v, k1v = acc(x);
      const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x);
      const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x);
      const double k4x = v + h * k3v, k4v = acc(x + h * k3x);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      s = x - tension(x, s) / ks;
      t += h;
      if (i % every == 0) xs.push_back(x);
    }
  }
};

}  // namespace

// A rubber bearing in series: m = 1 kg, k = 100 N/m, k_s = 400 N/m, F = 2 N, from x0 = 0.1 m.
// It slips while |k_s (x - s)| would exceed F, sticks (oscillating on k + k_s) between, and ends
// oscillating on both springs with the slider stuck.
TEST(FrictionDamper, SeriesSpringAgainstJenkinsReference) {
  const double k = 100, ks = 400, F = 2, x0 = 0.1, end = 2.0, h = 2.5e-4;
  const Model model = test::model_from(oscillator(x0, k, R"("force": 2, "series_stiffness": 400)", end, h));
  Data data(model);
  initialize(model, data);
  const double E0 = energy(model, data).total();
  std::vector<double> ref;
  Jenkins{k, ks, F, 1.0}.run(x0, end, h / 100, ref, h);
  double worst = 0;
  ASSERT_EQ(static_cast<std::int64_t>(ref.size()), step_count(model) + 1);
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    worst = std::max(worst, std::abs(position(data) - ref[static_cast<std::size_t>(i + 1)]));
  }
  // Trapezoidal phase error (omega h)^2 / 12 per radian, omega = sqrt(500): ~1e-4 x0 over 45 rad,
  // plus the O(h^2) error of each stick-slip switch.
  EXPECT_LT(worst, 2e-4 * x0);
  const Energy e = energy(model, data);
  EXPECT_GT(e.dissipated, 0.1 * E0);
  EXPECT_NEAR(e.total() + e.dissipated, E0, 1e-4 * E0);
  std::printf("series spring: max |x - x_RK4| = %.3e m over %.1f s; energy %.6f + dissipated %.6f = %.6f J (start %.6f)\n",
              worst, end, e.total(), e.dissipated, e.total() + e.dissipated, E0);
}

TEST(FrictionDamper, BadInputRefused) {
  expect_error(oscillator(0.1, 100, R"("force": -1)", 1, 1e-3), "forces[1].force", "expected a positive number");
  expect_error(oscillator(0.1, 100, R"("force": 1, "series_stiffness": 400, "velocity_tolerance": 1e-3)", 1, 1e-3),
               "forces[1].velocity_tolerance", "only without series_stiffness");
  expect_error(oscillator(0.1, 100, R"("force": 1, "series_stiffness": 0)", 1, 1e-3), "forces[1].series_stiffness",
               "expected a positive number");
  expect_error(oscillator(0.1, 100, R"("force": 1, "velocity_tolerance": 0)", 1, 1e-3), "forces[1].velocity_tolerance",
               "expected a positive number");
  expect_error(oscillator(0.1, 100, R"("force": 1, "at2": [-2, 0, 0])", 1, 1e-3), "forces[1]", "coincide");
  expect_error(oscillator(0.1, 100, R"("force": 1, "friction": 2)", 1, 1e-3), "forces[1].friction", "unknown field");
}

// Through ffr-sim: exit status 2, the file and the field named, no results file written.
TEST(FrictionDamper, NegativeForceIsExitTwoWithoutOutput) {
  test::TempDir dir("friction_cli");
  test::write_text(dir / "model.json", oscillator(0.1, 100, R"("force": -1)", 1, 1e-3));
  const test::SimRun r = test::run_ffr_sim((dir / "model.json").string() + " -o " + (dir / "out.h5").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("model.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("forces[1].force"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

// Adaptive steps: a rejected step returns to the saved State, the slip with it (a slip kept from
// the rejected attempt would shift the spring's unloaded length). Against the same RK4 reference.
TEST(FrictionDamper, SeriesSpringAdaptiveStepsRestoreTheSlip) {
  const double k = 100, ks = 400, F = 2, x0 = 0.1, end = 2.0;
  std::string json = oscillator(x0, k, R"("force": 2, "series_stiffness": 400)", end, 1e-3);
  const std::string fixed = R"("step": 0.001)";
  json.replace(json.find(fixed), fixed.size(), R"("step": "auto", "rtol": 1e-7, "output_interval": 0.01)");
  const Model model = test::model_from(json);
  Data data(model);
  initialize(model, data);
  StepControl control(model, data);
  std::vector<double> ref;
  Jenkins{k, ks, F, 1.0}.run(x0, end, 1e-6, ref, 0.01);
  double worst = 0;
  for (std::int64_t i = 1; i < output_count(model); ++i) {
    advance_to(model, data, control, output_time(model, i));
    worst = std::max(worst, std::abs(position(data) - ref[static_cast<std::size_t>(i)]));
  }
  std::printf("adaptive: %lld steps accepted, %lld rejected; max |x - x_RK4| = %.3e m\n", static_cast<long long>(control.accepted),
              static_cast<long long>(control.rejected), worst);
  EXPECT_GT(control.rejected, 0);
  EXPECT_LT(worst, 2e-4 * x0);
}

