// The interface-load stiffening (FORMULATION.md 7) from force elements whose two ends sit on one
// flexible body and from couplers, and the stiffening's dependence on the multipliers in
// Newton's direction.
//
// Sources: statics (the load of an element at each of its ends is its own force and torque
// there, computed here from the ends' positions and the elements' laws as the outputs report
// them; a coupler's torque -length lambda, MODEL_FILE.md); Euler's column (a pinned-pinned
// Euler-Bernoulli beam under an axial compression P vibrates at f0 sqrt(1 - P/Pcr),
// Pcr = pi^2 EI / L^2; S. Timoshenko, D. H. Young, W. Weaver, "Vibration Problems in
// Engineering", 4th ed., Wiley 1974, sec. 5.13); central finite differences of the Newton
// residual over the multipliers and of the elements' forces over q and q_dot.
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/outputs.hpp"
#include "forces/forces.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

// A free-free chain of `points` points (its interfaces A and B at the ends with K0F, K0M; Ke/M1).
ffr::formats::Sid free_chain_sid(int points, double L, double EA, double EI, int modes) {
  ffr::formats::synthetic::ChainParams p;
  p.points = points;
  p.length = L;
  p.mass = 1.0;
  p.EA = EA;
  p.EIy = p.EIz = EI;
  p.modes = modes;
  p.stiffening = true;
  p.nodes = {{"A", 0}, {"B", -1}, {"M", points / 2}};
  auto chain = ffr::formats::synthetic::spring_chain(p);
  // The chain's points carry no rotary inertia: give the frame a thin rod's about y and z (as
  // StiffeningOracle.FreeFreeRoundRodSliderCrank* does), so turning about them costs energy.
  const double d = 0.02;
  chain.sid.integrals.rrdm(1, 1) += p.mass * d * d / 16;
  chain.sid.integrals.rrdm(2, 2) += p.mass * d * d / 16;
  chain.sid.J.M0 = chain.sid.integrals.rrdm.trace() * Eigen::Matrix3d::Identity() - chain.sid.integrals.rrdm + chain.sid.rotary.I;
  return chain.sid;
}

// The position of node `name` of body 0 (r0 + A (origin + phi y)).
Eigen::Vector3d node_point(const Model& model, const Data& data, const char* name) {
  const Body& b = model.bodies[0];
  const NodeSlice& n = b.nodes[static_cast<std::size_t>(b.find_node(name))];
  return data.state.q.segment<3>(b.offset) +
         data.bodies[0].A * (n.origin + n.phi * data.state.q.segment(b.offset + 12, b.nq));
}

const std::string kRod = R"({"name": "rod", "type": "flexible", "sid": "rod.sid.h5", "stiffening": true,
              "position": [0.1, 0.2, 0.3], "orientation": [[0.36, 0.48, -0.8], [-0.8, 0.6, 0], [0.48, 0.64, 0.6]],
              "modal_coordinates": [0.004, -0.003, 0.002, 0.001, -0.002, 0.001]})";
const std::string kBody = R"("bodies": [)" + kRod + "]";
// The rod and a rigid mass at its end B (x = 1 in the rod's frame).
const std::string kBodyAndMass = R"("bodies": [)" + kRod + R"(,
    {"name": "mass", "type": "rigid", "mass": 0.5, "com": [0, 0, 0], "position": [0.46, -0.6, 0.78],
     "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]]}])";

}  // namespace

