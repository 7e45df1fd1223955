// A quarter car on a sinusoidal road: a mass on its tyre (spring k, damper c), carried along at
// constant speed V over h(s) = Y sin(2 pi s / lambda), is a base-excited oscillator at
// omega = 2 pi V / lambda. Its steady amplitude is the displacement transmissibility
//   X / Y = sqrt((1 + (2 zeta r)^2) / ((1 - r^2)^2 + (2 zeta r)^2)),  r = omega / omega_n,
// S. S. Rao, "Mechanical Vibrations" (5th ed., 2011), section 3.6.2 "Base excitation", eq. (3.68)
// (also T. D. Gillespie, "Fundamentals of Vehicle Dynamics" (1992), chapter 5, for the tyre as
// the road's spring). The road is a table of the sine (PCHIP, 64 samples per wavelength).
#include "support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

struct QuarterCar {
  double m = 50, k = 2e5, zeta = 0.1, R = 0.3, V = 10, lambda = 2, Y = 0.005, g = 9.81;
  double c() const { return 2 * zeta * std::sqrt(k * m); }

  // A driven cart along x carries the mass on a vertical guide; the mass's tyre rolls on the road.
  std::string json(double end, double h) const {
    std::string s = "[", hs = "[";
    const int per = 64;
    for (int i = 0; i <= static_cast<int>((V * end + 2) / lambda * per); ++i) {
      const double x = -1 + lambda * i / per;
      s += (i ? ", " : "") + num(x);
      hs += (i ? ", " : "") + num(Y * std::sin(2 * M_PI * x / lambda));
    }
    const double z0 = R - m * g / k;  // resting on the road at s = 0 (h = 0)
    return R"({
      "gravity": [0, 0, -9.81],
      "roads": [{"name": "sine", "direction": [1, 0, 0], "s": )" + s + R"(], "height": )" + hs + R"(]}],
      "bodies": [
        {"name": "cart", "type": "rigid", "mass": 1, "com": [0, 0, 1], "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
        {"name": "mass", "type": "rigid", "mass": )" + num(m) + R"(, "com": [0, 0, )" + num(z0) + R"(],
         "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}],
      "joints": [
        {"name": "track", "type": "prismatic", "body1": "ground", "body2": "cart", "at": [0, 0, 1], "axis": [1, 0, 0]},
        {"name": "guide", "type": "prismatic", "body1": "cart", "body2": "mass", "at": [0, 0, )" + num(z0) + R"(], "axis": [0, 0, 1]}],
      "motions": [{"joint": "track", "speed": {"t": [0, 1], "value": [)" + num(V) + ", " + num(V) + R"(]}}],
      "forces": [{"name": "tyre", "type": "tire", "body": "mass", "axis": [0, 1, 0], "radius": )" + num(R) +
           R"(, "vertical_stiffness": )" + num(k) + R"(, "vertical_damping": )" + num(c()) + R"(, "road": "sine"}],
      "solver": {"end": )" + num(end) + R"(, "step": )" + num(h) + R"(},
      "outputs": [{"name": "z", "type": "node_position", "body": "mass"}, {"name": "tyre", "type": "element_force", "force": "tyre"}]
    })";
  }
  double transmissibility() const {
    const double r = (2 * M_PI * V / lambda) / std::sqrt(k / m), q = 2 * zeta * r;
    return std::sqrt((1 + q * q) / ((1 - r * r) * (1 - r * r) + q * q));
  }
};

}  // namespace

TEST(QuarterCar, SteadyAmplitudeOnASineRoadIsTheBaseExcitationTransmissibility) {
  const QuarterCar qc;
  const double end = 3.0, h = 1e-3;
  const Model model = test::model_from(qc.json(end, h));
  Data data(model);
  initialize(model, data);
  // The transient decays as exp(-zeta omega_n t) (e^-12.6 by t = 2 s): the last second (five
  // road periods) is the steady response.
  double zmin = 1e9, zmax = -1e9, fn_min = 1e9;
  double out[6];
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    if (data.state.t < 2.0 - 1e-9) continue;
    const double z = data.state.q(model.bodies[1].offset + 2);
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
    evaluate_output(model, data, model.outputs[1], out);
    fn_min = std::min(fn_min, out[2]);
  }
  const double X = 0.5 * (zmax - zmin), Xref = qc.Y * qc.transmissibility();
  const double mean = 0.5 * (zmax + zmin), mean_ref = qc.R - qc.m * qc.g / qc.k;
  std::printf("amplitude %.6e m (Rao eq. 3.68: %.6e, X/Y = %.6f), relative error %.2e; mean %.6f (R - m g / k = %.6f); least Fn %.1f N\n",
              X, Xref, qc.transmissibility(), X / Xref - 1, mean, mean_ref, fn_min);
  ASSERT_GT(fn_min, 0);  // the tyre stays on the road: the linear oscillator holds
  EXPECT_NEAR(X / Xref, 1, 2e-3);
  // The mean sits higher by a term of order R slope^2 (the contact normal tilts with the road's
  // slope: FORMULATION.md section 8, tyres; quasi-statically R slope_max^2 / 4 = 1.9e-5 m here).
  EXPECT_NEAR(mean, mean_ref, 1e-2 * qc.Y);
}

