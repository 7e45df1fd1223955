// Tyres on roads (MODEL_FILE.md "Roads" and "Forces", FORMULATION.md section 8, tyres) against
// references computed here by hand:
//  - statics of a wheel on a flat road (Hooke: deflection m g / k) and on a uniform incline (the
//    normal force's vertical part carries the weight: N = m g / cos(theta), its horizontal part
//    m g tan(theta) taken by the guide);
//  - rolling without slip (kinematics of a disc rolling on a plane: v = omega r, r the distance of
//    the centre from the road) for a wheel left free to spin, started without spin;
//  - Coulomb's law of sliding friction (F = mu N) for a locked wheel dragged over the road, the
//    drag read both from the tyre and from the force the prescribed motion needs;
//  - the slip angle of a wheel driven at an angle to its plane (kinematics) and its side force;
//  - a locked wheel parked on an incline creeping at the speed its regularisation predicts;
//  - a wheel rolling down an incline (the rolling disc's acceleration) and a wheel bouncing on
//    its tyre (energy conservation with the tyre's potential, the peak force from the energy);
//  - a tyre on a flexible body's node against linear statics from the SID's members;
//  - the exact tangent against central differences of the generalized forces;
//  - bad input refused naming the file and field, and ffr-sim's exit status 2.
#include "central_differences.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

using test::central_differences;
using test::rel_err;

constexpr double g = 9.81;

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

using test::output;

// A 20 kg wheel on a vertical guide over a road through (s, height) = (-10, h0 - 10 slope) and
// (10, h0 + 10 slope), its centre `z0` above the origin; tyre of radius 0.3 m, k = 2e5 N/m.
std::string wheel_on_guide(double h0, double slope, double z0) {
  return R"({
    "gravity": [0, 0, -9.81],
    "roads": [{"name": "r", "direction": [1, 0, 0], "s": [-10, 10], "height": [)" + num(h0 - 10 * slope) + ", " +
         num(h0 + 10 * slope) + R"(]}],
    "bodies": [{"name": "wheel", "type": "rigid", "mass": 20, "com": [0, 0, )" + num(z0) + R"(],
                "inertia": [[0.5, 0, 0], [0, 0.8, 0], [0, 0, 0.5]]}],
    "joints": [{"name": "guide", "type": "prismatic", "body1": "ground", "body2": "wheel", "at": [0, 0, )" + num(z0) +
         R"(], "axis": [0, 0, 1]}],
    "forces": [{"name": "tyre", "type": "tire", "body": "wheel", "axis": [0, 1, 0], "radius": 0.3,
                "vertical_stiffness": 2e5, "vertical_damping": 500, "longitudinal_stiffness": 1e5,
                "cornering_stiffness": 5e4, "friction": 0.9, "road": "r"}],
    "solver": {"analysis": "static"},
    "outputs": [{"name": "c", "type": "node_position", "body": "wheel"},
                {"name": "tyre", "type": "element_force", "force": "tyre"},
                {"name": "guide", "type": "joint_reaction", "joint": "guide"}]
  })";
}

}  // namespace

// Hooke: the wheel settles m g / k into a flat road 0.1 m high, the tyre then carrying its weight.
TEST(Tire, StaticDeflectionIsWeightOverStiffness) {
  const double m = 20, k = 2e5, R = 0.3, h0 = 0.1;
  const Model model = test::model_from(wheel_on_guide(h0, 0, h0 + R - 0.001));
  Data data(model);
  initialize(model, data);
  const double z = output(model, data, "c")[2];
  const auto ty = output(model, data, "tyre");
  std::printf("flat road: centre %.12f m (h + R - m g / k = %.12f), Fn %.9f N (m g = %.9f), deflection %.3e (m g / k %.3e)\n", z,
              h0 + R - m * g / k, ty[2], m * g, ty[5], m * g / k);
  EXPECT_NEAR(z, h0 + R - m * g / k, 1e-10);
  EXPECT_NEAR(ty[2], m * g, 1e-6);
  EXPECT_NEAR(ty[5], m * g / k, 1e-12);
  EXPECT_NEAR(ty[0], 0, 1e-9);  // at rest: no slip, no horizontal force
  EXPECT_NEAR(ty[1], 0, 1e-9);
}

// A uniform incline of slope 0.2: the road pushes along its normal n = (-sin, 0, cos) theta, so
// N cos(theta) = m g, the deflection is N / k along n and the centre sits (R - N / k) / cos(theta)
// above the road point under it; the guide takes N sin(theta) = m g tan(theta) sideways.
TEST(Tire, StaticDeflectionOnAnIncline) {
  const double m = 20, k = 2e5, R = 0.3, slope = 0.2, h0 = 0.05;
  const double cs = 1 / std::sqrt(1 + slope * slope);
  const Model model = test::model_from(wheel_on_guide(h0, slope, h0 + R / cs - 0.001));
  Data data(model);
  initialize(model, data);
  const double N = m * g / cs;
  const double z = output(model, data, "c")[2];
  const auto ty = output(model, data, "tyre");
  const auto guide = output(model, data, "guide");
  std::printf("incline: centre %.12f m (%.12f), Fn %.9f N (m g / cos %.9f), guide %.9f N (m g tan %.9f)\n", z,
              h0 + (R - N / k) / cs, ty[2], N, guide[0], m * g * slope);
  EXPECT_NEAR(z, h0 + (R - N / k) / cs, 1e-10);
  EXPECT_NEAR(ty[2], N, 1e-6);
  EXPECT_NEAR(ty[5], N / k, 1e-12);
  EXPECT_NEAR(guide[0], m * g * slope, 1e-6);  // the ground pushes the wheel up the slope's rise (+x)
}

// At rest the tyres have no horizontal stiffness (their horizontal forces come from sliding): a
// car body held by nothing but its four tyres has neutral motions in the road's plane (x, y, yaw).
// With no force along them (a flat road) the static analysis settles the stiff motions and
// accepts the neutral ones with a note naming them (FORMULATION.md section 14); the tyres then
// carry the weight (vertical force balance). It was refused as singular before neutral motions
// were accepted.
TEST(Tire, StaticEquilibriumOnTyresAloneHasNeutralMotions) {
  std::string tyres;
  const double corners[4][2] = {{1.2, 0.7}, {1.2, -0.7}, {-1.2, 0.7}, {-1.2, -0.7}};
  for (int i = 0; i < 4; ++i)
    tyres += std::string(i ? ", " : "") + R"({"type": "tire", "body": "car", "center": [)" + num(corners[i][0]) + ", " + num(corners[i][1]) +
             R"(, 0.3], "axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": 2e5, "longitudinal_stiffness": 1e5,
               "cornering_stiffness": 5e4, "friction": 0.9, "road": "r"})";
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "roads": [{"name": "r", "direction": [1, 0, 0], "s": [-10, 10], "height": [0, 0]}],
    "bodies": [{"name": "car", "type": "rigid", "mass": 800, "com": [0.1, 0, 0.5], "inertia": [[300, 0, 0], [0, 1000, 0], [0, 0, 1100]]}],
    "forces": [)" + tyres + R"(],
    "solver": {"analysis": "static"}
  })");
  Data data(model);
  const auto notes = initialize(model, data);
  ASSERT_EQ(notes.size(), 2u);
  std::printf("%s\n", notes[1].c_str());
  EXPECT_NE(notes[1].find("neutral motion"), std::string::npos);
  EXPECT_NE(notes[1].find("body 'car'"), std::string::npos);
  // Rigid-body statics (small angles): the axles carry m g (x_G - x_r) / wb (front) and the rest
  // (rear), each tyre half of it, pressed by its load over k; the centre of mass sinks by the
  // deflection interpolated between the axles at x_G.
  const double m = 800, k = 2e5, xg = 0.1, wb = 2.4;
  const double df = m * g * (xg + 1.2) / wb / 2 / k, dr = m * g * (1.2 - xg) / wb / 2 / k;
  const double sink = dr + (df - dr) * (xg + 1.2) / wb;
  const double z = data.state.q(model.bodies[0].offset + 2);
  std::printf("car body centre of mass %.9f m (statics %.9f)\n", z, 0.5 - sink);
  EXPECT_NEAR(z, 0.5 - sink, 1e-4 * sink);
}

