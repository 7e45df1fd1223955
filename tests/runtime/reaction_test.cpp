// Joint reactions, joint rates, node and angular velocities and element forces as outputs
// (MODEL_FILE.md "Outputs", FORMULATION.md 13), each against a reference computed here
// independently of the runtime: statics by hand, a planar Newton-Euler solution of a four-bar,
// rigid-body kinematics v = v_O + omega x r, and finite differences of positions.
#include "formulation_models.hpp"  // tools/bench/formulations
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace ffr::runtime;

namespace {

constexpr double g = 9.81;

using test::output;

}  // namespace

// A 2 kg pendulum hanging at rest below its hinge: the hinge carries its weight (statics: the
// only other force on the body is m g), so the force the ground exerts on it is m g upwards and,
// the centre of mass being below the hinge, no torque. The joint written the other way round
// (body1 the pendulum) reports the force on the ground, -m g.
TEST(Reaction, HangingPendulumCarriesItsWeight) {
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "bob", "type": "rigid", "mass": 2, "com": [0, 0, -0.6],
                "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.002]]},
               {"name": "bob2", "type": "rigid", "mass": 2, "com": [1, 0, -0.6],
                "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.002]]}],
    "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bob", "at": [0, 0, 0], "axis": [0, 1, 0]},
               {"name": "ball", "type": "spherical", "body1": "bob2", "body2": "ground", "at": [1, 0, 0]}],
    "solver": {"end": 0.5, "step": 1e-3},
    "outputs": [{"name": "R", "type": "joint_reaction", "joint": "hinge"},
                {"name": "R2", "type": "joint_reaction", "joint": "ball"},
                {"name": "rate", "type": "joint_rate", "joint": "hinge"}]
  })");
  Data data(model);
  initialize(model, data);
  for (int i = 0; i < 500; ++i) step(model, data);
  const auto R = output(model, data, "R"), R2 = output(model, data, "R2");
  std::printf("hinge reaction after 0.5 s: F = (%.3e, %.3e, %.12f), T = (%.2e, %.2e, %.2e); ball %.12f\n", R[0], R[1], R[2], R[3],
              R[4], R[5], R2[2]);
  const double W = 2 * g;  // the weight
  EXPECT_NEAR(R[2], W, 1e-9 * W);
  EXPECT_NEAR(R2[2], -W, 1e-9 * W);
  for (int i : {0, 1}) EXPECT_NEAR(R[i], 0, 1e-9 * W);
  for (int i : {3, 4, 5}) EXPECT_NEAR(R[i], 0, 1e-9 * W);
  EXPECT_NEAR(output(model, data, "rate")[0], 0, 1e-12);
}

// A 3 kg bar held by a fixed joint to the ground at one end (a rigid cantilever, 0.8 m to its
// centre of mass along x): the joint carries the weight and the moment of the weight about the
// joint point, T = -(r_G - p) x m g. Its body would be driven (eliminated) without the output;
// the reaction keeps it integrated so its rows have multipliers.
TEST(Reaction, FixedJointCarriesWeightAndMoment) {
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "bar", "type": "rigid", "mass": 3, "com": [0.8, 0, 0],
                "inertia": [[0.001, 0, 0], [0, 0.64, 0], [0, 0, 0.64]]}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "bar", "at": [0, 0, 0]}],
    "solver": {"end": 0.1, "step": 1e-3},
    "outputs": [{"name": "R", "type": "joint_reaction", "joint": "clamp"}]
  })");
  ASSERT_FALSE(model.bodies[0].driven());
  Data data(model);
  initialize(model, data);
  for (int i = 0; i < 100; ++i) step(model, data);
  const auto R = output(model, data, "R");
  const Eigen::Vector3d W(0, 0, -3 * g), T = -Eigen::Vector3d(0.8, 0, 0).cross(W);
  std::printf("clamp reaction: F = (%.3e, %.3e, %.12f), T = (%.3e, %.12f, %.3e) (statics: T_y = %.12f)\n", R[0], R[1], R[2], R[3],
              R[4], R[5], T(1));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(R[i], -W(i), 1e-9 * 3 * g);
    EXPECT_NEAR(R[3 + i], T(i), 1e-9 * 3 * g);
  }
}

