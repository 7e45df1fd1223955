// Speed motions: a joint's rate prescribed by a table, its coordinate the exact integral.
//
// Reference: the integral of a cubic Hermite segment with values y0, y1 and slopes s0, s1 over
// an interval of length h is h (y0 + y1) / 2 + h^2 (s0 - s1) / 12 (integrate the Hermite basis;
// e.g. the corrected trapezoidal rule, P. J. Davis & P. Rabinowitz, "Methods of Numerical
// Integration", section 2.9); for a linear table the trapezoids. The PCHIP slopes of the table
// below are worked by hand (Fritsch-Carlson, as in table_test.cpp).
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

using test::error_of;
using test::expect_error;

// A drum (rigid, off-centre mass under gravity, so the drive carries a load) on a revolute joint
// about z, its speed 0 -> 10 rad/s over 1 s, held to 2 s, down to 0 at 4 s.
std::string drum(const std::string& motion, const std::string& solver_extra = "") {
  return R"({"gravity": [0, -9.81, 0],
   "bodies": [{"name": "drum", "type": "rigid", "mass": 3, "com": [0.1, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]],
               "position": [0, 0, 0]}],
   "joints": [{"name": "hub", "type": "revolute", "body1": "ground", "body2": "drum", "at": [0, 0, 0], "axis": [0, 0, 1]}],
   "motions": [)" + motion + R"(],
   "solver": {"end": 4, "step": 1e-3)" + solver_extra + R"(}})";
}

// The exact integral of the speed table from 0 to t at the sample times 1, 2, 4 s.
struct Expected {
  double t, angle, rate;
};

void check(const std::string& json, const Expected (&ex)[3], const char* what) {
  const Model model = test::model_from(json);
  Data data(model);
  initialize(model, data);
  int k = 0;
  double worst = 0;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    if (k < 3 && std::abs(data.state.t - ex[k].t) < 1e-9) {
      const double th = joint_coordinate(model, data, 0, JointCoordinate::Angle);
      // The rate from the drum's frame: u_dot . v (its x axis turning towards y).
      const double rate = data.state.qd.segment<3>(3).dot(data.state.q.segment<3>(6));
      EXPECT_NEAR(th, ex[k].angle, 1e-9 * (1 + std::abs(ex[k].angle))) << what << " at t = " << ex[k].t;
      EXPECT_NEAR(rate, ex[k].rate, 1e-8) << what << " at t = " << ex[k].t;
      worst = std::max(worst, std::abs(th - ex[k].angle));
      ++k;
    }
  }
  EXPECT_EQ(k, 3);
  std::printf("%s: angle at 4 s %.12f rad (exact %.12f), worst error %.2e rad\n", what,
              joint_coordinate(model, data, 0, JointCoordinate::Angle), ex[2].angle, worst);
}

}  // namespace

// Linear: trapezoids 5, 10, 10 rad.
TEST(SpeedMotion, LinearSpeedIntegratesExactly) {
  const Expected ex[3] = {{1, 5, 10}, {2, 15, 10}, {4, 25, 0}};
  const std::string m = R"({"joint": "hub", "speed": {"t": [0, 1, 2, 4], "value": [0, 10, 10, 0], "interpolation": "linear"}})";
  check(drum(m), ex, "linear speed, driven body");
  check(drum(m, R"(, "eliminate_driven_bodies": false)"), ex, "linear speed, integrated body");
}

// PCHIP (the default): chords 10, 0, -5; interior slopes 0 (the data turn or are flat), end
// slopes (3*10 - 0)/2 = 15 and (5*(-5) - 0)/3 = -25/3. Integrals: 5 + 15/12 = 6.25,
// 10, 2 * 10/2 + 4 * (25/3)/12 = 12.777...
TEST(SpeedMotion, PchipSpeedIntegratesExactly) {
  const Expected ex[3] = {{1, 6.25, 10}, {2, 16.25, 10}, {4, 16.25 + 10 + 100.0 / 36, 0}};
  check(drum(R"({"joint": "hub", "speed": {"t": [0, 1, 2, 4], "value": [0, 10, 10, 0]}})"), ex, "pchip speed");
}

TEST(SpeedMotion, SpeedAndCoordinateOnOneJointRefused) {
  expect_error(drum(R"({"joint": "hub", "speed": {"t": [0, 1], "value": [0, 1]}, "table": {"t": [0, 1], "value": [0, 1]}})"),
               "motions[0].speed", "either table");
  expect_error(drum(R"({"joint": "hub", "speed": {"t": [0, 1], "value": [0, 1]}}, {"joint": "hub", "table": {"t": [0, 1], "value": [0, 1]}})"),
               "motions[1].joint", "already prescribed");
  expect_error(drum(R"({"joint": "hub", "speed": {"t": [0, 1, 1], "value": [0, 1, 2]}})"), "motions[0].speed.t",
               "strictly increasing");
}