// A tyre on a node of a flexible body: a clamped Euler-Bernoulli chain (1.2 m, EI = 400 N m^2 in
// z, 24 modes; formats/synthetic.hpp) whose tip node carries a tyre pressed 1 cm into a flat road.
// Linear statics from the SID's own members: the tip rises by w = phi_B q (phi_B the tip's
// vertical mode slice) and the tyre pushes with P = k (delta0 - w), so
//   (Ke + k phi_B^T phi_B) q = Ct g + k delta0 phi_B^T,
// solved here; the tyre's force against P and, as a sanity bound, the tip against two springs in
// series (Roark's tip-loaded cantilever, 3 E I / l^3, in series with k; Roark's Formulas for Stress
// and Strain, 7th ed., Table 8.1 case 1a) plus the gravity sag.
TEST(Tire, OnAFlexibleBodysNodeLinearStatics) {
  test::TempDir dir("tire_node");
  ffr::formats::synthetic::ChainParams p;
  p.points = 41;
  p.length = 1.2;
  p.mass = 3.6;
  p.EA = 1e8;
  p.EIy = 400;
  p.EIz = 4000;
  p.clamped = true;
  p.modes = 24;
  const auto chain = ffr::formats::synthetic::spring_chain(p);
  test::write_sid_file(chain.sid, dir / "chain.sid.h5");
  const double k = 1000, delta0 = 0.01, R = 0.3;
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "roads": [{"name": "r", "direction": [1, 0, 0], "s": [-10, 10], "height": [)" + num(delta0 - R) + ", " + num(delta0 - R) + R"(]}],
    "bodies": [{"name": "beam", "type": "flexible", "sid": "chain.sid.h5"}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "beam"}],
    "forces": [{"name": "tyre", "type": "tire", "body": "beam", "node": "B", "axis": [0, 1, 0], "radius": 0.3,
                "vertical_stiffness": 1000, "road": "r"}],
    "solver": {"analysis": "static"},
    "outputs": [{"name": "q", "type": "modal_coordinates", "body": "beam"}, {"name": "tyre", "type": "element_force", "force": "tyre"},
                {"name": "tip", "type": "node_deformation", "body": "beam", "node": "B"}]
  })", dir.path);
  Data data(model);
  initialize(model, data);
  int b = -1;
  for (std::size_t i = 0; i < chain.sid.nodes.size(); ++i)
    if (chain.sid.nodes[i].name == "B") b = static_cast<int>(i);
  ASSERT_GE(b, 0);
  const Eigen::VectorXd phi = chain.sid.nodes[static_cast<std::size_t>(b)].phi.row(2).transpose();
  const Eigen::MatrixXd A = chain.sid.Ke + k * phi * phi.transpose();
  const Eigen::VectorXd ref = A.ldlt().solve(chain.sid.Ct.M0 * Eigen::Vector3d(0, 0, -9.81) + k * delta0 * phi);
  const auto q = output(model, data, "q");
  double worst = 0;
  for (Eigen::Index i = 0; i < ref.size(); ++i) worst = std::max(worst, std::abs(q[static_cast<std::size_t>(i)] - ref(i)));
  const double w = phi.dot(ref), P = k * (delta0 - w);
  const auto ty = output(model, data, "tyre");
  const double tip = output(model, data, "tip")[2];
  // Two springs in series, less the sag under the chain's own weight (w_g = m g l^3 / (8 E I)).
  const double kb = 3 * 400 / std::pow(1.2, 3), sag = 3.6 * 9.81 * std::pow(1.2, 3) / (8 * 400);
  const double w_roark = (k * (delta0 + sag) / (k + kb)) - sag;
  std::printf("tyre at a node: modal worst %.3e of %.3e; tip %.9f m (SID statics %.9f, Roark in series %.6f); Fn %.9f N (%.9f)\n",
              worst, ref.cwiseAbs().maxCoeff(), tip, w, w_roark, ty[2], P);
  EXPECT_LT(worst, 1e-8 * ref.cwiseAbs().maxCoeff());
  EXPECT_NEAR(tip, w, 1e-9);
  EXPECT_NEAR(ty[2], P, 1e-6 * P);
  EXPECT_NEAR(tip, w_roark, 0.02 * std::abs(w_roark));  // lumping and 24 modes
}

