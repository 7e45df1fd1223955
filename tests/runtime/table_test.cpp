// Tables: linear, PCHIP and natural-spline interpolation, and the default that never overshoots.
//
// References: F. N. Fritsch & R. E. Carlson, "Monotone piecewise cubic interpolation", SIAM J.
// Numer. Anal. 17 (1980) 238-246 (a PCHIP segment whose slopes have the sign of its chord and
// are at most three times it is monotone, hence between its samples); C. Moler, "Numerical
// Computing with MATLAB", section 3.4 (pchip: interior slope the harmonic mean of the chords for
// equal spacing, the three-point end formula), worked by hand below; the undamped oscillator
// under a ramp-and-hold force by Duhamel's integral (e.g. W. T. Thomson, "Theory of Vibration
// with Applications", section 4.2, ramp excitation).
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace ffr::runtime;

namespace {

Table table1(std::vector<double> t, std::vector<double> v, Interpolation k) {
  return Table(Eigen::Map<Eigen::VectorXd>(t.data(), t.size()), Eigen::Map<Eigen::VectorXd>(v.data(), v.size()), k);
}

using test::error_of;
using test::expect_error;

}  // namespace

// Moler's example worked by hand: samples (0,0), (1,1), (2,3); chords 1 and 2. Interior slope:
// the harmonic mean 2*1*2/(1+2) = 4/3; end slopes ((2h0+h1) d0 - h0 d1)/(h0+h1): (3-2)/2 = 1/2
// at t = 0 and (3*2-1)/2 = 5/2 at t = 2. At t = 0.5 the Hermite cubic with y = 0, 1 and slopes
// 1/2, 4/3 gives 0.5/8 + 1/2 - (4/3)/8 = 19/48.
TEST(Table, PchipSlopesByHand) {
  const Table p = table1({0, 1, 2}, {0, 1, 3}, Interpolation::Pchip);
  double v, d1, d2;
  p.eval(1.0, 0, v, d1, d2);
  EXPECT_NEAR(v, 1.0, 1e-15);
  EXPECT_NEAR(d1, 4.0 / 3.0, 1e-15);
  p.eval(0.0, 0, v, d1, d2);
  EXPECT_NEAR(d1, 0.5, 1e-15);
  p.eval(2.0, 0, v, d1, d2);
  EXPECT_NEAR(d1, 2.5, 1e-15);
  EXPECT_NEAR(p.value(0.5, 0), 19.0 / 48.0, 1e-15);
}

// Fritsch & Carlson: on monotone data PCHIP is monotone and never leaves [y_i, y_i+1] on any
// interval; it is C1 at the knots. Random monotone data with steps from flat to steep, and with
// plateaus; sampled densely.
TEST(Table, PchipNeverOvershootsMonotoneData) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 9;
    std::vector<double> t(n), v(n);
    t[0] = 0;
    v[0] = 0;
    for (int i = 1; i < n; ++i) {
      t[i] = t[i - 1] + 0.01 + 3 * U(rng);
      const double r = U(rng);
      v[i] = v[i - 1] + (r < 0.25 ? 0.0 : std::pow(10.0, 4 * U(rng) - 2));  // plateaus and jumps
    }
    const Table p = table1(t, v, Interpolation::Pchip);
    for (int i = 0; i + 1 < n; ++i) {
      double prev = v[i];
      for (int s = 1; s <= 200; ++s) {
        const double x = t[i] + (t[i + 1] - t[i]) * s / 200.0;
        const double y = p.value(x, 0);
        ASSERT_GE(y, v[i] - 1e-12 * (1 + std::abs(v[i]))) << "trial " << trial << " interval " << i;
        ASSERT_LE(y, v[i + 1] + 1e-12 * (1 + std::abs(v[i + 1]))) << "trial " << trial << " interval " << i;
        ASSERT_GE(y, prev - 1e-12 * (1 + std::abs(prev))) << "not monotone, trial " << trial;
        prev = y;
      }
      // C1 at the interior knots: the slopes from both sides agree (to the left one's change
      // over the offset, |d2| 1e-9 h).
      if (i > 0) {
        double a, da, dd, b, db, d2b;
        const double e = 1e-9 * (t[i] - t[i - 1]);
        p.eval(t[i] - e, 0, a, da, dd);
        p.eval(t[i], 0, b, db, d2b);
        EXPECT_NEAR(da, db, 2 * std::abs(dd) * e + 1e-12 * (1 + std::abs(db)));
      }
    }
  }
  // The natural spline on the same kind of data does overshoot (why it is not the default): by
  // hand, its knot curvature at t = 3 is 6 (0/7 + 2/3) / (2 (3 + 7)) = 0.2, and on [3, 10] it is
  // -2 + 0.2 (A^3 - A) 49/6 with A = (10 - t)/7, lowest -2 - 0.2 (2/(3 sqrt 3)) 49/6 = -2.62867.
  const Table s = table1({0, 3, 10}, {0, -2, -2}, Interpolation::Spline);
  double lowest = 0;
  for (int k = 0; k <= 1000; ++k) lowest = std::min(lowest, s.value(10.0 * k / 1000, 0));
  EXPECT_NEAR(lowest, -2 - 0.2 * (2 / (3 * std::sqrt(3.0))) * 49 / 6, 1e-5);
}

