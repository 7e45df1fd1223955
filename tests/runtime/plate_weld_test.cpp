// A rigid body welded (a `fixed` joint) to a node of an ANCF thin plate (FORMULATION.md 16,
// "Welds"): the node's axes are the exact Gram-Schmidt triad of its gradients r_x, r_y. Checked
// against references nobody here computed:
// - the rows' Jacobian, velocity and acceleration terms and second derivatives against central
//   differences of the rows themselves, at a strongly deformed state with a welded node turned
//   by 70 degrees (off the constraint manifold on purpose), rigid bodies and a flexible body's
//   node welded;
// - a cantilever plate strip with a rigid tip bar welded at its two tip nodes, the bar's centre of
//   mass beyond the tip: small-deflection tip deflection and slope against Kirchhoff plate-strip
//   (Euler-Bernoulli with EI = D b, nu = 0) theory for the bar's weight and moment plus the
//   strip's own weight, w = P L^3/(3 D b) + M L^2/(2 D b) + q L^4/(8 D b) (e.g. Timoshenko &
//   Gere, "Mechanics of Materials", cantilever tables); the same weight and moment applied as
//   point forces (a force couple over the last element) against the welded run, their difference
//   being beam theory's for the couple's spread, M d^2 / (6 D b); the bar welded at one tip
//   corner alone (a twist added, antisymmetric across the width) giving the same section means;
// - a large-rotation swing of a welded body on a soft strip: energy conserved to the trapezoidal
//   rule's second order, and the body's axes against the node's triad computed here from the
//   gradients (an independent Gram-Schmidt) to the solver's tolerance;
// - the relative formulation's swing against the absolute one's;
// - bad input refused naming the field.
#include "central_differences.hpp"
#include "state_probe.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/kinematics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace ffr::runtime;
using test::output;

namespace {

using test::central_differences;
using test::rel_err;

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The node's triad from its gradients, written here independently of the runtime's: t1 along
// r_x, t3 along r_x x r_y, t2 = t3 x t1.
Eigen::Matrix3d gram_schmidt(const Eigen::Vector3d& rx, const Eigen::Vector3d& ry) {
  Eigen::Matrix3d T;
  T.col(0) = rx.normalized();
  T.col(2) = rx.cross(ry).normalized();
  T.col(1) = T.col(2).cross(T.col(0));
  return T;
}

// A free plate (2 x 1 elements) with two rigid bodies welded at two nodes, one on each side of
// its joint (body1 and body2), with axes not along the plate's, and a flexible (reduced) body
// welded by a node of its own (node rotation slices) to a third.
struct Weld : ::testing::Test, test::StateProbe {
  test::TempDir dir{"plate_weld"};
  double t = 0.2;

  void SetUp() override {
    test::write_sid_file(test::lumpy_body(3), dir / "lumpy.sid.h5");
    start(test::model_from(R"({"gravity": [0, 0, -9.81],
      "bodies": [
        {"name": "plate", "type": "plate", "corners": [[0, 0, 0], [0.4, 0, 0], [0.4, 0.3, 0], [0, 0.3, 0]], "elements": [2, 1],
         "thickness": 0.01, "E": 1e7, "nu": 0.3, "rho": 1000},
        {"name": "bob", "type": "rigid", "mass": 0.5, "com": [0.45, 0.3, 0.05],
         "inertia": [[1e-3, 0, 0], [0, 2e-3, 0], [0, 0, 1.5e-3]]},
        {"name": "arm", "type": "rigid", "mass": 0.3, "com": [0.2, -0.05, -0.02],
         "inertia": [[1e-3, 1e-4, 0], [1e-4, 2e-3, 0], [0, 0, 1.5e-3]]},
        {"name": "flex", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0, 0.3, 0.05], "modal_coordinates": [0.01, -0.02, 0.015]}],
      "joints": [
        {"name": "weld", "type": "fixed", "body1": "plate", "node1": "n2_1", "body2": "bob", "axis": [0.3, 0.4, 0.866]},
        {"name": "weld2", "type": "fixed", "body1": "arm", "body2": "plate", "node2": "n1_0", "axis": [1, 0, 0]},
        {"name": "weld3", "type": "fixed", "body1": "flex", "node1": "B", "body2": "plate", "node2": "n0_1", "axis": [0, 1, 0]}],
      "solver": {"end": 1, "step": 1e-3}})",
                             dir.path), 5);
    // Node n2_1's gradients turned by 70 degrees, stretched and sheared: far beyond a linearisation.
    const int y = model.bodies[0].offset + 12 + 12 * 5;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(70 * M_PI / 180, Eigen::Vector3d(0.2, 1, 0.4).normalized()).toRotationMatrix();
    q.segment<3>(y + 3) = 1.1 * R.col(0) + Eigen::Vector3d(0.02, -0.03, 0.01) - Eigen::Vector3d::UnitX();
    q.segment<3>(y + 6) = 0.9 * R.col(1) + 0.2 * R.col(0) - Eigen::Vector3d::UnitY();
  }
  VectorXd constraints(const VectorXd& a) { return StateProbe::constraints(a, t); }
};

}  // namespace