namespace {

// A cart driven at 10 m/s along (cos beta, sin beta, 0) carries a wheel (radius 0.3 m, I = 1.2 kg m^2
// about its axle y) 0.29 m above a flat road: the tyre is pressed 0.01 m, Fn = 2000 N.
// `wheel_joint` is the wheel's joint to the cart (revolute: free to spin; fixed: locked).
std::string dragged_wheel(const std::string& wheel_joint, double beta = 0) {
  const std::string v = "[" + num(10 * std::cos(beta)) + ", " + num(10 * std::sin(beta)) + ", 0]";
  const std::string axis = "[" + num(std::cos(beta)) + ", " + num(std::sin(beta)) + ", 0]";
  return R"({
    "gravity": [0, 0, -9.81],
    "roads": [{"name": "flat", "direction": [1, 0, 0], "s": [-10, 100], "height": [0, 0]}],
    "bodies": [
      {"name": "cart", "type": "rigid", "mass": 10, "com": [0, 0, 0.29], "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
       "velocity": )" + v + R"(},
      {"name": "wheel", "type": "rigid", "mass": 15, "com": [0, 0, 0.29], "inertia": [[0.7, 0, 0], [0, 1.2, 0], [0, 0, 0.7]],
       "velocity": )" + v + R"(}],
    "joints": [
      {"name": "track", "type": "prismatic", "body1": "ground", "body2": "cart", "at": [0, 0, 0.29], "axis": )" + axis + R"(},
      {"name": "axle", "type": ")" + wheel_joint + R"(", "body1": "cart", "body2": "wheel", "at": [0, 0, 0.29], "axis": [0, 1, 0]}],
    "motions": [{"joint": "track", "speed": {"t": [0, 1], "value": [10, 10]}}],
    "forces": [{"name": "tyre", "type": "tire", "body": "wheel", "center": [0, 0, 0.29], "axis": [0, 1, 0], "radius": 0.3,
                "vertical_stiffness": 2e5, "vertical_damping": 1000, "longitudinal_stiffness": 1e5,
                "cornering_stiffness": 5e4, "friction": 0.9, "road": "flat"}],
    "solver": {"end": 0.5, "step": 1e-3},
    "outputs": [{"name": "spin", "type": "body_angular_velocity", "body": "wheel"},
                {"name": "tyre", "type": "element_force", "force": "tyre"},
                {"name": "track", "type": "joint_reaction", "joint": "track"}]
  })";
}

}  // namespace

// Started without spin, the wheel is dragged sliding (Fx = -mu Fn, Coulomb) until its spin
// reaches rolling without slip, omega = v / r with r = 0.29 m the centre's height over the road
// (the contact point is on the road: the loaded radius), where it stays with Fx = 0.
TEST(Tire, FreeWheelRollsWithoutSlip) {
  const double V = 10, r = 0.29, Fn = 2e5 * 0.01, mu = 0.9;
  const Model model = test::model_from(dragged_wheel("revolute"));
  Data data(model);
  initialize(model, data);
  double Fx_early = 0, omega_early = 0;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    if (i == 9) {
      Fx_early = output(model, data, "tyre")[0];
      omega_early = output(model, data, "spin")[1];
    }
  }
  const auto ty = output(model, data, "tyre");
  const double omega = output(model, data, "spin")[1];
  std::printf("t = 0.01 s: Fx %.6f N (-mu Fn = %.6f), omega %.4f rad/s; t = 0.5 s: omega %.12f rad/s (v / r = %.12f), Fx %.3e N, "
              "slip %.3e, Fn %.6f N\n",
              Fx_early, -mu * Fn, omega_early, omega, V / r, ty[0], ty[3], ty[2]);
  EXPECT_NEAR(Fx_early, -mu * Fn, 1e-6 * Fn);  // sliding: saturated
  EXPECT_LT(omega_early, 0.5 * V / r);
  EXPECT_NEAR(omega, V / r, 1e-9 * V / r);
  EXPECT_NEAR(ty[0], 0, 1e-6 * Fn);
  EXPECT_NEAR(ty[3], 0, 1e-9);
  EXPECT_NEAR(ty[2], Fn, 1e-6 * Fn);
}

