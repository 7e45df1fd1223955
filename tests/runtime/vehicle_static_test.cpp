// A rigid four-wheel vehicle standing on its tyres (issue 34's check "a vehicle standing still
// on a flat road after initial_equilibrium stays still"; FORMULATION.md 14, neutral motions):
//  - on a flat road it settles statically with each tyre's normal force the share of the weight
//    from rigid-body statics (two axles: moment balance about the rear axle in the settled
//    geometry, each wheel's own weight on its own tyre), its neutral motions (sliding, yaw, the
//    wheels' rolling) accepted with a note, and a dynamic run of 1 s from there stays still;
//  - on an incline with free wheels it would roll: refused, naming a motion and what to add;
//  - on the incline with the wheels locked (a motion holding each wheel's angle) the tyres still
//    have no force at rest (their horizontal forces come from the sliding velocity: a parked car
//    creeps, tire_test's ParkedOnAnIncline), so the sliding downhill is refused as well.
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

constexpr double g = 9.81;
constexpr double mc = 800, mw = 20, xg = 0.1, xa = 1.2, ya = 0.7, k = 2e5;
const char* wheel[4] = {"fl", "fr", "rl", "rr"};

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

using test::output;

// The car body (centre of mass xg ahead of the axles' middle, 0.5 m up) on four 20 kg wheels on
// revolute joints about y at (+-xa, +-ya, 0.3), tyres of radius 0.3 touching a road of the given
// slope (height = slope s), wheels locked to the body by a motion when `locked`.
std::string vehicle(double slope, bool locked, const std::string& solver) {
  std::string bodies = R"({"name": "car", "type": "rigid", "mass": )" + num(mc) + R"(, "com": [)" + num(xg) +
                       R"(, 0, 0.5], "inertia": [[300, 0, 0], [0, 1000, 0], [0, 0, 1100]]})";
  std::string joints, forces, motions, outputs = R"({"name": "car", "type": "node_position", "body": "car"})";
  for (int i = 0; i < 4; ++i) {
    const double x = i < 2 ? xa : -xa, y = i % 2 ? -ya : ya;
    const std::string c = num(x) + ", " + num(y) + ", " + num(0.3 + slope * x);
    const std::string w = wheel[i];
    bodies += R"(, {"name": ")" + w + R"(", "type": "rigid", "mass": )" + num(mw) + R"(, "com": [)" + c +
              R"(], "inertia": [[0.5, 0, 0], [0, 0.9, 0], [0, 0, 0.5]]})";
    joints += std::string(i ? ", " : "") + R"({"name": ")" + w + R"(", "type": "revolute", "body1": "car", "body2": ")" + w +
              R"(", "at": [)" + c + R"(], "axis": [0, 1, 0]})";
    forces += std::string(i ? ", " : "") + R"({"name": ")" + w + R"(", "type": "tire", "body": ")" + w +
              R"(", "axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": )" + num(k) +
              R"(, "vertical_damping": 2000, "longitudinal_stiffness": 1e5, "cornering_stiffness": 5e4, "friction": 0.9, "road": "r"})";
    if (locked) motions += std::string(i ? ", " : "") + R"({"joint": ")" + w + R"(", "table": {"t": [0], "value": [0]}})";
    outputs += R"(, {"name": "c_)" + w + R"(", "type": "node_position", "body": ")" + w + R"("}, {"name": "F_)" + w +
               R"(", "type": "element_force", "force": ")" + w + R"("}, {"name": "w_)" + w + R"(", "type": "joint_rate", "joint": ")" + w +
               R"("}, {"name": "a_)" + w + R"(", "type": "joint_coordinate", "joint": ")" + w + R"("})";
  }
  return R"({"gravity": [0, 0, -9.81],
    "roads": [{"name": "r", "direction": [1, 0, 0], "s": [-20, 20], "height": [)" + num(-20 * slope) + ", " + num(20 * slope) + R"(]}],
    "bodies": [)" + bodies + R"(], "joints": [)" + joints + R"(], "forces": [)" + forces + "]" +
         (locked ? R"(, "motions": [)" + motions + "]" : std::string()) + R"(, "solver": )" + solver + R"(, "outputs": [)" + outputs + "]}";
}

std::string refusal(const Model& model) { return test::initialize_refusal(model); }

}  // namespace

