// Coupler joints (belt, gear, rack): the change of joint1's coordinate is ratio times joint2's.
//
// Reference (analytic, rigid-body dynamics of a geared pair, e.g. J. L. Meriam & L. G. Kraige,
// "Engineering Mechanics: Dynamics", reflected inertia of gear trains): a torque T on shaft a
// whose rotation drives coordinate b at theta_b = r theta_a accelerates it at
// alpha = T / (I_a + r^2 I_b) (m_b for a rack), and the coupler acts on b with I_b r alpha (the
// force or torque that accelerates it), which is the coupler row's multiplier: with the row
// L (theta_b - r theta_a), I_b alpha_b + L lambda = 0.
//
// Agreement: to 0.2 s with h = 1 ms. The angle carries the trapezoidal rule's O(h^2) error on
// turning frame vectors (measured 1.3e-7 to 1.8e-7 of alpha); the multiplier, the one that
// balances the scheme's own accelerations, an error that grows with the rate (measured 2.5e-5
// to 8.1e-5 relative; 1e-2 by 1 s at 6 rad/s, 4e-4 there with h = 0.1 ms).
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

using test::error_of;
using test::expect_error;

// Shaft a (I_zz = 0.2) turns in the ground about z; b is a disk (I_zz = 0.05) on `joint_b` (its
// JSON), coupled by "belt" {joint1: b, joint2: a, ratio}; a torque 1.3 N m on a.
std::string pair(const std::string& joint_b, double ratio, const std::string& b_body = "") {
  char r[32];
  std::snprintf(r, sizeof r, "%.17g", ratio);
  return R"({"bodies": [
      {"name": "a", "type": "rigid", "mass": 1, "com": [0, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]]},
      )" + (b_body.empty() ? R"({"name": "b", "type": "rigid", "mass": 2, "com": [1, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]})" : b_body) + R"(],
    "joints": [{"name": "ja", "type": "revolute", "body1": "ground", "body2": "a", "at": [0, 0, 0], "axis": [0, 0, 1]},
               )" + joint_b + R"(,
               {"name": "belt", "type": "coupler", "joint1": "jb", "joint2": "ja", "ratio": )" + r + R"(}],
    "forces": [{"type": "point_torque", "body": "a", "table": {"t": [0, 1], "value": [[0, 0, 1.3], [0, 0, 1.3]]}}],
    "solver": {"end": 0.2, "step": 1e-3}})";
}

struct Result {
  double theta_a, coord_b, alpha, multiplier;
};

Result run(const std::string& json, JointCoordinate cb) {
  const Model model = test::model_from(json);
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  Result r;
  r.theta_a = joint_coordinate(model, data, 0, JointCoordinate::Angle);
  r.coord_b = joint_coordinate(model, data, 1, cb);
  r.alpha = 2 * r.theta_a / (data.state.t * data.state.t);  // theta = alpha t^2 / 2
  r.multiplier = data.state.lambda(model.blocks[static_cast<std::size_t>(model.couplers[0].block)].row0);
  // The row's scale: the model length for an angle of joint1 (the multiplier is then per length).
  if (cb == JointCoordinate::Angle) r.multiplier *= model.length;
  return r;
}

}  // namespace

// Belt between two shafts in the ground (b at x = 1 m): r = 3, alpha = 1.3 / (0.2 + 9 * 0.05) = 2.
TEST(Coupler, BeltBetweenShaftsReflectedInertia) {
  const double r = 3, Ib = 0.05, alpha = 1.3 / (0.2 + r * r * Ib);
  const Result x = run(pair(R"({"name": "jb", "type": "revolute", "body1": "ground", "body2": "b", "at": [1, 0, 0], "axis": [0, 0, 1]})", r),
                    JointCoordinate::Angle);
  EXPECT_NEAR(x.alpha, alpha, 1e-6 * alpha);
  EXPECT_NEAR(x.coord_b, r * x.theta_a, 1e-10);
  // The coupler's torque on b, -L lambda, is I_b r alpha.
  EXPECT_NEAR(-x.multiplier, Ib * r * alpha, 2e-4 * std::abs(Ib * r * alpha));
  std::printf("belt r = 3: alpha %.12f (analytic %.12f), coupler torque on b %.12f (I_b r alpha %.12f)\n", x.alpha, alpha,
              -x.multiplier, Ib * r * alpha);
}

