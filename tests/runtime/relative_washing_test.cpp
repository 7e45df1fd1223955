// A rotor spinning on a flexible body, as the washing machine's drum and motor rotor on its
// elastic tub (meshes/washing_machine): each shaft turns in a rigid housing fixed to the flexible
// body's node, so the relative formulation places the housing at the node's point (its rotation
// rows to the node's first-order triad kept, FORMULATION.md 18) and the rotor wholly on the
// housing by its joint angle; the belt is a coupler between two such shafts, four bodies.
//
// References:
//  - the spinning rotor at the tip of Simeon's rod (the IVP Test Set slider-crank's elastic rod,
//    4 modes, hinged to the ground at its frame origin and released horizontal) against the
//    absolute formulation of the same model (natural coordinates, every joint a constraint):
//    two discretisations of the same equations, apart by O(h^2) (no outside reference for the
//    motion itself);
//  - the belt between two shafts each in its own housing on an accelerating carrier against the
//    analytic reflected-inertia result of coupler_test.cpp (J. L. Meriam & L. G. Kraige,
//    "Engineering Mechanics: Dynamics", gear trains): the housings are welded to the carrier, so
//    alpha = (T - (I_a + r I_b) beta) / (I_a + r^2 I_b), in both formulations.
#include "relative_rod_rotor.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/runtime/relative.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

bool has_note(const Model& m, const std::string& text) {
  return std::any_of(m.notes.begin(), m.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

struct RodRotor {
  Eigen::Vector3d tip, mass;
  Eigen::VectorXd y;
  double hinge = 0, spin = 0;
};

RodRotor run_rod_rotor(double h, const char* formulation, const std::filesystem::path& dir) {
  const Model model = test::model_from(test::rod_rotor_json(h, formulation), dir);
  if (std::string(formulation) == "relative") {
    EXPECT_TRUE(has_note(model, "joint 'mount' assembled (fixed, body 'housing' placed at node 'B' of 'rod'"));
    EXPECT_TRUE(has_note(model, "joint 'shaft' assembled (revolute, body 'rotor' placed on 'housing' by 1 joint coordinate(s))"));
    EXPECT_TRUE(model.relative && !model.relative->bodies[2].point && model.relative->bodies[2].s_angle >= 0);
  }
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const auto x = test::output(model, data, "tip"), p = test::output(model, data, "mass");
  return {Eigen::Vector3d(x[0], x[1], x[2]), Eigen::Vector3d(p[0], p[1], p[2]), data.state.q.segment(12, model.bodies[0].nq),
          joint_coordinate(model, data, 0, JointCoordinate::Angle), joint_coordinate(model, data, 2, JointCoordinate::Angle)};
}

}  // namespace

TEST(RelativeWashing, RotorInAHousingOnAFlexibleNodeMatchesAbsolute) {
  test::TempDir dir("relative_rod_rotor");
  test::write_sid_file(test::rod_with_tip_rotations(), dir / "rod.sid.h5");
  double d_tip[2], d_hinge[2], d_y[2], d_mass[2];
  int i = 0;
  for (const double h : {5e-4, 2.5e-4}) {
    const RodRotor a = run_rod_rotor(h, "absolute", dir.path), r = run_rod_rotor(h, "relative", dir.path);
    d_tip[i] = (a.tip - r.tip).norm();
    d_mass[i] = (a.mass - r.mass).norm();
    d_hinge[i] = std::abs(a.hinge - r.hinge);
    d_y[i] = (a.y - r.y).norm() / a.y.norm();
    std::printf("h = %g: hinge %.6f rad (absolute %.6f), spin %.4f rad (%.4f), tip (%.6f, %.6f), modal |y| %.3e; apart: tip %.3e m, "
                "unbalance %.3e m, hinge %.3e rad, modal %.3e relative\n",
                h, r.hinge, a.hinge, r.spin, a.spin, r.tip(0), r.tip(1), a.y.norm(), d_tip[i], d_mass[i], d_hinge[i], d_y[i]);
    // The spin is the integral of the speed ramp in both (the motion's row): 40 rad.
    EXPECT_NEAR(std::remainder(r.spin - 40.0, 2 * M_PI), 0.0, 1e-6);
    EXPECT_NEAR(std::remainder(a.spin - 40.0, 2 * M_PI), 0.0, 1e-6);
    ++i;
  }
  // The swing is large (the rod falls through 0.76 rad), the rotor's spin 40 rad. Measured apart
  // at h = 0.25 ms: tip 1.9e-6 m, unbalance 1.9e-6 m, hinge 6.2e-6 rad (at 0.5 ms 9.4e-6 m,
  // 9.8e-6 m, 3.1e-5 rad).
  EXPECT_LT(d_tip[1], 5e-6);
  EXPECT_LT(d_mass[1], 5e-6);
  EXPECT_LT(d_hinge[1], 2e-5);
  // Second order: halving the step divides the difference by about four.
  EXPECT_GT(d_tip[0] / d_tip[1], 2.5);
  EXPECT_GT(d_hinge[0] / d_hinge[1], 2.5);
  (void)d_y;
}

// Two shafts each in its own housing, the housings welded to a carrier turning about z at the
// constant angular acceleration beta; the belt couples the shafts' angles in their housings (a
// coupler row on four bodies). The analytic reference is coupler_test.cpp's
// BeltInAnAcceleratingCarrier, the housings being rigid parts of the carrier.
std::string housings_json(const char* formulation, double r) {
  return std::string(R"({"bodies": [
      {"name": "c", "type": "rigid", "mass": 5, "com": [0, 0, 0], "inertia": [[1.2, 0, 0], [0, 1.2, 0], [0, 0, 2]]},
      {"name": "ha", "type": "rigid", "mass": 0.3, "com": [0.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.015]]},
      {"name": "hb", "type": "rigid", "mass": 0.3, "com": [-0.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.015]]},
      {"name": "a", "type": "rigid", "mass": 1, "com": [0.5, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]]},
      {"name": "b", "type": "rigid", "mass": 2, "com": [-0.5, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]}],
    "joints": [{"name": "jc", "type": "revolute", "body1": "ground", "body2": "c", "at": [0, 0, 0], "axis": [0, 0, 1]},
               {"name": "ja", "type": "revolute", "body1": "ha", "body2": "a", "at": [0.5, 0, 0], "axis": [0, 0, 1]},
               {"name": "jb", "type": "revolute", "body1": "hb", "body2": "b", "at": [-0.5, 0, 0], "axis": [0, 0, 1]},
               {"name": "wa", "type": "fixed", "body1": "c", "body2": "ha", "at": [0.5, 0, 0]},
               {"name": "wb", "type": "fixed", "body1": "c", "body2": "hb", "at": [-0.5, 0, 0]},
               {"name": "belt", "type": "coupler", "joint1": "jb", "joint2": "ja", "ratio": )") + num(r) + R"(}],
    "motions": [{"joint": "jc", "speed": {"t": [0, 1], "value": [0, 2]}}],
    "forces": [{"type": "point_torque", "body": "a", "table": {"t": [0, 1], "value": [[0, 0, 1.3], [0, 0, 1.3]]}}],
    "solver": {"formulation": ")" + formulation + R"(", "end": 0.2, "step": 1e-3, "eliminate_driven_bodies": false}})";
}