// A spring-damper and a bushing, each between the two end nodes A and B of one free flexible body
// (both interfaces of its stiffening): the loads that reach A and B are the element's force on
// each end (and, for the bushing, its torque), resolved in the body frame, the moment about the
// node. Before, such an element was left out of the stiffening (both ends' loads are summed in the
// body's frame entries of Q).
TEST(InterfaceStiffening, ForceElementBetweenTwoInterfacesOfOneBodyLoadsBoth) {
  test::TempDir dir("iface_same_body");
  test::write_sid_file(free_chain_sid(11, 1.0, 1e5, 50, 6), dir / "rod.sid.h5");
  for (const bool bushing : {false, true}) {
    const std::string force =
        bushing ? R"({"name": "e", "type": "bushing", "body1": "rod", "node1": "A", "body2": "rod", "node2": "B",
                      "stiffness": [100, 200, 300, 4, 5, 6],
                      "preload": {"force": [30, -20, 10], "torque": [1, 2, -3]}})"
                : R"({"name": "e", "type": "spring_damper", "body1": "rod", "node1": "A", "body2": "rod", "node2": "B",
                      "k": 1000, "length0": 0.9, "preload": 50})";
    const Model model = test::model_from("{" + kBody + R"(, "forces": [)" + force + R"(],
  "solver": {"end": 0.1, "step": 1e-3}})",
                                         dir.path);
    const Body& b = model.bodies[0];
    ASSERT_TRUE(b.stiffening.has_value());
    const int sA = 0, sB = 1;  // the chain's interfaces: A, B, M
    ASSERT_EQ(b.stiffening->interfaces.size(), 3u);
    ASSERT_EQ(b.stiffening->interfaces[sA].node, b.find_node("A"));
    ASSERT_EQ(b.stiffening->interfaces[sB].node, b.find_node("B"));
    Data data(model);
    // A deformed, moved state (not the initial one, where a bushing's measures vanish).
    data.state.q.segment(b.offset + 12, b.nq) += Eigen::VectorXd::LinSpaced(b.nq, 0.01, -0.01);
    data.state.q.segment<3>(b.offset) += Eigen::Vector3d(0.01, -0.02, 0.03);
    data.state.qd.segment(b.offset + 12, b.nq).setConstant(0.1);
    update_bodies(model, data);
    update_markers(model, data);
    generalized_forces(model, data, 0);
    const Eigen::Matrix3d A = data.bodies[0].A;
    const Eigen::Vector3d pA = node_point(model, data, "A"), pB = node_point(model, data, "B");
    // The ends' points: a spring's at the nodes; a bushing's both at A's point, its end 2
    // carried by node B (a lever from B).
    const int m1 = bushing ? model.bushings[0].m1 : model.springs[0].m1, m2 = bushing ? model.bushings[0].m2 : model.springs[0].m2;
    const Eigen::Vector3d p1 = data.markers[static_cast<std::size_t>(m1)].p, p2 = data.markers[static_cast<std::size_t>(m2)].p;
    // The element's force F2 and torque T2 (about p2) on end 2, global; end 1 takes -F2 and,
    // about p1, -T2 - (p2 - p1) x F2. About the nodes: M_A = T1 + (p1 - pA) x F1, M_B = T2 +
    // (p2 - pB) x F2.
    Eigen::Vector3d F2, T2 = Eigen::Vector3d::Zero();
    double out[6];
    if (bushing) {
      element_force(model, data, ForceElementKind::Bushing, 0, out);
      F2 = Eigen::Vector3d(out[0], out[1], out[2]);
      T2 = Eigen::Vector3d(out[3], out[4], out[5]);
    } else {
      element_force(model, data, ForceElementKind::SpringDamper, 0, out);  // tension, pulling the ends together
      F2 = -out[0] * (p2 - p1).normalized();
    }
    const Eigen::Vector3d F1 = -F2;
    const Eigen::Vector3d M1 = -T2 - (p2 - p1).cross(F2) + (p1 - pA).cross(F1), M2 = T2 + (p2 - pB).cross(F2);
    const auto& L = data.bodies[0].iface_load;
    const double scale = F2.norm();
    std::printf("%s between A and B: |F| %.4f N; interface A force error %.2e, moment %.2e; B force %.2e, moment %.2e (N, N m)\n",
                bushing ? "bushing" : "spring", scale, (Eigen::Vector3d(L.col(sA).head<3>()) - A.transpose() * F1).norm(),
                (Eigen::Vector3d(L.col(sA).tail<3>()) - A.transpose() * M1).norm(),
                (Eigen::Vector3d(L.col(sB).head<3>()) - A.transpose() * F2).norm(),
                (Eigen::Vector3d(L.col(sB).tail<3>()) - A.transpose() * M2).norm());
    EXPECT_GT(scale, 10.0);
    EXPECT_LT((Eigen::Vector3d(L.col(sA).head<3>()) - A.transpose() * F1).norm(), 1e-10 * scale);
    EXPECT_LT((Eigen::Vector3d(L.col(sB).head<3>()) - A.transpose() * F2).norm(), 1e-10 * scale);
    EXPECT_LT((Eigen::Vector3d(L.col(sA).tail<3>()) - A.transpose() * M1).norm(), 1e-10 * scale);
    EXPECT_LT((Eigen::Vector3d(L.col(sB).tail<3>()) - A.transpose() * M2).norm(), 1e-10 * scale);
  }
}