TEST_F(Weld, RowsJacobianBiasAndHessianMatchFiniteDifferences) {
  set(q, qd, qdd);
  evaluate_constraints(model, *data, t);
  const MatrixXd J = data->Phiq;
  const VectorXd Phit = data->Phit, gamma = data->gamma;
  const MatrixXd Jfd = central_differences([&](const VectorXd& z) { return constraints(z); }, q, 1e-6);
  // Along the path q + s qd + s^2/2 qdd: Phi_d = J qd, Phi_dd = J qdd + gamma.
  const double eps = 1e-4;
  auto path = [&](double s) { return constraints(q + s * qd + 0.5 * s * s * qdd); };
  const VectorXd p0 = path(0), pp = path(eps), pm = path(-eps);
  const VectorXd d1 = (pp - pm) / (2 * eps), d2 = (pp - 2 * p0 + pm) / (eps * eps);
  // d(Phi_q^T lambda)/dq for fixed lambda.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  const VectorXd lam = VectorXd::NullaryExpr(model.nconstraints, [&](Eigen::Index) { return 10 * u(rng); });
  const Hessians hs = constraint_hessians(lam, t);
  const MatrixXd& H = hs.H;
  const MatrixXd& Hfd = hs.Hfd;
  std::printf("weld rows: Jacobian %.2e, Phi_dot %.2e, Phi_ddot %.2e, Hessian %.2e (max %.2e), Hessian symmetry %.2e\n",
              rel_err(J, Jfd), rel_err(J * qd + Phit, d1), rel_err(J * qdd + gamma, d2), rel_err(H, Hfd), H.cwiseAbs().maxCoeff(),
              (H - H.transpose()).cwiseAbs().maxCoeff());
  EXPECT_LT(rel_err(J, Jfd), 1e-7);
  EXPECT_LT(rel_err(J * qd + Phit, d1), 1e-7);
  EXPECT_LT(rel_err(J * qdd + gamma, d2), 1e-5);  // second differences: eps^2 and round-off
  EXPECT_LT(rel_err(H, Hfd), 1e-6);
  // The node's axes are the triad of its gradients (here, independently) times the weld's
  // constant relative orientation: turning the gradients turns the axes exactly.
  const Joint& w = model.joints[0];
  const Marker& mk = model.markers[static_cast<std::size_t>(w.m1)];
  const int y = model.bodies[0].offset + 12 + 12 * 5;
  const Eigen::Matrix3d T0 = gram_schmidt(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  const Eigen::Matrix3d T = gram_schmidt(q.segment<3>(y + 3) + Eigen::Vector3d::UnitX(), q.segment<3>(y + 6) + Eigen::Vector3d::UnitY());
  set(q, qd, qdd);
  double axes = 0;
  for (int k = 0; k < 3; ++k)
    if (mk.axes[static_cast<std::size_t>(k)])
      axes = std::max(axes, (data->bodies[0].A * T * T0.transpose() * mk.E.col(k) - data->markers[static_cast<std::size_t>(w.m1)].e[static_cast<std::size_t>(k)]).norm());
  std::printf("node axes against the triad of the gradients: %.2e\n", axes);
  EXPECT_LT(axes, 1e-13);
}

namespace {

// A cantilever strip L x b (10 : 1), clamped at x = 0, nu = 0 (plate-strip bending is then
// Euler-Bernoulli's with EI = D b), a rigid tip bar of mass m across the tip, welded at both tip
// nodes, its centre of mass e beyond the tip. With `couple`, no bar: its weight and moment as
// point forces at the tip nodes and the nodes one element in.
struct Strip {
  double L = 1, b = 0.1, h = 0.01, E = 2.1e11, rho = 100, m = 1, e = 0.1, g = 9.81;
  double D() const { return E * h * h * h / 12; }
  double P() const { return m * g; }
  double M() const { return m * g * e; }
  double q() const { return rho * h * b * g; }
};

std::string strip_json(const Strip& s, int nx, bool couple, const std::string& solver = R"({"analysis": "static"})",
                       double E_override = 0, bool one_weld = false) {
  const std::string n = std::to_string(nx), n1 = std::to_string(nx - 1);
  std::string json = R"({"gravity": [0, 0, )" + num(-s.g) + R"(], "bodies": [{"name": "strip", "type": "plate",
      "corners": [[0, 0, 0], [)" + num(s.L) + R"(, 0, 0], [)" + num(s.L) + ", " + num(s.b) + R"(, 0], [0, )" + num(s.b) + R"(, 0]],
      "elements": [)" + n + R"(, 1], "thickness": )" + num(s.h) + R"(, "E": )" + num(E_override > 0 ? E_override : s.E) +
                     R"(, "nu": 0, "rho": )" + num(s.rho) + R"(, "supports": {"x0": "clamped"}})";
  if (!couple) {
    json += R"(, {"name": "bar", "type": "rigid", "mass": )" + num(s.m) + R"(, "com": [)" + num(s.L + s.e) + ", " + num(s.b / 2) +
            R"(, 0], "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]]}],
      "joints": [{"name": "weld0", "type": "fixed", "body1": "strip", "node1": "n)" + n + R"(_0", "body2": "bar"})" +
            (one_weld ? std::string("]") : R"(,
                 {"name": "weld1", "type": "fixed", "body1": "bar", "body2": "strip", "node2": "n)" + n + R"(_1"}])");
  } else {
    const double d = s.L / nx, F = s.M() / d;
    json += "], \"forces\": [";
    for (int j = 0; j < 2; ++j) {
      const std::string jj = std::to_string(j);
      json += std::string(j ? ", " : "") + R"({"name": "tip)" + jj + R"(", "type": "point_force", "body": "strip", "node": "n)" + n + "_" +
              jj + R"(", "table": {"t": [0, 1], "value": [[0, 0, )" + num(-(s.P() + F) / 2) + "], [0, 0, " + num(-(s.P() + F) / 2) +
              R"(]]}}, {"name": "in)" + jj + R"(", "type": "point_force", "body": "strip", "node": "n)" + n1 + "_" + jj +
              R"(", "table": {"t": [0, 1], "value": [[0, 0, )" + num(F / 2) + "], [0, 0, " + num(F / 2) + "]]}}";
    }
    json += "]";
  }
  json += R"(, "solver": )" + solver + R"(, "outputs": [{"name": "tip0", "type": "node_position", "body": "strip", "node": "n)" + n +
          R"(_0"}, {"name": "tip1", "type": "node_position", "body": "strip", "node": "n)" + n + R"(_1"}, {"name": "e", "type": "energy"}]})";
  return json;
}