TEST(RelativeWashing, BeltBetweenShaftsInTwoHousings) {
  const double Ia = 0.2, Ib = 0.05, T = 1.3, beta = 2;
  for (const char* form : {"absolute", "relative"})
    for (double r : {3.0, -0.5}) {
      const double alpha = (T - (Ia + r * Ib) * beta) / (Ia + r * r * Ib);
      const Model model = test::model_from(housings_json(form, r));
      const auto& blk = model.blocks[static_cast<std::size_t>(model.couplers[0].block)];
      EXPECT_NE(blk.body4, kGround);  // a, b and their housings
      if (std::string(form) == "relative") {
        EXPECT_TRUE(has_note(model, "joint 'ja' assembled (revolute, body 'a' placed on 'ha' by 1 joint coordinate(s))"));
        EXPECT_TRUE(has_note(model, "joint 'jb' assembled (revolute, body 'b' placed on 'hb' by 1 joint coordinate(s))"));
      }
      Data data(model);
      initialize(model, data);
      for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
      const double t = data.state.t;
      const double ta = joint_coordinate(model, data, 1, JointCoordinate::Angle);
      const double tb = joint_coordinate(model, data, 2, JointCoordinate::Angle);
      const double a = 2 * ta / (t * t);
      std::printf("%s r = %g: alpha %.12f (analytic %.12f), theta_b - r theta_a %.2e\n", form, r, a, alpha, tb - r * ta);
      // coupler_test.cpp's tolerance for the same motion (measured there 1.8e-7, 2.8e-7).
      EXPECT_NEAR(a, alpha, 1e-6 * std::abs(alpha)) << form << " r " << r;
      EXPECT_NEAR(tb, r * ta, 1e-10);
    }
}