// Locked to the cart, the wheel slides at 10 m/s: the road drags it back with mu Fn (Coulomb), and
// the prescribed motion has to push the cart forward with that force.
TEST(Tire, LockedWheelDragsWithMuTimesLoad) {
  const double Fn = 2e5 * 0.01, mu = 0.9;
  const Model model = test::model_from(dragged_wheel("fixed"));
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < 100; ++i) step(model, data);
  const auto ty = output(model, data, "tyre");
  const auto track = output(model, data, "track");
  std::printf("locked wheel: Fx %.9f N (-mu Fn = %.9f), slip %.9f, Fn %.6f; the motion pushes with %.9f N\n", ty[0], -mu * Fn, ty[3],
              ty[2], track[0]);
  EXPECT_NEAR(ty[0], -mu * Fn, 1e-6 * Fn);
  EXPECT_NEAR(ty[3], -1, 1e-4);  // kappa = -v / sqrt(v^2 + v_tol^2): fully sliding
  EXPECT_NEAR(ty[2], Fn, 1e-6 * Fn);
  EXPECT_NEAR(track[0], mu * Fn, 1e-6 * Fn);
}

// The same wheel free to spin, its cart driven at beta = 0.02 rad to the wheel's plane: it rolls
// at omega r = V cos(beta) (no longitudinal slip), and its slip angle is the angle between its
// plane and its velocity (rolling kinematics), tan(alpha) = -V sin(beta) / sqrt((V cos(beta))^2 +
// v_tol^2), which gives the side force C_alpha tan(alpha) of the linear cornering law (H. B.
// Pacejka, "Tire and Vehicle Dynamics" (3rd ed., 2012), section 1.2: F_y = C_F_alpha alpha in
// the linear range, here in tan(alpha)); the cart's guide holds it.
TEST(Tire, CorneringWheelSideForce) {
  const double V = 10, r = 0.29, beta = 0.02, C = 5e4, vtol = 0.1;
  const Model model = test::model_from(dragged_wheel("revolute", beta));
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const auto ty = output(model, data, "tyre");
  const auto track = output(model, data, "track");
  const double omega = output(model, data, "spin")[1];
  const double tan_alpha = -V * std::sin(beta) / std::hypot(V * std::cos(beta), vtol);
  std::printf("cornering: omega %.9f (V cos(beta) / r = %.9f), alpha %.9f rad (%.9f), Fy %.6f N (C tan(alpha) = %.6f), Fx %.2e; "
              "guide (%.6f, %.6f) N\n",
              omega, V * std::cos(beta) / r, ty[4], std::atan(tan_alpha), ty[1], C * tan_alpha, ty[0], track[0], track[1]);
  EXPECT_NEAR(omega, V * std::cos(beta) / r, 1e-9 * V / r);
  EXPECT_NEAR(ty[4], std::atan(tan_alpha), 1e-9);
  EXPECT_NEAR(ty[1], C * tan_alpha, 1e-6 * std::abs(C * tan_alpha));
  EXPECT_NEAR(ty[0], 0, 1e-6 * ty[2]);  // (what Newton's tolerance leaves: 1e-5 N)
  // The tyre pushes the wheel by Fy along the axle (y); the ground holds the cart against it.
  EXPECT_NEAR(track[0], 0, 1e-6 * ty[2]);
  EXPECT_NEAR(track[1], -C * tan_alpha, 1e-6 * std::abs(C * tan_alpha));
}

// Rolling down an incline of slope 0.1: a carrier slides along the slope on a guide parallel to it
// and holds the wheel's axle at rho = 0.29 m from the road plane (Fn = k (R - rho) = 2000 N). Only
// the tyre's longitudinal force turns the wheel, so the rolling disc's law holds (Newton-Euler for
// rolling without slip, e.g. J. L. Meriam and L. G. Kraige, "Engineering Mechanics: Dynamics",
// rolling wheel on an incline): (M + I / rho^2) a = M g sin(theta), M the translating mass; from
// rest the carrier covers a t^2 / 2. Generalized-alpha (rho_inf = 0.5): see the force's check.
TEST(Tire, RollsDownAnInclineLikeARollingDisc) {
  const double slope = 0.1, th = std::atan(slope), rho = 0.29, mc = 10, mw = 15, I = 1.2, T = 1.0;
  const Vector3d along(std::cos(th), 0, std::sin(th)), normal(-std::sin(th), 0, std::cos(th));
  const Vector3d c0 = rho * normal;  // the axle above the road point at s = 0 (height 0)
  auto v3 = [](const Vector3d& v) { return "[" + num(v(0)) + ", " + num(v(1)) + ", " + num(v(2)) + "]"; };
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "roads": [{"name": "hill", "direction": [1, 0, 0], "s": [-20, 20], "height": [-2, 2]}],
    "bodies": [
      {"name": "cart", "type": "rigid", "mass": 10, "com": )" + v3(c0) + R"(, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
      {"name": "wheel", "type": "rigid", "mass": 15, "com": )" + v3(c0) + R"(, "inertia": [[0.7, 0, 0], [0, 1.2, 0], [0, 0, 0.7]]}],
    "joints": [
      {"name": "slope", "type": "prismatic", "body1": "ground", "body2": "cart", "at": )" + v3(c0) + R"(, "axis": )" + v3(along) + R"(},
      {"name": "axle", "type": "revolute", "body1": "cart", "body2": "wheel", "at": )" + v3(c0) + R"(, "axis": [0, 1, 0]}],
    "forces": [{"name": "tyre", "type": "tire", "body": "wheel", "axis": [0, 1, 0], "radius": 0.3,
                "vertical_stiffness": 2e5, "longitudinal_stiffness": 1e6, "cornering_stiffness": 5e5, "friction": 0.9, "road": "hill"}],
    "solver": {"end": 1.0, "step": 1e-3, "integrator": "generalized_alpha", "spectral_radius": 0.5},
    "outputs": [{"name": "x", "type": "joint_coordinate", "joint": "slope"}, {"name": "tyre", "type": "element_force", "force": "tyre"},
                {"name": "spin", "type": "body_angular_velocity", "body": "wheel"}]
  })");
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const double M = mc + mw, a = M * 9.81 * std::sin(th) / (M + I / (rho * rho));
  const double x = output(model, data, "x")[0], omega = output(model, data, "spin")[1];
  const auto ty = output(model, data, "tyre");
  std::printf("incline: travelled %.9f m (a t^2 / 2 = %.9f, rel. %.2e), omega %.9f rad/s (-a t / rho = %.9f), Fx %.6f N "
              "(I a / rho^2 = %.6f), Fn %.6f N\n",
              x, -0.5 * a * T * T, x / (-0.5 * a * T * T) - 1, omega, -a * T / rho, ty[0], I * a / (rho * rho), ty[2]);
  EXPECT_NEAR(x, -0.5 * a * T * T, 1e-5 * 0.5 * a * T * T);  // downhill: towards -x
  EXPECT_NEAR(omega, -a * T / rho, 1e-5 * a * T / rho);
  // The force that spins the wheel up, I alpha / rho. The slip force is a stiff damper on the
  // sliding velocity (C_kappa / V h / m ~ 1e5 here): the trapezoidal rule leaves it ringing from
  // step to step (the motion is right: the travel agrees to 6e-6 either way, the end-of-step Fx was
  // 5.6 N), hence generalized-alpha, whose balance at its weighted instant leaves 2e-4.
  EXPECT_NEAR(std::abs(ty[0]), I * a / (rho * rho), 5e-4 * I * a / (rho * rho));
  EXPECT_NEAR(ty[2], 2e5 * 0.01, 1e-6 * 2e3);
}