// ---- the four-bar against planar Newton-Euler ---------------------------------------------
namespace {

// The four-bar of tools/bench/formulations (the one four_bar_test.cpp runs): crank a, coupler
// b, rocker c, ground pivots O = (0, 0) and C = (d, 0), bars uniform, gravity -y.
using formulations::four_bar::d;
using formulations::four_bar::inertia;
using formulations::four_bar::mass;
using formulations::four_bar::pose;

// Centres of mass and angles as a vector [G0x, G0y, phi0, G1x, ...] of theta.
Eigen::Matrix<double, 9, 1> config(double th) {
  const formulations::four_bar::Config k = formulations::four_bar::config(th);
  Eigen::Matrix<double, 9, 1> v;
  for (int i = 0; i < 3; ++i) v.segment<3>(3 * i) << k.G[i], k.phi[i];
  return v;
}

double cross2(const Eigen::Vector2d& r, const Eigen::Vector2d& f) { return r(0) * f(1) - r(1) * f(0); }

// The pin forces R_O (ground on crank), R_A (crank on coupler), R_B (coupler on rocker) and R_C
// (rocker on ground) from the nine Newton-Euler equations of the three bars, m a_G = sum F + m g,
// I alpha = sum (r - G) x F, given the motion theta, theta_dot, theta_ddot (least squares: one
// equation is the equation of motion itself, satisfied by the given motion).
Eigen::Matrix<double, 8, 1> newton_euler(double th, double w, double al) {
  const double e = 1e-4;
  const auto k0 = config(th), kp = config(th + e), km = config(th - e);
  const Eigen::Matrix<double, 9, 1> d1 = (kp - km) / (2 * e), d2 = (kp - 2 * k0 + km) / (e * e);
  const Eigen::Matrix<double, 9, 1> acc = d2 * w * w + d1 * al;  // second derivative in time
  const formulations::four_bar::Pose p = pose(th);
  const Eigen::Vector2d O(0, 0), C(d, 0);
  Eigen::Matrix<double, 9, 8> Aeq = Eigen::Matrix<double, 9, 8>::Zero();
  Eigen::Matrix<double, 9, 1> rhs;
  // Force on bar i: crank +R_O - R_A; coupler +R_A - R_B; rocker +R_B - R_C. Columns 2k, 2k+1 = R_k.
  const int pins[3][2] = {{0, 1}, {1, 2}, {2, 3}};
  const Eigen::Vector2d at[4] = {O, p.A, p.B, C};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d G = k0.segment<2>(3 * i);
    for (int s = 0; s < 2; ++s) {
      const int k = pins[i][s];
      const double sign = s == 0 ? 1.0 : -1.0;
      Aeq(3 * i, 2 * k) = sign;
      Aeq(3 * i + 1, 2 * k + 1) = sign;
      const Eigen::Vector2d r = at[k] - G;
      Aeq(3 * i + 2, 2 * k) = sign * -r(1);  // r x F = r_x F_y - r_y F_x
      Aeq(3 * i + 2, 2 * k + 1) = sign * r(0);
    }
    rhs(3 * i) = mass[i] * acc(3 * i);
    rhs(3 * i + 1) = mass[i] * acc(3 * i + 1) + mass[i] * g;
    rhs(3 * i + 2) = inertia(i) * acc(3 * i + 2);
  }
  (void)cross2;
  return Aeq.colPivHouseholderQr().solve(rhs);
}

}  // namespace