// The tip's deflection (downward) and slope (turning x towards -z): at its two nodes (the
// corners), and the slope's mean across the width, int w_x dy / b, which the element's cubic
// Hermite interpolation across the width gives from the nodes' slopes and twists:
// mean of the corners' r_x,z + b/12 (r_xy,z(0) - r_xy,z(b)); the deflection's mean likewise from
// the corners' w and r_y,z.
struct Tip {
  double w, slope, mean_slope, mean_w;
};
Tip tip_of(const Model& model, Data& data, int nx, double b) {
  const auto t0 = output(model, data, "tip0"), t1 = output(model, data, "tip1");
  const Body& body = model.bodies[0];
  double slope = 0, twist = 0, tilt = 0;
  for (int j = 0; j < 2; ++j) {
    const int k = body.offset + 12 + 12 * (j * (nx + 1) + nx);
    const Eigen::Vector3d rx = Eigen::Vector3d::UnitX() + data.state.q.segment<3>(k + 3);
    slope += 0.5 * std::atan2(-rx(2), rx(0));
    twist += (j ? 1 : -1) * data.state.q(k + 9 + 2);
    tilt += (j ? 1 : -1) * data.state.q(k + 6 + 2);
  }
  return {-(t0[2] + t1[2]) / 2, slope, slope + b / 12 * twist, -(t0[2] + t1[2]) / 2 + b / 12 * tilt};
}

}  // namespace