// A negative ratio (a gear pair turning the other way) gives the same magnitude.
TEST(Coupler, GearPairNegativeRatio) {
  const double r = -0.5, Ib = 0.05, alpha = 1.3 / (0.2 + r * r * Ib);
  const Result x = run(pair(R"({"name": "jb", "type": "revolute", "body1": "ground", "body2": "b", "at": [1, 0, 0], "axis": [0, 0, 1]})", r),
                    JointCoordinate::Angle);
  EXPECT_NEAR(x.alpha, alpha, 1e-6 * alpha);
  EXPECT_NEAR(x.coord_b, r * x.theta_a, 1e-10);
  EXPECT_NEAR(-x.multiplier, Ib * r * alpha, 2e-4 * std::abs(Ib * r * alpha));
}

// Rack: b (2 kg) slides along x, x_b = r theta_a with r = 0.1 m/rad: alpha = 1.3 / (0.2 + 0.01 * 2),
// the rack's force m_b r alpha.
TEST(Coupler, RackAndPinion) {
  const double r = 0.1, mb = 2, alpha = 1.3 / (0.2 + r * r * mb);
  const Result x = run(pair(R"({"name": "jb", "type": "prismatic", "body1": "ground", "body2": "b", "at": [1, 0, 0], "axis": [1, 0, 0]})", r),
                    JointCoordinate::Displacement);
  EXPECT_NEAR(x.alpha, alpha, 1e-6 * alpha);
  EXPECT_NEAR(x.coord_b, r * x.theta_a, 1e-10);
  EXPECT_NEAR(-x.multiplier, mb * r * alpha, 2e-4 * std::abs(mb * r * alpha));
  std::printf("rack r = 0.1 m/rad: alpha %.12f (analytic %.12f), rack force %.12f (m_b r alpha %.12f)\n", x.alpha, alpha,
              -x.multiplier, mb * r * alpha);
}

// b turns on a (coaxial, joint jb between a and b), its angle relative to a r times a's: b's
// absolute rate is (1 + r) omega_a, so alpha = T / (I_a + (1 + r)^2 I_b). The row touches a
// through both joints (the coupler's sides need not be the joints').
TEST(Coupler, CoaxialOnTheDrivenShaft) {
  const double r = 2, Ib = 0.05, alpha = 1.3 / (0.2 + (1 + r) * (1 + r) * Ib);
  const Result x = run(pair(R"({"name": "jb", "type": "revolute", "body1": "a", "body2": "b", "at": [0, 0, 0], "axis": [0, 0, 1]})", r,
                         R"({"name": "b", "type": "rigid", "mass": 2, "com": [0, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]})"),
                    JointCoordinate::Angle);
  EXPECT_NEAR(x.alpha, alpha, 1e-6 * alpha);
  EXPECT_NEAR(x.coord_b, r * x.theta_a, 1e-10);
  // b's absolute acceleration (1 + r) alpha comes from the coupler alone.
  EXPECT_NEAR(-x.multiplier, Ib * (1 + r) * alpha, 2e-4 * std::abs(Ib * (1 + r) * alpha));
}

// Two shafts in a moving carrier (a belt in a washing machine's tub): the carrier c turns about z
// with the constant angular acceleration beta (a speed motion, w = beta t), shaft a at x = 0.5 and
// b at x = -0.5 on revolute joints in c about z, the belt couples their angles relative to c,
// theta_b = r theta_a, and the torque T acts on a. The row touches three bodies (a, b, c).
// Reference (analytic, as above, in the carrier's frame): about its own axis each shaft turns
// absolutely at beta + its relative acceleration, the revolute joints pass no torque about z, and
// the belt's torques do no work (tau_a = -r tau_b), so
//   I_b (beta + r alpha) = tau_b,   I_a (beta + alpha) = T - r tau_b
//   => alpha = (T - (I_a + r I_b) beta) / (I_a + r^2 I_b),  the belt's torque on b I_b (beta + r alpha).
// With eliminate_driven_bodies false the carrier is integrated (three bodies in the block); with
// it true the carrier follows its motion and the block has two bodies with unknowns.
std::string carrier(bool eliminate, double r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", r);
  return std::string(R"({"bodies": [
      {"name": "c", "type": "rigid", "mass": 5, "com": [0, 0, 0], "inertia": [[1.2, 0, 0], [0, 1.2, 0], [0, 0, 2]]},
      {"name": "a", "type": "rigid", "mass": 1, "com": [0.5, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]]},
      {"name": "b", "type": "rigid", "mass": 2, "com": [-0.5, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]}],
    "joints": [{"name": "jc", "type": "revolute", "body1": "ground", "body2": "c", "at": [0, 0, 0], "axis": [0, 0, 1]},
               {"name": "ja", "type": "revolute", "body1": "c", "body2": "a", "at": [0.5, 0, 0], "axis": [0, 0, 1]},
               {"name": "jb", "type": "revolute", "body1": "c", "body2": "b", "at": [-0.5, 0, 0], "axis": [0, 0, 1]},
               {"name": "belt", "type": "coupler", "joint1": "jb", "joint2": "ja", "ratio": )") + buf + R"(}],
    "motions": [{"joint": "jc", "speed": {"t": [0, 1], "value": [0, 2]}}],
    "forces": [{"type": "point_torque", "body": "a", "table": {"t": [0, 1], "value": [[0, 0, 1.3], [0, 0, 1.3]]}}],
    "solver": {"end": 0.2, "step": 1e-3, "eliminate_driven_bodies": )" + (eliminate ? "true" : "false") + "}}";
}