namespace {

// The two-mass quarter car (T. D. Gillespie, "Fundamentals of Vehicle Dynamics" (1992), section 5
// "Quarter-car model"; S. S. Rao, "Mechanical Vibrations" (5th ed.), section 5.6 "Forced
// vibration analysis" of two-degree-of-freedom systems): sprung mass ms on the suspension (ks, cs)
// over the unsprung mass mu on the tyre (kt, ct). With y = Y e^{i w t} the steady amplitudes solve
//   [ks + i w cs - w^2 ms,  -(ks + i w cs)               ] [Zs]   [0              ]
//   [-(ks + i w cs),        ks + kt + i w (cs + ct) - w^2 mu] [Zu] = [(kt + i w ct) Y]
// solved here by Cramer's rule.
struct TwoMass {
  double ms = 250, mu = 35, ks = 16000, cs = 1000, kt = 160000, ct = 100, R = 0.3, V = 10, lambda = 5, Y = 0.01, g = 9.81;

  void amplitudes(double& Zs, double& Zu) const {
    using C = std::complex<double>;
    const double w = 2 * M_PI * V / lambda;
    const C i(0, 1);
    const C a11 = ks + i * w * cs - w * w * ms, a12 = -(ks + i * w * cs);
    const C a22 = ks + kt + i * w * (cs + ct) - w * w * mu, b2 = (kt + i * w * ct) * Y;
    const C det = a11 * a22 - a12 * a12;
    Zs = std::abs(-a12 * b2 / det);
    Zu = std::abs(a11 * b2 / det);
  }

  std::string json(double end, double h) const {
    std::string s = "[", hs = "[";
    const int per = 64;
    for (int i = 0; i <= static_cast<int>((V * end + 2) / lambda * per); ++i) {
      const double x = -1 + lambda * i / per;
      s += (i ? ", " : "") + num(x);
      hs += (i ? ", " : "") + num(Y * std::sin(2 * M_PI * x / lambda));
    }
    // At rest on the road at s = 0: the tyre carries both masses, the suspension (a preload, its
    // tension negative: pushing) the sprung one.
    const double zu = R - (ms + mu) * g / kt, zs = zu + 0.5;
    return R"({
      "gravity": [0, 0, -9.81],
      "roads": [{"name": "sine", "direction": [1, 0, 0], "s": )" + s + R"(], "height": )" + hs + R"(]}],
      "bodies": [
        {"name": "cart", "type": "rigid", "mass": 1, "com": [0, 0, 2], "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
        {"name": "body", "type": "rigid", "mass": )" + num(ms) + R"(, "com": [0, 0, )" + num(zs) + R"(],
         "inertia": [[10, 0, 0], [0, 10, 0], [0, 0, 10]]},
        {"name": "wheel", "type": "rigid", "mass": )" + num(mu) + R"(, "com": [0, 0, )" + num(zu) + R"(],
         "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}],
      "joints": [
        {"name": "track", "type": "prismatic", "body1": "ground", "body2": "cart", "at": [0, 0, 2], "axis": [1, 0, 0]},
        {"name": "body_guide", "type": "prismatic", "body1": "cart", "body2": "body", "at": [0, 0, )" + num(zs) + R"(], "axis": [0, 0, 1]},
        {"name": "wheel_guide", "type": "prismatic", "body1": "cart", "body2": "wheel", "at": [0, 0, )" + num(zu) + R"(], "axis": [0, 0, 1]}],
      "motions": [{"joint": "track", "speed": {"t": [0, 1], "value": [)" + num(V) + ", " + num(V) + R"(]}}],
      "forces": [
        {"name": "suspension", "type": "spring_damper", "body1": "body", "body2": "wheel", "k": )" + num(ks) + R"(, "c": )" + num(cs) +
           R"(, "preload": )" + num(-ms * g) + R"(},
        {"name": "tyre", "type": "tire", "body": "wheel", "axis": [0, 1, 0], "radius": )" + num(R) + R"(, "vertical_stiffness": )" +
           num(kt) + R"(, "vertical_damping": )" + num(ct) + R"(, "road": "sine"}],
      "solver": {"end": )" + num(end) + R"(, "step": )" + num(h) + R"(},
      "outputs": [{"name": "tyre", "type": "element_force", "force": "tyre"}]
    })";
  }
};

}  // namespace

TEST(QuarterCar, TwoMassSteadyAmplitudesOnASineRoad) {
  const TwoMass qc;
  const double end = 9.0, h = 2e-3;
  const Model model = test::model_from(qc.json(end, h));
  Data data(model);
  initialize(model, data);
  // The slowest mode (the body's, damping ratio ~0.25 at ~1.2 Hz) decays by e^-12 in 6 s: the
  // last two seconds (four road periods) are the steady response.
  double smin = 1e9, smax = -1e9, umin = 1e9, umax = -1e9, fn_min = 1e9;
  double out[6];
  const int ob = model.bodies[1].offset + 2, ow = model.bodies[2].offset + 2;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    if (data.state.t < end - 2 - 1e-9) continue;
    smin = std::min(smin, data.state.q(ob));
    smax = std::max(smax, data.state.q(ob));
    umin = std::min(umin, data.state.q(ow));
    umax = std::max(umax, data.state.q(ow));
    evaluate_output(model, data, model.outputs[0], out);
    fn_min = std::min(fn_min, out[2]);
  }
  double Zs, Zu;
  qc.amplitudes(Zs, Zu);
  const double xs = 0.5 * (smax - smin), xu = 0.5 * (umax - umin);
  std::printf("body %.6e m (Cramer %.6e, error %.2e), wheel %.6e m (%.6e, error %.2e); least Fn %.1f N\n", xs, Zs, xs / Zs - 1, xu, Zu,
              xu / Zu - 1, fn_min);
  ASSERT_GT(fn_min, 0);
  EXPECT_NEAR(xs / Zs, 1, 2e-3);
  EXPECT_NEAR(xu / Zu, 1, 2e-3);
}