namespace {

// A free-free chain rod (1 m, 1 kg, EI 1000 N m^2, axially stiff: its 16 lowest modes bend;
// with 8 the basis's own buckling load is 0.55 % above Euler's, 2.4 % on f / f0 at 0.9 Pcr)
// pinned at A to the ground and at B to a light slider on a guide along x (pinned-pinned), and
// compressed by a spring of preload P pulling its own two ends together: the compression reaches
// the rod only through its interfaces A and B (K0F), the joints carry nothing. The chord stays
// on the x axis, so the spring's pull is the dead axial load of Euler's column. The midpoint is
// nudged by a short transverse pulse; the frequency from its zero crossings.
double column_frequency(const std::filesystem::path& dir, double P, bool stiffening) {
  const double f_est = M_PI / 2 * std::sqrt(1000.0) * std::sqrt(std::max(0.05, 1 - P / (M_PI * M_PI * 1000)));
  const double h = 1 / (f_est * 400), end = 8 / f_est;
  char json[4096];
  std::snprintf(json, sizeof json, R"({
  "bodies": [
    {"name": "rod", "type": "flexible", "sid": "rod.sid.h5", "stiffening": %s},
    {"name": "slider", "type": "rigid", "mass": 0.01, "com": [1, 0, 0], "inertia": [[1e-6, 0, 0], [0, 1e-6, 0], [0, 0, 1e-6]]}
  ],
  "joints": [
    {"name": "pin", "type": "revolute", "body1": "ground", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "wrist", "type": "revolute", "body1": "rod", "body2": "slider", "node1": "B", "axis": [0, 0, 1]},
    {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "at": [1, 0, 0], "axis": [1, 0, 0]}
  ],
  "forces": [
    {"name": "tendon", "type": "spring_damper", "body1": "rod", "node1": "A", "body2": "rod", "node2": "B", "k": 0, "preload": %.17g},
    {"name": "nudge", "type": "point_force", "body": "rod", "node": "M",
     "table": {"t": [0, %.17g, %.17g, 100], "value": [[0, 0, 0], [0, 1, 0], [0, 0, 0], [0, 0, 0]]}}
  ],
  "solver": {"end": %.17g, "step": %.17g}
})",
                stiffening ? "true" : "false", P, 0.05 / f_est, 0.1 / f_est, end, h);
  const Model model = test::model_from(json, dir);
  Data data(model);
  initialize(model, data);
  const int marker = model.loads[0].marker;
  std::vector<double> t, y;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    if (data.state.t < 0.2 / f_est) continue;
    t.push_back(data.state.t);
    y.push_back(data.markers[static_cast<std::size_t>(marker)].p.y());
  }
  std::vector<double> up;
  for (std::size_t i = 1; i < y.size(); ++i)
    if (y[i - 1] < 0 && y[i] >= 0) up.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-y[i - 1]) / (y[i] - y[i - 1]));
  if (up.size() < 2) return NAN;
  return static_cast<double>(up.size() - 1) / (up.back() - up.front());
}

}  // namespace

TEST(InterfaceStiffening, ColumnCompressedByItsOwnTendonFollowsEuler) {
  test::TempDir dir("iface_tendon_column");
  test::write_sid_file(free_chain_sid(41, 1.0, 1e8, 1000, 16), dir / "rod.sid.h5");
  const double Pcr = M_PI * M_PI * 1000;
  const double f0 = column_frequency(dir.path, 0, true);
  std::printf("tendon column: f0 %.4f Hz (Euler-Bernoulli pinned-pinned %.4f Hz)\n", f0, M_PI / 2 * std::sqrt(1000.0));
  for (const double r : {0.5, 0.9}) {
    const double f = column_frequency(dir.path, r * Pcr, true);
    const double f_off = column_frequency(dir.path, r * Pcr, false);
    std::printf("tendon column, P = %.1f Pcr: f / f0 = %.5f stiffened, Euler %.5f (%.3f %%); unstiffened %.5f\n", r, f / f0,
                std::sqrt(1 - r), 100 * (f / f0 / std::sqrt(1 - r) - 1), f_off / f0);
    EXPECT_NEAR(f / f0 / std::sqrt(1 - r), 1, 0.01);
    EXPECT_GT(f_off / f0, 0.97);  // without the tendon's load at A and B the rod does not feel it
  }
}