// Parked on the incline with the wheel locked, the tyre holds the weight's downhill part F through
// its speed regularisation alone: sliding at v, the force is C v / sqrt(v^2 + v_tol^2), so the
// wheel creeps at v = v_tol F / sqrt(C^2 - F^2) (FORMULATION.md section 8, tyres; solved here).
TEST(Tire, ParkedOnAnInclineCreepsAtTheRegularisationsSpeed) {
  const double slope = 0.1, th = std::atan(slope), rho = 0.29, M = 25, C = 1e5, vtol = 0.1;
  const Vector3d along(std::cos(th), 0, std::sin(th)), normal(-std::sin(th), 0, std::cos(th));
  const Vector3d c0 = rho * normal;
  auto v3 = [](const Vector3d& v) { return "[" + num(v(0)) + ", " + num(v(1)) + ", " + num(v(2)) + "]"; };
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "roads": [{"name": "hill", "direction": [1, 0, 0], "s": [-20, 20], "height": [-2, 2]}],
    "bodies": [
      {"name": "cart", "type": "rigid", "mass": 10, "com": )" + v3(c0) + R"(, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
      {"name": "wheel", "type": "rigid", "mass": 15, "com": )" + v3(c0) + R"(, "inertia": [[0.7, 0, 0], [0, 1.2, 0], [0, 0, 0.7]]}],
    "joints": [
      {"name": "slope", "type": "prismatic", "body1": "ground", "body2": "cart", "at": )" + v3(c0) + R"(, "axis": )" + v3(along) + R"(},
      {"name": "brake", "type": "fixed", "body1": "cart", "body2": "wheel", "at": )" + v3(c0) + R"(, "axis": [0, 1, 0]}],
    "forces": [{"name": "tyre", "type": "tire", "body": "wheel", "axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": 2e5,
                "longitudinal_stiffness": 1e5, "cornering_stiffness": 5e4, "friction": 0.9, "road": "hill"}],
    "solver": {"end": 0.2, "step": 1e-3, "integrator": "generalized_alpha", "spectral_radius": 0.5},
    "outputs": [{"name": "v", "type": "joint_rate", "joint": "slope"}]
  })");
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const double F = M * 9.81 * std::sin(th), v_ref = vtol * F / std::sqrt(C * C - F * F);
  const double v = output(model, data, "v")[0];
  std::printf("parked: creeps at %.9e m/s (v_tol F / sqrt(C^2 - F^2) = %.9e)\n", v, -v_ref);
  EXPECT_NEAR(v, -v_ref, 1e-4 * v_ref);  // downhill: towards -x
}

// Without damping or slips the tyre is a unilateral spring with the potential 1/2 k delta^2: a
// wheel dropped 5 cm onto it bounces, leaving and hitting the road, with its energy conserved
// (Lagrange's equations with a potential; the trapezoidal rule conserves it to its error at the
// contact's kink).
TEST(Tire, BouncingWheelConservesEnergy) {
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "roads": [{"name": "r", "direction": [1, 0, 0], "s": [-10, 10], "height": [0, 0]}],
    "bodies": [{"name": "wheel", "type": "rigid", "mass": 20, "com": [0, 0, 0.35], "inertia": [[0.5, 0, 0], [0, 0.8, 0], [0, 0, 0.5]]}],
    "joints": [{"name": "guide", "type": "prismatic", "body1": "ground", "body2": "wheel", "at": [0, 0, 0.35], "axis": [0, 0, 1]}],
    "forces": [{"name": "tyre", "type": "tire", "body": "wheel", "axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": 2e5, "road": "r"}],
    "solver": {"end": 1.0, "step": 1e-4},
    "outputs": [{"name": "tyre", "type": "element_force", "force": "tyre"}]
  })");
  Data data(model);
  initialize(model, data);
  const double E0 = energy(model, data).total();
  double worst = 0, fn_max = 0;
  int landings = 0;
  bool in_contact = false;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    worst = std::max(worst, std::abs(energy(model, data).total() - E0));
    const double fn = output(model, data, "tyre")[2];
    fn_max = std::max(fn_max, fn);
    if (fn > 0 && !in_contact) ++landings;
    in_contact = fn > 0;
  }
  // Reference: the drop's energy m g h = 9.81 J; the peak force from 1/2 k d^2 - m g d = m g h.
  const double m = 20, g = 9.81, k = 2e5, dmax = (m * g + std::sqrt(m * g * m * g + 2 * k * m * g * 0.05)) / k;
  std::printf("bouncing: %d landings, energy drift %.3e J of %.3f J, peak Fn %.2f N (energy balance %.2f N)\n", landings, worst,
              E0, fn_max, k * dmax);
  EXPECT_GE(landings, 3);
  EXPECT_LT(worst, 1e-3 * m * g * 0.05);
  EXPECT_NEAR(fn_max, k * dmax, 1e-2 * k * dmax);
}