// Every kind: d1 and d2 are the derivatives of the value (central differences), the values hit
// the samples, and the integral is the integral of the value (composite Simpson, 2e4 panels per
// interval, also over the linear continuation beyond both ends).
TEST(Table, DerivativesAndIntegralAreConsistent) {
  const std::vector<double> t = {0, 0.4, 1.0, 1.3, 2.5}, v = {1, -0.5, 2, 2, 0.3};
  for (Interpolation k : {Interpolation::Linear, Interpolation::Pchip, Interpolation::Spline}) {
    const Table p = table1(t, v, k);
    for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(p.value(t[i], 0), v[i], 1e-14) << to_string(k);
    for (double x : {0.13, 0.7, 1.17, 2.0, 3.1, -0.4}) {
      const double e = 1e-5;
      double y, d1, d2, yp, d1p, d2p, ym, d1m, d2m;
      p.eval(x, 0, y, d1, d2);
      p.eval(x + e, 0, yp, d1p, d2p);
      p.eval(x - e, 0, ym, d1m, d2m);
      EXPECT_NEAR(d1, (yp - ym) / (2 * e), 1e-8) << to_string(k) << " at " << x;
      EXPECT_NEAR(d2, (d1p - d1m) / (2 * e), 1e-6) << to_string(k) << " at " << x;
    }
    auto simpson = [&](double a, double b) {
      const int n = 20000;
      const double h = (b - a) / n;
      double s = p.value(a, 0) + p.value(b, 0);
      for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * p.value(a + i * h, 0);
      return s * h / 3;
    };
    double ref = 0;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) ref += simpson(t[i], t[i + 1]);
    EXPECT_NEAR(p.integral(2.5, 0), ref, 1e-12) << to_string(k);
    EXPECT_NEAR(p.integral(1.15, 0), simpson(0, 1.0) + simpson(1.0, 1.15), 1e-12) << to_string(k);
    EXPECT_NEAR(p.integral(3.5, 0), ref + simpson(2.5, 3.5), 1e-12) << to_string(k);
    EXPECT_NEAR(p.integral(-0.5, 0), -simpson(-0.5, 0), 1e-12) << to_string(k);
  }
  // Linear: the chord between samples.
  EXPECT_NEAR(table1(t, v, Interpolation::Linear).value(0.2, 0), 0.25, 1e-15);
}

namespace {

// A 1 kg mass on a prismatic joint (z) with a spring of k = 10 N/m to the ground, loaded by a
// force ramped from 0 to -2 N over 3 s and then held (to 10 s), through the model file's
// default interpolation of a load (or `interp`).
std::string ramp_model(const std::string& interp) {
  return R"({"bodies": [{"name": "mass", "type": "rigid", "mass": 1, "com": [0, 0, 0],
                  "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]}],
   "joints": [{"name": "slide", "type": "prismatic", "body1": "ground", "body2": "mass", "at": [0, 0, 0], "axis": [0, 0, 1]}],
   "forces": [{"type": "spring_damper", "body1": "ground", "at1": [0, 0, 1], "body2": "mass", "k": 10},
              {"type": "point_force", "body": "mass", "table": {"t": [0, 3, 10], "value": [[0, 0, 0], [0, 0, -2], [0, 0, -2]])" +
         interp + R"(}}],
   "solver": {"end": 10, "step": 1e-3}})";
}

// Duhamel's integral for x'' + w^2 x = F(t)/m with F ramping linearly to F0 over tr, then held:
//   x = F0 / (k tr) [ (t - sin(w t)/w) - H(t - tr) ((t - tr) - sin(w (t - tr))/w) ].
double ramp_response(double t, double F0, double k, double w, double tr) {
  double x = t - std::sin(w * t) / w;
  if (t > tr) x -= (t - tr) - std::sin(w * (t - tr)) / w;
  return F0 / (k * tr) * x;
}

}  // namespace