// Newton's equations f = kq [M q_dd + Phi_q^T lambda - Q(q, lambda)] depend on the multipliers
// through the constraint forces and through the interface-load stiffening of the joints' loads
// at a flexible body's interfaces. Their derivative in lambda, Phi_q^T + G with G = -dQ/dlambda
// (add_constraint_forces, add_interface_multiplier_forces: what the multiplier passes apply),
// against central differences of Phi_q^T lambda - Q over each multiplier (exact up to round-off:
// both are linear in lambda), at a deformed, moved state of a free-free chain with a revolute at
// its interface A and a spherical joint to a rigid mass at B.
TEST(InterfaceStiffening, MultiplierDerivativeMatchesFiniteDifferences) {
  test::TempDir dir("iface_lambda_fd");
  test::write_sid_file(free_chain_sid(11, 1.0, 1e5, 50, 6), dir / "rod.sid.h5");
  const Model model = test::model_from("{" + kBodyAndMass + R"(,
  "joints": [
    {"name": "pin", "type": "revolute", "body1": "ground", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "ball", "type": "spherical", "body1": "rod", "body2": "mass", "node1": "B"}
  ],
  "solver": {"end": 0.1, "step": 1e-3}})",
                                       dir.path);
  ASSERT_EQ(model.bodies[0].stiffening->interfaces.size(), 3u);  // A, B, M
  Data data(model);
  const Body& b = model.bodies[0];
  data.state.q.segment(b.offset + 12, b.nq) += Eigen::VectorXd::LinSpaced(b.nq, 0.01, -0.01);
  data.state.qd.segment(b.offset + 12, b.nq).setConstant(0.1);
  // evaluate() computes the forces before the constraints: the second pass's interface loads use
  // the Jacobian of this state (as every Newton iterate after the first does).
  evaluate(model, data, 0);
  evaluate(model, data, 0);
  const int na = data.na, n = static_cast<int>(data.state.q.size());
  ASSERT_GT(na, 0);
  Eigen::VectorXd lam0 = 100 * Eigen::VectorXd::LinSpaced(data.state.lambda.size(), 1.0, -0.7);
  auto residual = [&](const Eigen::VectorXd& lam) {
    data.state.lambda = lam;
    generalized_forces(model, data, 0);
    Eigen::VectorXd r = -data.Q;
    add_constraint_forces(model, data, lam, r);
    return r;
  };
  double worst = 0, worst_without_g = 0, size = 0;
  for (int j = 0; j < na; ++j) {
    Eigen::VectorXd a = lam0, c = lam0;
    const double eps = 1.0;
    a(j) += eps;
    c(j) -= eps;
    const Eigen::VectorXd fd = (residual(a) - residual(c)) / (2 * eps);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(lam0.size());
    e(j) = 1;
    Eigen::VectorXd col = Eigen::VectorXd::Zero(n), col_phi = Eigen::VectorXd::Zero(n);
    add_constraint_forces(model, data, e, col_phi);
    col = col_phi;
    detail::add_interface_multiplier_forces(model, data, e, col);
    worst = std::max(worst, (col - fd).cwiseAbs().maxCoeff());
    worst_without_g = std::max(worst_without_g, (col_phi - fd).cwiseAbs().maxCoeff());
    size = std::max(size, fd.cwiseAbs().maxCoeff());
  }
  std::printf("d(Phi_q^T lambda - Q)/dlambda: analytic vs central differences %.2e of max %.3e; without the stiffening's "
              "part G %.2e\n",
              worst, size, worst_without_g);
  EXPECT_GT(worst_without_g, 1e-4 * size);  // the stiffening's part is there to check
  EXPECT_LT(worst, 1e-9 * size);
}