namespace {

// Two tyres at a generic state, both inside the friction circle (on it the tangent takes the
// secant slope on purpose: FORMULATION.md section 8, tyres): one on a node of a flexible body over
// a curved road, one on a rigid wheel over a straight sloped road.
std::string tangent_model() {
  std::string s = "[", h = "[";
  for (int i = 0; i <= 40; ++i) {
    const double x = -2 + 0.1 * i;
    s += (i ? ", " : "") + num(x);
    h += (i ? ", " : "") + num(0.05 * std::sin(2.1 * x));
  }
  return R"({
  "gravity": [0, 0, -9.81],
  "roads": [{"name": "wavy", "direction": [0.6, 0.8, 0], "s": )" + s + R"(], "height": )" + h + R"(], "interpolation": "spline"},
            {"name": "ramp", "direction": [1, 0, 0], "s": [-5, 5], "height": [-0.5, 0.5]}],
  "bodies": [
    {"name": "flex", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0.1, 0.2, 0.3],
     "orientation": [[0.36, 0.48, -0.8], [-0.8, 0.6, 0], [0.48, 0.64, 0.6]], "modal_coordinates": [0.01, -0.02, 0.015]},
    {"name": "wheel", "type": "rigid", "mass": 2.0, "com": [0.5, 0.1, 0.2],
     "inertia": [[0.02, 0.001, 0], [0.001, 0.03, 0.002], [0, 0.002, 0.025]], "position": [0.4, 0, 0.1]}
  ],
  "forces": [
    {"name": "t1", "type": "tire", "body": "flex", "node": "B", "axis": [0.2, 1, 0.1], "radius": 0.8, "vertical_stiffness": 1e3,
     "vertical_damping": 20, "longitudinal_stiffness": 500, "cornering_stiffness": 400, "friction": 30, "velocity_tolerance": 0.5, "road": "wavy"},
    {"name": "t2", "type": "tire", "body": "wheel", "center": [0.5, 0.1, 0.2], "axis": [0.1, 1, 0.2], "radius": 0.5,
     "vertical_stiffness": 1e3, "vertical_damping": 30, "longitudinal_stiffness": 20, "cornering_stiffness": 15,
     "friction": 1.0, "road": "ramp"}
  ],
  "solver": {"end": 1.0, "step": 1e-3},
  "outputs": [{"name": "t1", "type": "element_force", "force": "t1"}, {"name": "t2", "type": "element_force", "force": "t2"}]
})";
}

// A state off equilibrium for the tangent tests (fixed seed): coordinates moved by up to 0.02,
// rates up to 1.
void random_state(const Data& data, VectorXd& q, VectorXd& qd) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  q = data.state.q;
  qd = data.state.qd;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q(i) += 0.02 * u(rng);
    qd(i) = u(rng);
  }
}

// The generalized forces at (q, qd), which become data's state.
VectorXd forces_at(const Model& model, Data& data, const VectorXd& q, const VectorXd& qd) {
  data.state.q = q;
  data.state.qd = qd;
  update_bodies(model, data);
  update_markers(model, data);
  generalized_forces(model, data, 0.1);
  return data.Q;
}

}  // namespace

TEST(Tire, TangentsMatchFiniteDifferences) {
  test::TempDir dir("tire_jac");
  test::write_sid_file(test::lumpy_body(3), dir / "lumpy.sid.h5");
  const Model model = test::model_from(tangent_model(), dir.path);
  Data data(model);
  VectorXd q, qd;
  random_state(data, q, qd);
  auto forces = [&](const VectorXd& a, const VectorXd& b) { return forces_at(model, data, a, b); };
  forces(q, qd);
  const auto t1 = output(model, data, "t1"), t2 = output(model, data, "t2");
  std::printf("t1: F = (%.4g, %.4g, %.4g), slips %.4g %.4g, deflection %.4g\nt2: F = (%.4g, %.4g, %.4g), slips %.4g %.4g, deflection %.4g\n",
              t1[0], t1[1], t1[2], t1[3], t1[4], t1[5], t2[0], t2[1], t2[2], t2[3], t2[4], t2[5]);
  // Both in contact, with slip forces well inside the circle.
  ASSERT_GT(t1[2], 0);
  ASSERT_GT(t2[2], 0);
  EXPECT_LT(std::hypot(t1[0], t1[1]), 0.9 * 30 * t1[2]);
  EXPECT_GT(std::hypot(t1[0], t1[1]), 0.1 * t1[2]);
  EXPECT_LT(std::hypot(t2[0], t2[1]), 0.9 * t2[2]);
  forces(q, qd);
  force_tangents(model, data, 0.1);
  const MatrixXd K = data.K, C = data.C;
  const MatrixXd Kfd = -central_differences([&](const VectorXd& z) { return forces(z, qd); }, q, 1e-6);
  const MatrixXd Cfd = -central_differences([&](const VectorXd& zd) { return forces(q, zd); }, qd, 1e-6);
  std::printf("K: %.2e (max |K| %.2e), C: %.2e (max |C| %.2e)\n", rel_err(K, Kfd), K.cwiseAbs().maxCoeff(), rel_err(C, Cfd),
              C.cwiseAbs().maxCoeff());
  EXPECT_LT(rel_err(K, Kfd), 1e-6);
  EXPECT_LT(rel_err(C, Cfd), 1e-6);
}