TEST(Table, RampAndHoldLoadStaysInItsStaticEnvelope) {
  const double k = 10, F0 = -2, tr = 3, w = std::sqrt(k / 1.0);
  const double x_static = F0 / k;
  // The quasi-static response plus the largest free vibration a ramp of length tr can leave:
  // |x| <= |F0/k| (1 + 2 / (w tr)) (the Duhamel solution above, |sin| <= 1).
  const double envelope = std::abs(x_static) * (1 + 2 / (w * tr));
  for (const std::string interp : {"", R"(, "interpolation": "linear")", R"(, "interpolation": "spline")"}) {
    const Model model = test::model_from(ramp_model(interp));
    Data data(model);
    initialize(model, data);
    double worst = 0, deepest = 0;
    for (std::int64_t i = 0; i < step_count(model); ++i) {
      step(model, data);
      const double x = joint_coordinate(model, data, 0, JointCoordinate::Displacement);
      deepest = std::max(deepest, std::abs(x));
      worst = std::max(worst, std::abs(x - ramp_response(data.state.t, F0, k, w, tr)));
    }
    if (interp.find("spline") != std::string::npos) {
      // The spline's load dips below -2 N after the ramp: the spring goes past the envelope.
      EXPECT_GT(deepest, 1.1 * envelope) << "spline";
      continue;
    }
    EXPECT_LE(deepest, envelope) << interp;
    // Trapezoidal rule: phase error (w h)^2 / 12 per radian, ~3e-7 of the amplitude per period.
    EXPECT_LT(worst, 1e-5 * std::abs(x_static)) << interp;
    std::printf("ramp-and-hold %s: max |x| %.6f m (envelope %.6f), max error vs Duhamel %.3e m\n",
                interp.empty() ? "default" : interp.c_str(), deepest, envelope, worst);
  }
}

TEST(Table, BadInterpolationRefused) {
  expect_error(R"({"bodies": [{"name": "m", "type": "rigid", "mass": 1, "inertia": [[1,0,0],[0,1,0],[0,0,1]]}],
     "forces": [{"type": "point_force", "body": "m", "table": {"t": [0, 1], "value": [[0,0,0],[0,0,1]], "interpolation": "cubic"}}],
     "solver": {"end": 1, "step": 0.01}})",
               "forces[0].table.interpolation", "unknown interpolation 'cubic'");
  expect_error(R"({"bodies": [{"name": "m", "type": "rigid", "mass": 1, "inertia": [[1,0,0],[0,1,0],[0,0,1]]}],
     "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "m", "at": [0,0,0], "axis": [0,0,1]}],
     "motions": [{"joint": "j", "table": {"t": [0, 1], "value": [0, 1], "interpolation": 3}}],
     "solver": {"end": 1, "step": 0.01}})",
               "motions[0].table.interpolation", "");
}

// A time table whose samples all lie outside the run (here milliseconds given as seconds, and a
// speed table of an earlier run) is read only by extrapolation: each gets a note naming it; one
// that overlaps the run gets none.
TEST(Table, TimeTablesOutsideTheRunAreNoted) {
  const auto model = [](const std::string& force_t, const std::string& motion_t) {
    return R"({"bodies": [{"name": "m", "type": "rigid", "mass": 1, "inertia": [[1,0,0],[0,1,0],[0,0,1]]}],
     "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "m", "at": [0,0,0], "axis": [0,0,1]}],
     "forces": [{"name": "push", "type": "point_force", "body": "m", "table": {"t": )" + force_t + R"(, "value": [[0,0,0],[0,0,1]]}}],
     "motions": [{"joint": "j", "speed": {"t": )" + motion_t + R"(, "value": [0, 1]}}],
     "solver": {"start": 1, "end": 2, "step": 0.01}})";
  };
  const auto notes_with = [](const Model& m, const std::string& text) {
    int n = 0;
    for (const auto& note : m.notes) n += note.find(text) != std::string::npos;
    return n;
  };
  const Model outside = test::model_from(model("[100, 2000]", "[0, 0.5]"));
  EXPECT_EQ(notes_with(outside, "point_force 'push': its samples, t = 100 .. 2000 s, all lie outside the run (1 .. 2 s): "
                                "it is extrapolated over the whole run with its end slope"), 1);
  EXPECT_EQ(notes_with(outside, "the speed of the motion of joint 'j': its samples, t = 0 .. 0.5 s, all lie outside the run"), 1);
  const Model overlapping = test::model_from(model("[1.5, 2000]", "[0, 1]"));  // touching the start counts
  EXPECT_EQ(notes_with(overlapping, "all lie outside the run"), 0);
}