TEST(Coupler, BeltInAnAcceleratingCarrier) {
  const double Ia = 0.2, Ib = 0.05, T = 1.3, beta = 2;
  for (double r : {3.0, -0.5})
    for (bool eliminate : {false, true}) {
      const double alpha = (T - (Ia + r * Ib) * beta) / (Ia + r * r * Ib);
      const Model model = test::model_from(carrier(eliminate, r));
      const auto& blk = model.blocks[static_cast<std::size_t>(model.couplers[0].block)];
      EXPECT_NE(blk.body3, kGround);  // a, b and c
      Data data(model);
      initialize(model, data);
      for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
      const double t = data.state.t;
      const double ta = joint_coordinate(model, data, 1, JointCoordinate::Angle);
      const double tb = joint_coordinate(model, data, 2, JointCoordinate::Angle);
      const double tc = joint_coordinate(model, data, 0, JointCoordinate::Angle);
      const double a = 2 * ta / (t * t);
      const double torque_b = -model.length * data.state.lambda(blk.row0);
      EXPECT_NEAR(tc, 0.5 * beta * t * t, 1e-9);  // the carrier followed its motion
      EXPECT_NEAR(a, alpha, 1e-6 * std::abs(alpha)) << "r " << r << " eliminate " << eliminate;  // measured 1.8e-7, 2.8e-7
      EXPECT_NEAR(tb, r * ta, 1e-10);
      // The multiplier's error (as above, 2e-4) is relative to the torques it balances, I_b beta
      // and I_b r alpha, which nearly cancel for r = -0.5 (measured 1.5e-5 and 1.8e-5 N m there,
      // 5e-6 and 9e-6 relative for r = 3).
      EXPECT_NEAR(torque_b, Ib * (beta + r * alpha), 2e-4 * Ib * (std::abs(beta) + std::abs(r * alpha)));
      std::printf("carrier r = %g, eliminate %d: alpha %.12f (analytic %.12f), belt torque on b %.10f (analytic %.10f)\n",
                  r, eliminate, a, alpha, torque_b, Ib * (beta + r * alpha));
    }
}

TEST(Coupler, BadInputRefused) {
  const std::string jb = R"({"name": "jb", "type": "revolute", "body1": "ground", "body2": "b", "at": [1, 0, 0], "axis": [0, 0, 1]})";
  expect_error(pair(jb, 0), "joints[2].ratio", "must not be zero");
  expect_error(pair(R"({"name": "jb", "type": "spherical", "body1": "ground", "body2": "b", "at": [1, 0, 0]})", 2), "joints[2].joint1",
               "revolute, prismatic or cylindrical joint; 'jb' is spherical");
  std::string unknown = pair(jb, 2);
  unknown.replace(unknown.find(R"("joint2": "ja")"), 14, R"("joint2": "jx")");
  expect_error(unknown, "joints[2].joint2", "unknown joint 'jx'");
  std::string same = pair(jb, 2);
  same.replace(same.find(R"("joint2": "ja")"), 14, R"("joint2": "jb")");
  expect_error(same, "joints[2].joint2", "must differ");
  std::string extra = pair(jb, 2);
  extra.replace(extra.find(R"("ratio")"), 7, R"("axis": [0, 0, 1], "ratio")");
  expect_error(extra, "joints[2].axis", "unknown field");
  // (Two joints with four different bodies, each shaft in its own housing, are coupled:
  // relative_washing_test.cpp.)
}