// Sliding well beyond the friction circle (friction lowered until the linear slip forces exceed
// mu Fn by more than tire.cpp's band), the step's first tangent takes the exact slope
// (Data::first_tangent_of_step with the tyre's committed tire_sliding): K and C then match
// central differences of the forces, and the secant slope of later refreshes does not.
TEST(Tire, SlidingTyresFirstTangentIsExact) {
  test::TempDir dir("tire_slide_jac");
  test::write_sid_file(test::lumpy_body(3), dir / "lumpy.sid.h5");
  std::string json = tangent_model();
  const auto lower = [&](const std::string& from, const std::string& to) {
    const auto at = json.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    json.replace(at, from.size(), to);
  };
  lower(R"("friction": 30,)", R"("friction": 0.02,)");
  lower(R"("friction": 1.0,)", R"("friction": 0.05,)");
  const Model model = test::model_from(json, dir.path);
  Data data(model);
  VectorXd q, qd;
  random_state(data, q, qd);
  auto forces = [&](const VectorXd& a, const VectorXd& b) { return forces_at(model, data, a, b); };
  forces(q, qd);
  for (const char* name : {"t1", "t2"}) {
    const auto t = output(model, data, name);
    ASSERT_GT(t[2], 0) << name;
    // On the circle (that the linear law lies beyond tire.cpp's band is what the exact slope
    // below needs: inside it the tangent stays the secant and the comparison fails).
    const double mu = std::string(name) == "t1" ? 0.02 : 0.05;
    EXPECT_NEAR(std::hypot(t[0], t[1]), mu * t[2], 1e-9 * t[2]) << name;
  }
  const MatrixXd Kfd = -central_differences([&](const VectorXd& z) { return forces(z, qd); }, q, 1e-6);
  const MatrixXd Cfd = -central_differences([&](const VectorXd& zd) { return forces(q, zd); }, qd, 1e-6);
  auto tangents = [&](bool exact) {
    forces(q, qd);
    std::fill(data.tire_sliding.begin(), data.tire_sliding.end(), 1);
    data.first_tangent_of_step = exact;
    force_tangents(model, data, 0.1);
    data.first_tangent_of_step = false;
  };
  tangents(true);
  std::printf("exact: K %.2e (max |K| %.2e), C %.2e (max |C| %.2e)\n", rel_err(data.K, Kfd), data.K.cwiseAbs().maxCoeff(),
              rel_err(data.C, Cfd), data.C.cwiseAbs().maxCoeff());
  EXPECT_LT(rel_err(data.K, Kfd), 1e-6);
  EXPECT_LT(rel_err(data.C, Cfd), 1e-6);
  tangents(false);
  std::printf("secant: K %.2e, C %.2e\n", rel_err(data.K, Kfd), rel_err(data.C, Cfd));
  EXPECT_GT(rel_err(data.C, Cfd), 1e-2);
}

// A wheel spun by a motion relative to its free cart at 1.5 times its rolling speed slides at
// kappa ~ 0.5 (its linear slip force over 20 times the friction circle) and pushes the cart and
// wheel (515 kg along the track, at 10 m/s) with Coulomb's mu Fn: the cart's speed grows by
// mu Fn / m t exactly. With the exact slope in each step's first tangent Newton converges at once
// (the force is constant); with the secant slope alone (measured with the exact slope disabled)
// it took 2.00 iterations a step and the cart ended 1.06e-3 m/s slow after 0.21 s (a speed gain
// 0.13 % short of Coulomb's). That is not Newton stopping early: with the secant and at least
// three iterations a step (tried) the cart's speed is the same to 3e-10 m/s. The projections
// cause it: their metric W = M + kv C + kq K carries the secant's damping slope along the slip,
// so the velocity projection corrects the axle's speed motion by moving spin and cart together;
// without the velocity projection the cart was 1.6e-6 m/s slow, without both 3.5e-10
// (runtime/FORMULATION.md, the tyre's tangent).
TEST(Tire, SpunWheelSlidingPushesWithMuTimesLoad) {
  std::string json = dragged_wheel("revolute");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = json.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    json.replace(at, from.size(), to);
  };
  replace(R"("name": "cart", "type": "rigid", "mass": 10,)", R"("name": "cart", "type": "rigid", "mass": 500,)");
  replace(R"("motions": [{"joint": "track", "speed": {"t": [0, 1], "value": [10, 10]}}],)",
          R"("motions": [{"joint": "axle", "speed": {"t": [0, 1], "value": [51.72413793, 51.72413793]}}],)");
  const Model model = test::model_from(json);
  Data data(model);
  initialize(model, data);
  const double Fn = 2e5 * 0.01, mu = 0.9, m = 500 + 15;
  for (int i = 0; i < 210; ++i) step(model, data);
  const double per_step = static_cast<double>(data.stats.newton_iterations) / 210;
  const auto ty = output(model, data, "tyre");
  const double v = data.state.qd(0), v_coulomb = 10 + mu * Fn / m * data.state.t;
  std::printf("spun wheel: Fx %.6f N, Fn %.6f N, slip %.6f; cart at %.12f m/s (Coulomb %.12f); %.2f Newton iterations a step\n",
              ty[0], ty[2], ty[3], v, v_coulomb, per_step);
  EXPECT_NEAR(ty[0], mu * Fn, 1e-6 * Fn);
  EXPECT_GT(ty[3], 0.3);
  EXPECT_NEAR(v, v_coulomb, 1e-8);
  EXPECT_LE(per_step, 1.2);
}