TEST(VehicleStatic, SettlesOnAFlatRoadAsRigidBodyStaticsAndStaysStill) {
  const Model model = test::model_from(vehicle(0, false, R"({"end": 1, "step": 1e-3, "initial_equilibrium": true})"));
  Data data(model);
  const auto notes = initialize(model, data);
  for (const auto& n : notes) std::printf("note: %s\n", n.c_str());
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[1].find("neutral motion"), std::string::npos);
  // Rigid-body statics in the settled geometry: the road pushes straight up (flat), so the
  // vehicle's moment balance about the rear axle fixes the car body's front share
  // mc g (x_G - x_r) / (x_f - x_r), half on each side (symmetric in y), plus each wheel's weight.
  const auto G = output(model, data, "car");
  const double xf = output(model, data, "c_fl")[0], xr = output(model, data, "c_rl")[0];
  const double front = 0.5 * mc * g * (G[0] - xr) / (xf - xr) + mw * g, rear = 0.5 * mc * g * (xf - G[0]) / (xf - xr) + mw * g;
  double worst = 0;
  for (int i = 0; i < 4; ++i) {
    const double Fn = output(model, data, std::string("F_") + wheel[i])[2], ref = i < 2 ? front : rear;
    std::printf("tyre %s: Fn %.9f N (statics %.9f), rel %.2e\n", wheel[i], Fn, ref, Fn / ref - 1);
    worst = std::max(worst, std::abs(Fn / ref - 1));
    EXPECT_NEAR(Fn, ref, 1e-9 * ref) << wheel[i];
  }
  // The same to first order in the initial geometry (the settled pitch moves x_G by ~1e-4 m).
  EXPECT_NEAR(output(model, data, "F_fl")[2], 0.5 * mc * g * (xg + xa) / (2 * xa) + mw * g, 2e-4 * front);
  // A second of dynamics from the static state: nothing moves.
  double drift = 0, spin = 0, turn = 0;
  const auto a0 = output(model, data, "a_fl");
  for (int s = 0; s < 1000; ++s) {
    step(model, data);
    const auto p = output(model, data, "car");
    drift = std::max(drift, std::sqrt((p[0] - G[0]) * (p[0] - G[0]) + (p[1] - G[1]) * (p[1] - G[1]) + (p[2] - G[2]) * (p[2] - G[2])));
    for (int i = 0; i < 4; ++i) spin = std::max(spin, std::abs(output(model, data, std::string("w_") + wheel[i])[0]));
    turn = std::max(turn, std::abs(output(model, data, "a_fl")[0] - a0[0]));
  }
  std::printf("1 s from the static state: centre of mass drift %.3e m, largest wheel spin %.3e rad/s, wheel turn %.3e rad (t = %.3f)\n",
              drift, spin, turn, data.state.t);
  EXPECT_NEAR(data.state.t, 1.0, 1e-12);
  EXPECT_LT(drift, 1e-6);
  EXPECT_LT(spin, 1e-6);
  EXPECT_LT(turn, 1e-6);
}

// Slope 0.1: the weight's part along the road, (mc + 4 mw) g sin(atan 0.1) ~ 860 N, drives the
// rolling that nothing holds.
TEST(VehicleStatic, RollingDownAnInclineIsRefused) {
  const std::string msg = refusal(test::model_from(vehicle(0.1, false, R"({"analysis": "static"})")));
  std::printf("free wheels on the incline: %s\n", msg.c_str());
  EXPECT_NE(msg.find("static equilibrium at t = 0 s"), std::string::npos) << msg;
  EXPECT_NE(msg.find("a force remains along it"), std::string::npos) << msg;
  EXPECT_NE(msg.find("settle the vehicle on a flat road"), std::string::npos) << msg;
  EXPECT_NE(msg.find("its position along x"), std::string::npos) << msg;  // rolling down the slope (x)
}

TEST(VehicleStatic, LockedWheelsOnAnInclineSlideWithoutStaticFriction) {
  const std::string msg = refusal(test::model_from(vehicle(0.1, true, R"({"analysis": "static"})")));
  std::printf("locked wheels on the incline: %s\n", msg.c_str());
  EXPECT_NE(msg.find("a force remains along it"), std::string::npos) << msg;
  EXPECT_NE(msg.find("its position along x"), std::string::npos) << msg;  // sliding down the slope (x)
  EXPECT_NE(msg.find("a tyre holds nothing"), std::string::npos) << msg;
}