// A coupler (gear pair) between the revolute that pins the rod at its interface A and a wheel's
// shaft: its one row's multiplier lambda is a torque -length lambda about the joint axis on joint
// 1's body2 (MODEL_FILE.md, coupler; FORMULATION.md 13, the angle row), the rod, and that is
// the load that reaches A (no force, in the initial configuration where the revolute's axes
// coincide), the revolute's own multipliers set to zero.
TEST(InterfaceStiffening, CouplerTorqueReachesTheInterfaceOfItsJoint) {
  test::TempDir dir("iface_coupler");
  test::write_sid_file(free_chain_sid(11, 1.0, 1e5, 50, 6), dir / "rod.sid.h5");
  const Model model = test::model_from(R"({
  "bodies": [
    {"name": "rod", "type": "flexible", "sid": "rod.sid.h5", "stiffening": true, "orientation": [[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]]},
    {"name": "wheel", "type": "rigid", "mass": 1, "com": [0, 0, 0], "position": [0, 2, 0], "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]}
  ],
  "joints": [
    {"name": "pin", "type": "revolute", "body1": "ground", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "shaft", "type": "revolute", "body1": "ground", "body2": "wheel", "at": [0, 2, 0], "axis": [0, 0, 1]},
    {"name": "gears", "type": "coupler", "joint1": "pin", "joint2": "shaft", "ratio": -2}
  ],
  "solver": {"end": 0.1, "step": 1e-3}})",
                                       dir.path);
  ASSERT_EQ(model.couplers.size(), 1u);
  Data data(model);
  evaluate(model, data, 0);
  evaluate(model, data, 0);
  const ConstraintBlock& cb = model.blocks[static_cast<std::size_t>(model.couplers[0].block)];
  data.state.lambda.setZero();
  const double lam = 3.0;
  data.state.lambda(cb.row0) = lam;
  generalized_forces(model, data, 0);
  const Eigen::Matrix3d A = data.bodies[0].A;
  const Eigen::Vector3d M = A.transpose() * (-model.length * lam * Eigen::Vector3d::UnitZ());
  const auto& L = data.bodies[0].iface_load;
  const Eigen::Vector3d FA = L.col(0).head<3>(), MA = L.col(0).tail<3>();
  std::printf("coupler at A: moment (%.6f, %.6f, %.6f) N m, expected (%.6f, %.6f, %.6f); force %.2e N; B %.2e\n", MA(0), MA(1),
              MA(2), M(0), M(1), M(2), FA.norm(), L.col(1).norm());
  EXPECT_LT((MA - M).norm(), 1e-12 * M.norm());
  EXPECT_LT(FA.norm(), 1e-12 * M.norm());
  EXPECT_EQ(L.col(1).norm(), 0.0);
}