// The runtime's reactions of the four pins against the Newton-Euler pin forces for the motion
// it computed (its crank angle, rate and acceleration): the in-plane forces (the out-of-plane
// components and torques of a closed planar loop are redundant, not unique).
TEST(Reaction, FourBarMatchesPlanarNewtonEuler) {
  const double th0 = formulations::four_bar::kTheta0, h = 5e-4;
  const std::string json = formulations::four_bar::json(h, 1.0, "absolute", R"("outputs": [
    {"name": "O", "type": "joint_reaction", "joint": "O"}, {"name": "A", "type": "joint_reaction", "joint": "A"},
    {"name": "B", "type": "joint_reaction", "joint": "B"}, {"name": "C", "type": "joint_reaction", "joint": "C"},
    {"name": "rate", "type": "joint_rate", "joint": "O"}, {"name": "w", "type": "body_angular_velocity", "body": "crank"}])");
  const Model model = test::model_from(json);
  Data data(model);
  initialize(model, data);
  double worst = 0, scale = 0;
  for (int s = 1; s <= 2000; ++s) {
    step(model, data);
    if (s % 250 != 0) continue;
    const double th = th0 + joint_coordinate(model, data, 0, JointCoordinate::Angle);
    const double rate = output(model, data, "rate")[0];
    // The crank's angular acceleration about z from the integrator's accelerations.
    update_bodies(model, data);
    const double al = (data.bodies[0].A * data.bodies[0].alpha)(2);
    EXPECT_NEAR(output(model, data, "w")[2], rate, 1e-9 * std::abs(rate));
    const auto ref = newton_euler(th, rate, al);
    const char* names[4] = {"O", "A", "B", "C"};
    for (int k = 0; k < 4; ++k) {
      const auto R = output(model, data, names[k]);
      scale = std::max(scale, Eigen::Vector2d(ref(2 * k), ref(2 * k + 1)).norm());
      worst = std::max({worst, std::abs(R[0] - ref(2 * k)), std::abs(R[1] - ref(2 * k + 1))});
      if (s == 1000) std::printf("t = %.2f pin %s: runtime (%.6f, %.6f) N, Newton-Euler (%.6f, %.6f) N\n", data.state.t, names[k], R[0], R[1], ref(2 * k), ref(2 * k + 1));
    }
  }
  std::printf("four-bar pin forces: worst difference %.3e N of %.3f N\n", worst, scale);
  EXPECT_LT(worst, 1e-5 * scale);
}

// A free rigid body spinning about a principal axis through its centre of mass and drifting:
// every point moves with v = v_G + omega x (p - r_G) (rigid-body kinematics), and the angular
// velocity stays the initial one.
TEST(Velocity, RigidSpinIsOmegaCrossR) {
  const Model model = test::model_from(R"({
    "bodies": [{"name": "top", "type": "rigid", "mass": 1.5, "com": [0.1, 0.2, 0.3],
                "inertia": [[0.03, 0, 0], [0, 0.04, 0], [0, 0, 0.05]],
                "velocity": [1, -0.5, 0.25], "angular_velocity": [0, 0, 7]}],
    "solver": {"end": 0.3, "step": 1e-3},
    "outputs": [{"name": "v", "type": "node_velocity", "body": "top", "at": [0.3, 0.1, 0.35]},
                {"name": "p", "type": "node_position", "body": "top", "at": [0.3, 0.1, 0.35]},
                {"name": "c", "type": "node_position", "body": "top"},
                {"name": "w", "type": "body_angular_velocity", "body": "top"}]
  })");
  Data data(model);
  initialize(model, data);
  for (int i = 0; i < 300; ++i) step(model, data);
  const auto v = output(model, data, "v"), p = output(model, data, "p"), cg = output(model, data, "c"), w = output(model, data, "w");
  const Eigen::Vector3d omega(0, 0, 7), vG(1, -0.5, 0.25);
  const Eigen::Vector3d ref = vG + omega.cross(Eigen::Vector3d(p[0] - cg[0], p[1] - cg[1], p[2] - cg[2]));
  std::printf("spin: v = (%.12f, %.12f, %.12f), omega x r: (%.12f, %.12f, %.12f); omega_z = %.12f\n", v[0], v[1], v[2], ref(0), ref(1),
              ref(2), w[2]);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(v[i], ref(i), 1e-9);
    EXPECT_NEAR(w[i], omega(i), 1e-9);
  }
}