namespace {

// A valid model with one tyre; `road` and `tire` replace the roads list and the tyre's keys.
std::string tire_model(const std::string& roads, const std::string& tire, const std::string& gravity = "[0, 0, -9.81]") {
  return R"({"gravity": )" + gravity + R"(, "roads": )" + roads + R"(,
    "bodies": [{"name": "wheel", "type": "rigid", "mass": 20, "com": [0, 0, 0.3], "inertia": [[0.5, 0, 0], [0, 0.8, 0], [0, 0, 0.5]]}],
    "forces": [{"type": "tire", "body": "wheel", )" + tire + R"(}],
    "solver": {"end": 1, "step": 1e-3}})";
}
const std::string kRoad = R"([{"name": "r", "direction": [1, 0, 0], "s": [0, 10], "height": [0, 0]}])";
const std::string kTire = R"("axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": 2e5, "road": "r")";

}  // namespace

TEST(Tire, BadInputIsRefusedNamingTheField) {
  ASSERT_EQ(test::error_of(tire_model(kRoad, kTire)), "");
  // The reference model parses; each case changes one thing.
  test::expect_error(tire_model(kRoad, R"("axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": 2e5)"), "forces[0].road",
                     "missing required field");
  test::expect_error(tire_model(kRoad, R"("axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": 2e5, "road": "nope")"),
                     "forces[0].road", "unknown road 'nope' (roads: r)");
  test::expect_error(tire_model("[]", kTire), "forces[0].road", "the model has no \"roads\"");
  test::expect_error(tire_model(R"([{"name": "r", "direction": [1, 0, 0], "s": [0, 10, 10], "height": [0, 0, 1]}])", kTire), "roads[0].s",
                     "must be strictly increasing (entry 2)");
  test::expect_error(tire_model(R"([{"name": "r", "direction": [1, 0, 0], "s": [0, 10], "height": [0, 0, 1]}])", kTire),
                     "roads[0].height", "has 3 entries but s has 2");
  test::expect_error(tire_model(R"([{"name": "r", "direction": [1, 0, 0.5], "s": [0, 10], "height": [0, 0]}])", kTire),
                     "roads[0].direction", "must be horizontal");
  test::expect_error(tire_model(kRoad, kTire, "[0, 0, 0]"), "roads[0]", "nonzero \"gravity\"");
  test::expect_error(tire_model(R"([{"name": "r", "direction": [1, 0, 0], "s": [0, 10], "height": [0, 1e999]}])", kTire), "1e999",
                     "not a finite number");
  test::expect_error(tire_model(R"([{"name": "r", "direction": [1, 0, 0], "s": [0, 10], "height": [0, 0], "interpolation": "linear"}])", kTire),
                     "roads[0].interpolation", "linear is not accepted for a road");
  test::expect_error(tire_model(kRoad, R"("axis": [0, 1, 0], "radius": -0.3, "vertical_stiffness": 2e5, "road": "r")"),
                     "forces[0].radius", "expected a positive number, found -0.3");
  test::expect_error(tire_model(kRoad, R"("axis": [0, 1, 0], "radius": 0.3, "vertical_stiffness": 0, "road": "r")"),
                     "forces[0].vertical_stiffness", "expected a positive number");
  test::expect_error(tire_model(kRoad, R"("axis": [0, 0, 1], "radius": 0.3, "vertical_stiffness": 2e5, "road": "r")"),
                     "forces[0].axis", "lies flat on the road");
  test::expect_error(tire_model(kRoad, kTire + R"(, "friction": 0.8)"), "forces[0].friction",
                     "applies only with a longitudinal_stiffness or cornering_stiffness");
  test::expect_error(tire_model(kRoad, kTire + R"(, "longitudinal_stiffness": 1e5)"), "forces[0].friction", "missing required field");
  test::expect_error(tire_model(kRoad, kTire + R"(, "pressure": 2)"), "forces[0].pressure", "unknown field");
  test::expect_error(tire_model(kRoad, kTire + R"(, "center": [0, 0, -0.3])"), "forces[0].center", "0.300000 m below the road 'r'");
  test::expect_error(tire_model(R"([{"name": "r", "direction": [1, 0, 0], "s": [0, 10], "height": [0.5, 0.5]}])", kTire), "forces[0]",
                     "0.200000 m below the road 'r' at set-up (the centre is the body's frame origin");
  test::expect_error(tire_model(R"([{"name": "r", "direction": [1, 0, 0], "s": [0, 10], "height": [0, 0]},
                                    {"name": "r", "direction": [0, 1, 0], "s": [0, 10], "height": [0, 0]}])", kTire),
                     "roads[1].name", "duplicate road name 'r'");
}

// ffr-sim: exit status 2, the file and the field named, no results written.
TEST(Tire, FfrSimExitsWithStatus2OnABadRoad) {
  test::TempDir dir("tire_cli");
  test::write_text(dir / "m.json", tire_model(R"([{"name": "r", "direction": [1, 0, 0], "s": [5, 0], "height": [0, 0]}])", kTire));
  const auto r = test::run_ffr_sim((dir / "m.json").string() + " -o " + (dir / "out.h5").string());
  std::printf("status %d: %s\n", r.status, r.output.c_str());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("m.json"), std::string::npos);
  EXPECT_NE(r.output.find("roads[0].s"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}