// What stays refused: a spring between two points of one rigid body (it would exert nothing),
// and a bushing within one flexible body unless it joins two different nodes; each names the
// file and the field.
TEST(InterfaceStiffening, ElementsWithinOneBodyAreRefusedWhereMeaningless) {
  test::TempDir dir("iface_refused");
  test::write_sid_file(free_chain_sid(11, 1.0, 1e5, 50, 6), dir / "rod.sid.h5");
  auto message = [&](const std::string& json) {
    try {
      test::model_from(json, dir.path);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string rigid = message(R"({
  "bodies": [{"name": "box", "type": "rigid", "mass": 1, "com": [0, 0, 0], "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}],
  "forces": [{"type": "spring_damper", "body1": "box", "at1": [0, 0, 0], "body2": "box", "at2": [1, 0, 0], "k": 1}],
  "solver": {"end": 0.1, "step": 1e-3}})");
  const std::string one_node = message("{" + kBody + R"(,
  "forces": [{"type": "bushing", "body1": "rod", "node1": "A", "body2": "rod", "node2": "A", "stiffness": [1, 1, 1, 1, 1, 1]}],
  "solver": {"end": 0.1, "step": 1e-3}})");
  std::printf("refused: %s\nrefused: %s\n", rigid.c_str(), one_node.c_str());
  EXPECT_NE(rigid.find("test-model.json: forces[0].body2: a spring needs two different bodies, or two points of one flexible body"),
            std::string::npos);
  EXPECT_NE(one_node.find("forces[0].body2: within one flexible body, give two different nodes"), std::string::npos);
}

// The tangents K = -dQ/dq and C = -dQ/dq_dot of a spring-damper and a bushing between two nodes
// of one flexible body (both ends' terms land in the same block) against central differences
// of their generalized forces: the model with the elements less the same body without them, at
// a deformed, moving state (stiffening off: the interface loads' feedback is a frozen load in
// the tangent, FORMULATION.md 7).
TEST(InterfaceStiffening, ElementWithinOneBodyTangentsMatchFiniteDifferences) {
  test::TempDir dir("iface_same_body_fd");
  test::write_sid_file(free_chain_sid(11, 1.0, 1e5, 50, 6), dir / "rod.sid.h5");
  std::string rod = kRod;
  rod.replace(rod.find(R"("stiffening": true)"), 18, R"("stiffening": false)");
  const std::string tail = R"(, "solver": {"end": 0.1, "step": 1e-3}})";
  const Model bare = test::model_from(R"({"bodies": [)" + rod + "]" + tail, dir.path);
  const Model with = test::model_from(R"({"bodies": [)" + rod + R"(], "forces": [
    {"type": "spring_damper", "body1": "rod", "node1": "A", "body2": "rod", "node2": "B", "k": 1000, "c": 3, "length0": 0.9, "preload": 50},
    {"type": "bushing", "body1": "rod", "node1": "A", "body2": "rod", "node2": "B", "stiffness": [100, 200, 300, 4, 5, 6],
     "damping": [1, 2, 3, 0.1, 0.2, 0.3], "preload": {"force": [30, -20, 10], "torque": [1, 2, -3]}}])" + tail,
                                      dir.path);
  Data db(bare), dw(with);
  const int n = static_cast<int>(dw.state.q.size());
  Eigen::VectorXd q = dw.state.q, qd = Eigen::VectorXd::Zero(n);
  const Body& b = with.bodies[0];
  q.segment(b.offset + 12, b.nq) += Eigen::VectorXd::LinSpaced(b.nq, 0.01, -0.01);
  q.segment<3>(b.offset) += Eigen::Vector3d(0.01, -0.02, 0.03);
  qd.segment(b.offset + 12, b.nq) = Eigen::VectorXd::LinSpaced(b.nq, 0.3, -0.2);
  qd.segment<3>(b.offset) = Eigen::Vector3d(0.1, 0.2, -0.1);
  auto forces = [&](const Model& m, Data& d, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
    d.state.q = x;
    d.state.qd = v;
    update_bodies(m, d);
    update_markers(m, d);
    generalized_forces(m, d, 0);
    return Eigen::VectorXd(d.Q);
  };
  auto element_q = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& v) -> Eigen::VectorXd {
    return forces(with, dw, x, v) - forces(bare, db, x, v);
  };
  forces(with, dw, q, qd);
  force_tangents(with, dw, 0);
  forces(bare, db, q, qd);
  force_tangents(bare, db, 0);
  const Eigen::MatrixXd K = dw.K - db.K, C = dw.C - db.C;
  const double eps = 1e-6;
  Eigen::MatrixXd Kfd(n, n), Cfd(n, n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd a = q, c = q, va = qd, vc = qd;
    a(j) += eps;
    c(j) -= eps;
    va(j) += eps;
    vc(j) -= eps;
    Kfd.col(j) = -(element_q(a, qd) - element_q(c, qd)) / (2 * eps);
    Cfd.col(j) = -(element_q(q, va) - element_q(q, vc)) / (2 * eps);
  }
  const double ek = (K - Kfd).cwiseAbs().maxCoeff() / Kfd.cwiseAbs().maxCoeff();
  const double ec = (C - Cfd).cwiseAbs().maxCoeff() / Cfd.cwiseAbs().maxCoeff();
  std::printf("spring and bushing within one body: K vs central differences %.2e of max %.3e, C %.2e of max %.3e\n", ek,
              Kfd.cwiseAbs().maxCoeff(), ec, Cfd.cwiseAbs().maxCoeff());
  EXPECT_LT(ek, 1e-6);
  EXPECT_LT(ec, 1e-6);
}