// A flexible body (synthetic point masses on three modes) hung at node A and swinging under
// gravity: node C's velocity against the central difference of its position over neighbouring
// steps (second order: the difference is ~h^2/6 times the jerk).
TEST(Velocity, FlexibleNodeVelocityIsTheRateOfItsPosition) {
  test::TempDir dir("reaction_flex");
  test::write_sid_file(test::lumpy_body(3, 7, true, 0.02), dir / "lumpy.sid.h5");
  const Model model = test::model_from(R"({
    "gravity": [0, -9.81, 0],
    "bodies": [{"name": "flap", "type": "flexible", "sid": "lumpy.sid.h5", "angular_velocity": [0.5, 0, 2]}],
    "joints": [{"name": "hinge", "type": "spherical", "body1": "ground", "body2": "flap", "node2": "A"}],
    "solver": {"end": 0.2, "step": 1e-4},
    "outputs": [{"name": "v", "type": "node_velocity", "body": "flap", "node": "C"},
                {"name": "p", "type": "node_position", "body": "flap", "node": "C"}]
  })", dir.path);
  Data data(model);
  initialize(model, data);
  std::vector<Eigen::Vector3d> pos, vel;
  for (int i = 0; i <= 2000; ++i) {
    if (i > 0) step(model, data);
    const auto v = output(model, data, "v"), p = output(model, data, "p");
    pos.emplace_back(p[0], p[1], p[2]);
    vel.emplace_back(v[0], v[1], v[2]);
  }
  double worst = 0, vmax = 0;
  for (std::size_t i = 1; i + 1 < pos.size(); ++i) {
    const Eigen::Vector3d fd = (pos[i + 1] - pos[i - 1]) / 2e-4;
    worst = std::max(worst, (fd - vel[i]).cwiseAbs().maxCoeff());
    vmax = std::max(vmax, vel[i].cwiseAbs().maxCoeff());
  }
  std::printf("flexible node velocity vs central difference: worst %.3e m/s of %.3f m/s\n", worst, vmax);
  EXPECT_GT(vmax, 0.1);
  EXPECT_LT(worst, 1e-5 * vmax);
}

// A spring's tension is k (l - length0) + c l_dot from the positions and velocities of its two
// ends (here read as outputs), and a bushing's force on body2 is -k times the displacement
// of its point along each axis (translational, no rotation: a body on a bushing moving straight).
TEST(ElementForce, SpringAndBushingFollowTheirLaws) {
  const Model model = test::model_from(R"({
    "bodies": [{"name": "m", "type": "rigid", "mass": 1, "com": [0, 0, -1], "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]],
                "velocity": [0.3, 0.2, -0.4]},
               {"name": "n", "type": "rigid", "mass": 2, "com": [3, 0, 0], "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]],
                "velocity": [0.1, -0.2, 0.05]}],
    "forces": [{"name": "s", "type": "spring_damper", "body1": "ground", "at1": [0, 0, 0], "body2": "m", "k": 200, "c": 3, "length0": 0.8},
               {"name": "bu", "type": "bushing", "body1": "ground", "body2": "n", "at": [3, 0, 0],
                "stiffness": [100, 200, 300, 10, 10, 10]}],
    "solver": {"end": 0.1, "step": 1e-3},
    "outputs": [{"name": "Fs", "type": "element_force", "force": "s"}, {"name": "Fb", "type": "element_force", "force": "bu"},
                {"name": "p", "type": "node_position", "body": "m"}, {"name": "v", "type": "node_velocity", "body": "m"},
                {"name": "q", "type": "node_position", "body": "n"}]
  })");
  Data data(model);
  initialize(model, data);
  for (int i = 0; i < 100; ++i) step(model, data);
  const auto Fs = output(model, data, "Fs"), Fb = output(model, data, "Fb"), p = output(model, data, "p"), v = output(model, data, "v"),
             q = output(model, data, "q");
  const Eigen::Vector3d P(p[0], p[1], p[2]), V(v[0], v[1], v[2]);
  const double ref = 200 * (P.norm() - 0.8) + 3 * P.dot(V) / P.norm();
  const Eigen::Vector3d u(q[0] - 3, q[1], q[2]);
  std::printf("spring tension %.12f (law %.12f); bushing force (%.9f, %.9f, %.9f), -k u = (%.9f, %.9f, %.9f)\n", Fs[0], ref, Fb[0], Fb[1],
              Fb[2], -100 * u(0), -200 * u(1), -300 * u(2));
  EXPECT_NEAR(Fs[0], ref, 1e-10 * std::abs(ref));
  EXPECT_NEAR(Fb[0], -100 * u(0), 1e-9);
  EXPECT_NEAR(Fb[1], -200 * u(1), 1e-9);
  EXPECT_NEAR(Fb[2], -300 * u(2), 1e-9);
  for (int i = 3; i < 6; ++i) EXPECT_NEAR(Fb[i], 0, 1e-9);
}