// Small deflection: tip deflection and slope against plate-strip (beam) theory, and the welded
// bar against its weight and moment applied as point forces.
TEST(PlateWeld, CantileverStripWithAWeldedTipBarMatchesPlateStripTheory) {
  const Strip s;
  const double EI = s.D() * s.b, P = s.P(), M = s.M(), q = s.q(), L = s.L;
  const double w_ref = P * L * L * L / (3 * EI) + M * L * L / (2 * EI) + q * std::pow(L, 4) / (8 * EI);
  const double th_ref = P * L * L / (2 * EI) + M * L / EI + q * L * L * L / (6 * EI);
  for (const int nx : {4, 8}) {
    const Model welded = test::model_from(strip_json(s, nx, false));
    Data dw(welded);
    for (const auto& n : initialize(welded, dw)) std::printf("note: %s\n", n.c_str());
    const Tip tw = tip_of(welded, dw, nx, s.b);
    // The bar's x axis turns with the node's triad.
    const double bar = std::atan2(-dw.bodies[1].A(2, 0), dw.bodies[1].A(0, 0));
    const Model coupled = test::model_from(strip_json(s, nx, true));
    Data dc(coupled);
    initialize(coupled, dc);
    const Tip tc = tip_of(coupled, dc, nx, s.b);
    const double d = L / nx;
    const double wc_ref = w_ref - M * d * d / (6 * EI), thc_ref = th_ref - M * d / (2 * EI);
    std::printf("strip %d x 1 (L/b = %g): welded tip w %.9e m at the corners, mean %.9e (theory %.9e, %+.2e); slope %.9e at the "
                "corners (%+.2e), mean %.9e (theory %.9e, %+.2e); bar %.9e\n"
                "  force couple: w %.9e at the corners, mean %.9e (theory %.9e, %+.2e); slope %.9e at the corners (%+.2e), mean %.9e "
                "(theory %.9e, %+.2e); welded - couple mean w %.6e (theory %.6e)\n",
                nx, L / s.b, tw.w, tw.mean_w, w_ref, tw.mean_w / w_ref - 1, tw.slope, tw.slope / th_ref - 1, tw.mean_slope, th_ref,
                tw.mean_slope / th_ref - 1, bar, tc.w, tc.mean_w, wc_ref, tc.mean_w / wc_ref - 1, tc.slope, tc.slope / thc_ref - 1,
                tc.mean_slope, thc_ref, tc.mean_slope / thc_ref - 1, tw.mean_w - tc.mean_w, M * d * d / (6 * EI));
    EXPECT_NEAR(tw.mean_w / w_ref, 1.0, 2e-5);
    EXPECT_NEAR(tw.mean_slope / th_ref, 1.0, 2e-5);
    EXPECT_NEAR(tc.mean_w / wc_ref, 1.0, 2e-5);
    EXPECT_NEAR(tc.mean_slope / thc_ref, 1.0, 2e-5);
    EXPECT_NEAR(tw.mean_w - tc.mean_w, M * d * d / (6 * EI), 2e-5 * w_ref);
    // The welded bar holds the tip edge straight: its corners' deflection is the mean.
    EXPECT_NEAR(tw.w / w_ref, 1.0, 2e-5);
    // The bar turns with the corners' triads (its rows), which the tip section's warping (the
    // twist r_xy the loads at two nodes leave there) sets apart from the mean slope by a local,
    // mesh-dependent amount (measured 7e-4 and 2.4e-3 of it on 4 and 8 elements).
    EXPECT_NEAR(bar, tw.slope, 1e-9);
    // The bar welded at one tip corner alone: its weight, off the weld by half the width, twists
    // the strip too, but in the linear theory a twist (antisymmetric across the width) adds
    // nothing to the section's mean deflection and slope, which stay plate-strip theory's.
    const Model one = test::model_from(strip_json(s, nx, false, R"({"analysis": "static"})", 0, true));
    Data d1(one);
    initialize(one, d1);
    const Tip t1 = tip_of(one, d1, nx, s.b);
    std::printf("  one weld at a corner: corners' w %.9e, mean %.9e (%+.2e); mean slope %.9e (%+.2e)\n", t1.w, t1.mean_w,
                t1.mean_w / w_ref - 1, t1.mean_slope, t1.mean_slope / th_ref - 1);
    EXPECT_NEAR(t1.mean_w / w_ref, 1.0, 2e-5);
    EXPECT_NEAR(t1.mean_slope / th_ref, 1.0, 2e-5);
  }
}

// Large rotations: a soft strip (P L^2 / (D b) about 3) with the welded bar released flat swings
// the tip through tens of degrees. Energy is kept to the trapezoidal rule's order (halving the
// step quarters the drift) and the bar's axes stay on the node's triad (computed here).
TEST(PlateWeld, LargeRotationSwingKeepsEnergyAndTheWeld) {
  Strip s;
  s.rho = 1000;
  s.m = 0.3;
  s.e = 0.05;
  const double E = 1e7;
  double drift[2] = {0, 0};
  for (int r = 0; r < 2; ++r) {
    const double h = r == 0 ? 2e-3 : 1e-3;
    const Model model = test::model_from(strip_json(s, 4, false, R"({"end": 0.6, "step": )" + num(h) + "}", E));
    Data data(model);
    initialize(model, data);
    const auto e0 = output(model, data, "e");
    double emax = 0, turn = 0, weld = 0;
    const Body& b = model.bodies[0];
    while (data.state.t < 0.6 - 1e-9) {
      step(model, data);
      const auto e = output(model, data, "e");
      emax = std::max(emax, std::abs(e[2] - e0[2]));
      const int k = b.offset + 12 + 12 * 4 + 3;  // node n4_0
      const Eigen::Matrix3d T = gram_schmidt(Eigen::Vector3d::UnitX() + data.state.q.segment<3>(k),
                                             Eigen::Vector3d::UnitY() + data.state.q.segment<3>(k + 3));
      // The bar's frame started on the reference triad (both the global axes).
      weld = std::max(weld, (data.bodies[1].A - T).cwiseAbs().maxCoeff());
      turn = std::max(turn, std::acos(std::clamp(T(0, 0), -1.0, 1.0)));
    }
    drift[r] = emax;
    std::printf("h = %g s: largest tip turn %.1f deg, energy drift %.3e J of %.3e J (m g L), weld |A - T| %.2e\n", h, turn * 180 / M_PI,
                emax, s.m * s.g * s.L, weld);
    EXPECT_GT(turn, 30 * M_PI / 180);
    EXPECT_LT(weld, 1e-6);
    EXPECT_LT(emax, 1e-2 * s.m * s.g * s.L);
  }
  std::printf("drift ratio %.2f (second order: 4)\n", drift[0] / drift[1]);
  EXPECT_GT(drift[0] / drift[1], 3.0);
}

TEST(PlateWeld, BadInputIsRefusedNamingTheField) {
  const std::string good = strip_json(Strip{}, 4, false);
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  EXPECT_EQ(test::error_of(good), "");
  // The runtime says how each weld is held (as it says which joints it assembled).
  const Model m = test::model_from(good);
  int weld_notes = 0;
  for (const auto& n : m.notes)
    if (n.find("(fixed) at node") != std::string::npos && n.find("exact triad") != std::string::npos &&
        n.find("not assembled") != std::string::npos)
      ++weld_notes;
  EXPECT_EQ(weld_notes, 2);
  test::expect_error(with("\"node1\": \"n4_0\"", "\"node1\": \"n9_0\""), "joints[0].node1", "has no node 'n9_0'");
  test::expect_error(with("\"type\": \"fixed\", \"body1\": \"strip\"", "\"type\": \"revolute\", \"axis\": [0, 1, 0], \"body1\": \"strip\""),
                     "joints[0].type", "not supported");
  test::expect_error(with("\"node1\": \"n4_0\"", "\"node1\": \"n4_0\", \"offset1\": [0.1, 0, 0]"), "joints[0].offset1", "not supported");
}

// The relative formulation (FORMULATION.md 18) places the bar at a weld's point and keeps the
// rotation rows: its swing follows the absolute formulation's.
TEST(PlateWeld, RelativeFormulationAgrees) {
  Strip s;
  s.rho = 1000;
  s.m = 0.3;
  s.e = 0.05;
  double tip[2][3];
  for (int r = 0; r < 2; ++r) {
    const Model model = test::model_from(strip_json(
        s, 4, false, std::string(R"({"end": 0.3, "step": 1e-3, "formulation": ")") + (r ? "relative" : "absolute") + "\"}", 1e7));
    Data data(model);
    for (const auto& n : initialize(model, data)) std::printf("note: %s\n", n.c_str());
    while (data.state.t < 0.3 - 1e-9) step(model, data);
    const auto t0 = output(model, data, "tip0");
    for (int k = 0; k < 3; ++k) tip[r][k] = t0[static_cast<std::size_t>(k)];
  }
  const double apart = std::hypot(tip[0][0] - tip[1][0], tip[0][1] - tip[1][1], tip[0][2] - tip[1][2]);
  std::printf("tip at 0.3 s: absolute (%.6f, %.6f, %.6f), relative (%.6f, %.6f, %.6f), %.2e m apart\n", tip[0][0], tip[0][1],
              tip[0][2], tip[1][0], tip[1][1], tip[1][2], apart);
  EXPECT_LT(tip[0][2], -0.3);  // a large swing
  EXPECT_LT(apart, 1e-4);
}