// The element forces of the laws with tables, preloads and friction are the elements' own, by
// statics and Coulomb's law: a 2 kg slider hanging from a spring with a force table and a
// preload, and a 3 kg slider standing on a bushing with a table and a preload, both settled
// statically (each element then carries its body's weight, whatever the split between table and
// preload); a 1 kg slider pushed along a guide against a friction damper of 4 N, its end moving
// away faster than the regularisation band: the damper pulls with exactly 4 N.
TEST(ElementForce, TablesPreloadsAndFrictionAreTheElementsOwn) {
  const char* sliders = R"(
    "bodies": [{"name": "a", "type": "rigid", "mass": 2, "com": [0, 0, -1], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]},
               {"name": "b", "type": "rigid", "mass": 3, "com": [2, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]}],
    "joints": [{"name": "ga", "type": "prismatic", "body1": "ground", "body2": "a", "at": [0, 0, -1], "axis": [0, 0, 1]},
               {"name": "gb", "type": "prismatic", "body1": "ground", "body2": "b", "at": [2, 0, 0], "axis": [0, 0, 1]}],
    "forces": [{"name": "s", "type": "spring_damper", "body1": "ground", "at1": [0, 0, 0], "body2": "a", "preload": 5,
                "force_table": {"x": [-1, 0, 0.02, 1], "value": [-800, 0, 10, 900]}},
               {"name": "bu", "type": "bushing", "body1": "ground", "body2": "b", "at": [2, 0, 0],
                "stiffness": [100, 100, 0, 10, 10, 10], "preload": {"force": [0, 0, -7], "torque": [0, 0, 0]},
                "tables": {"z": {"x": [-1, 0, 1], "value": [-500, 0, 500]}}}],)";
  const Model statics = test::model_from(std::string(R"({"gravity": [0, 0, -9.81],)") + sliders + R"(
    "solver": {"analysis": "static"},
    "outputs": [{"name": "Fs", "type": "element_force", "force": "s"}, {"name": "Fb", "type": "element_force", "force": "bu"}]})");
  Data data(statics);
  initialize(statics, data);
  const auto Fs = output(statics, data, "Fs"), Fb = output(statics, data, "Fb");
  std::printf("settled: spring tension %.9f N (weight %.9f), bushing force on the slider (%.2e, %.2e, %.9f) N (weight %.9f)\n", Fs[0],
              2 * g, Fb[0], Fb[1], Fb[2], 3 * g);
  EXPECT_NEAR(Fs[0], 2 * g, 1e-8);
  EXPECT_NEAR(Fb[2], 3 * g, 1e-8);  // the bushing holds the slider up
  for (int i : {0, 1, 3, 4, 5}) EXPECT_NEAR(Fb[static_cast<std::size_t>(i)], 0, 1e-8);

  const Model friction = test::model_from(R"({
    "bodies": [{"name": "m", "type": "rigid", "mass": 1, "com": [1, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]],
                "velocity": [2, 0, 0]}],
    "joints": [{"name": "guide", "type": "prismatic", "body1": "ground", "body2": "m", "at": [1, 0, 0], "axis": [1, 0, 0]}],
    "forces": [{"name": "f", "type": "friction_damper", "body1": "ground", "at1": [0, 0, 0], "body2": "m", "force": 4}],
    "solver": {"end": 0.1, "step": 1e-3},
    "outputs": [{"name": "F", "type": "element_force", "force": "f"}, {"name": "v", "type": "node_velocity", "body": "m"}]})");
  Data fd(friction);
  initialize(friction, fd);
  for (int i = 0; i < 100; ++i) step(friction, fd);
  const double F = output(friction, fd, "F")[0], v = output(friction, fd, "v")[0];
  std::printf("sliding at %.6f m/s (Coulomb: 2 - 4 t = %.6f): friction force %.12f N\n", v, 2 - 4 * 0.1, F);
  EXPECT_NEAR(v, 2 - 4 * 0.1, 1e-9);  // a constant 4 N deceleration of 1 kg
  EXPECT_NEAR(F, 4, 1e-12);
}

// A bar turned by a motion at a constant 3 rad/s about a horizontal hinge (its frame at the
// hinge, its centre of mass d = 0.5 m out along x; the angle about +y turns x towards -z): the
// hinge's reaction is the bar's d'Alembert force and the motion's torque, by Newton-Euler for a
// rigid body in uniform rotation, F = m (a_G - g) with a_G = -omega^2 (G - O), and about the
// hinge T_y = -m g d cos(theta) (the drive holds the weight's moment; I alpha = 0). The bar would
// be driven (eliminated) without the output.
namespace {
double driven_hinge_error(const char* solver) {
  const Model model = test::model_from(std::string(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "bar", "type": "rigid", "mass": 1.0, "com": [0.5, 0, 0], "position": [0, 0, 0],
                "inertia": [[6.6666666666666667e-5, 0, 0], [0, 0.08336666666666667, 0], [0, 0, 0.08336666666666667]]}],
    "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bar", "at": [0, 0, 0], "axis": [0, 1, 0]}],
    "motions": [{"joint": "hinge", "table": {"t": [0, 1], "value": [0, 3]}}],
    "solver": )") + solver + R"(,
    "outputs": [{"name": "R", "type": "joint_reaction", "joint": "hinge"}, {"name": "rate", "type": "joint_rate", "joint": "hinge"}]
  })");
  EXPECT_FALSE(model.bodies[0].driven());
  Data data(model);
  initialize(model, data);
  double worst = 0;
  for (int i = 1; i <= 500; ++i) {
    step(model, data);
    if (i % 100 != 0) continue;
    const double th = joint_coordinate(model, data, 0, JointCoordinate::Angle), w = 3.0, m = 1.0, dG = 0.5;
    const Eigen::Vector3d r(dG * std::cos(th), 0, -dG * std::sin(th));
    const Eigen::Vector3d F = m * (-w * w * r - Eigen::Vector3d(0, 0, -g));
    const double Ty = -m * g * dG * std::cos(th);
    const auto R = output(model, data, "R");
    EXPECT_NEAR(output(model, data, "rate")[0], 3.0, 1e-9);
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(R[k] - F(k)));
    worst = std::max({worst, std::abs(R[4] - Ty), std::abs(R[3]), std::abs(R[5])});
    if (i == 500) std::printf("%s: driven hinge at theta = %.3f: F = (%.9f, %.3e, %.9f) N [%.9f, 0, %.9f], T_y = %.9f N m [%.9f]\n", solver, th, R[0],
                              R[1], R[2], F(0), F(2), R[4], Ty);
  }
  return worst;
}
}  // namespace

TEST(Reaction, DrivenHingeGivesTheDriveTorque) {
  // The multipliers hold the accelerations' projection to its tolerance: 1e-6 of the 14 N here.
  EXPECT_LT(driven_hinge_error(R"({"end": 0.5, "step": 1e-3})"), 1e-5);
  const double ga = driven_hinge_error(R"({"end": 0.5, "step": 1e-3, "integrator": "generalized_alpha", "spectral_radius": 0.7})");
  std::printf("generalized-alpha: worst %.3e\n", ga);
  EXPECT_LT(ga, 1e-5);
}

// Bad output definitions are refused naming the field (ffr-sim: exit status 2, nothing written).
TEST(Reaction, BadOutputsAreRefused) {
  const char* cases[][2] = {
      {R"({"name": "o", "type": "element_force", "force": "nothing"})", "no spring_damper, bushing, friction_damper or tire named 'nothing'"},
      {R"({"name": "o", "type": "element_force", "force": "push"})", "is a point load"},
      {R"({"name": "o", "type": "node_velocity", "body": "b", "force": "s"})", "is a key of element_force outputs"},
      {R"({"name": "o", "type": "joint_reaction", "joint": "nothing"})", "unknown joint 'nothing'"},
      {R"({"name": "o", "type": "joint_rate", "joint": "ball"})", "has no joint coordinate"},
      {R"({"name": "o", "type": "body_angular_velocity", "body": "ground"})", "the ground does not move"},
      {R"({"name": "o", "type": "element_force"})", "force"},
  };
  for (const auto& c : cases) {
    const std::string json = std::string(R"({"bodies": [{"name": "b", "type": "rigid", "mass": 1, "com": [0, 0, 0],
      "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}],
      "joints": [{"name": "ball", "type": "spherical", "body1": "ground", "body2": "b", "at": [0, 0, 0]}],
      "forces": [{"name": "s", "type": "spring_damper", "body1": "ground", "at1": [1, 0, 0], "body2": "b", "k": 1},
                 {"name": "push", "type": "point_force", "body": "b", "table": {"t": [0], "value": [[1, 0, 0]]}}],
      "solver": {"end": 1, "step": 0.1}, "outputs": [)") + c[0] + "]}";
    try {
      test::model_from(json);
      ADD_FAILURE() << "accepted: " << c[0];
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find(c[1]), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("outputs[0]"), std::string::npos) << e.what();
    }
  }
}
