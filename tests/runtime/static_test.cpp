// Static equilibrium ("analysis": "static", "initial_equilibrium": true; FORMULATION.md 14)
// against references computed here: a mass on a spring (m g / k), a body hanging on three
// springs (the spring forces from the three equilibrium equations of a rigid body), a flexible
// cantilever under gravity (the linear static deflection K q = Phi^T f from the SID's members,
// and Roark's beam formula), and the refusal of models without a stable equilibrium.
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

constexpr double g = 9.81;

using test::output;

std::string refusal(const Model& model) { return test::initialize_refusal(model); }

}  // namespace

// A 2 kg slider on a vertical guide hanging from a spring of k = 500 N/m, unstretched at the
// start: it settles m g / k lower (Hooke), the spring then carrying its weight.
TEST(Static, MassOnSpringSettlesToWeightOverStiffness) {
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "m", "type": "rigid", "mass": 2, "com": [0, 0, -1], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]}],
    "joints": [{"name": "guide", "type": "prismatic", "body1": "ground", "body2": "m", "at": [0, 0, -1], "axis": [0, 0, 1]}],
    "forces": [{"name": "s", "type": "spring_damper", "body1": "ground", "at1": [0, 0, 0], "body2": "m", "k": 500}],
    "solver": {"analysis": "static"},
    "outputs": [{"name": "z", "type": "node_position", "body": "m"}, {"name": "F", "type": "element_force", "force": "s"},
                {"name": "R", "type": "joint_reaction", "joint": "guide"}]
  })");
  Data data(model);
  const auto notes = initialize(model, data);
  for (const auto& n : notes) std::printf("note: %s\n", n.c_str());
  const double z = output(model, data, "z")[2], F = output(model, data, "F")[0];
  const auto R = output(model, data, "R");
  std::printf("mass on spring: z = %.12f (Hooke %.12f), spring force %.9f N (weight %.9f), guide reaction (%.2e, %.2e, %.2e)\n", z,
              -1 - 2 * g / 500, F, 2 * g, R[0], R[1], R[2]);
  EXPECT_NEAR(z, -1 - 2 * g / 500, 1e-10);
  EXPECT_NEAR(F, 2 * g, 1e-8);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(R[i], 0, 1e-8);
  EXPECT_NEAR(data.state.qdd.cwiseAbs().maxCoeff(), 0, 1e-8);  // at rest: the accelerations vanish
}

// A 30 kg tub-like rigid body (centre of mass off its middle) hanging from three vertical springs
// of k = 2e5 N/m: statically determinate, the spring forces are fixed by the vertical force
// balance and the two moment balances about the centre of mass (rigid-body statics):
//   F1 + F2 + F3 = m g,  sum F_i (x_i - x_G) = 0,  sum F_i (y_i - y_G) = 0,
// i.e. each spring's preload at equilibrium. Hanging springs in tension hold the tub sideways
// and in yaw (their tension over their length).
TEST(Static, TubOnSpringsSettlesToTheirPreload) {
  const Model model = test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "tub", "type": "rigid", "mass": 30, "com": [0.1, 0.05, 0],
                "inertia": [[0.8, 0.02, 0], [0.02, 1.1, 0], [0, 0, 1.4]]}],
    "forces": [{"name": "s1", "type": "spring_damper", "body1": "ground", "at1": [-0.3, -0.2, 0.5], "body2": "tub", "at2": [-0.3, -0.2, 0], "k": 2e5, "length0": 0.5},
               {"name": "s2", "type": "spring_damper", "body1": "ground", "at1": [0.4, -0.25, 0.5], "body2": "tub", "at2": [0.4, -0.25, 0], "k": 2e5, "length0": 0.5},
               {"name": "s3", "type": "spring_damper", "body1": "ground", "at1": [0.05, 0.35, 0.5], "body2": "tub", "at2": [0.05, 0.35, 0], "k": 2e5, "length0": 0.5}],
    "solver": {"analysis": "static"},
    "outputs": [{"name": "F1", "type": "element_force", "force": "s1"}, {"name": "F2", "type": "element_force", "force": "s2"},
                {"name": "F3", "type": "element_force", "force": "s3"}]
  })");
  Data data(model);
  for (const auto& n : initialize(model, data)) std::printf("note: %s\n", n.c_str());
  Eigen::Matrix3d A;
  A << 1, 1, 1, -0.4, 0.3, -0.05, -0.25, -0.3, 0.3;
  const Eigen::Vector3d ref = A.colPivHouseholderQr().solve(Eigen::Vector3d(30 * g, 0, 0));
  const double F[3] = {output(model, data, "F1")[0], output(model, data, "F2")[0], output(model, data, "F3")[0]};
  std::printf("tub on springs: %.6f %.6f %.6f N, statics %.6f %.6f %.6f N\n", F[0], F[1], F[2], ref(0), ref(1), ref(2));
  // The tilt that sets the forces moves the lever arms by ~(deflection / arm)^2 ~ 1e-6.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(F[i], ref(i), 1e-5 * 30 * g);
}

namespace {

// A clamped Euler-Bernoulli chain (formats/synthetic.hpp): 1.2 m, EI_y = 400 N m^2 (bending
// along z), 3.6 kg, 41 points, its lowest 24 modes.
ffr::formats::synthetic::Chain cantilever_chain() {
  ffr::formats::synthetic::ChainParams p;
  p.points = 41;
  p.length = 1.2;
  p.mass = 3.6;
  p.EA = 1e8;
  p.EIy = 400;
  p.EIz = 4000;
  p.clamped = true;
  p.modes = 24;
  return ffr::formats::synthetic::spring_chain(p);
}

std::string cantilever_json(const char* solver) {
  return std::string(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "beam", "type": "flexible", "sid": "chain.sid.h5", "damping": {"ratio": 0.05}}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "beam"}],
    "solver": )") + solver + R"(,
    "outputs": [{"name": "q", "type": "modal_coordinates", "body": "beam"},
                {"name": "tip", "type": "node_deformation", "body": "beam", "node": "B"},
                {"name": "R", "type": "joint_reaction", "joint": "clamp"}]
  })";
}

}  // namespace

// The chain clamped at its frame origin under gravity: the static modal coordinates solve
// Ke q = Ct.M0 g (the modal gravity load Phi^T f, from the SID's own members, Ke and Ct.M0 =
// int Phi^T dm), and the tip deflection is Roark's uniformly loaded cantilever, y = w l^4 / (8 E I)
// (Roark's Formulas for Stress and Strain, 7th ed., Table 8.1 case 2a), within the lumping and
// the truncation to 24 modes. The clamp carries the weight and its moment.
TEST(Static, FlexibleCantileverSagsAsLinearStatics) {
  test::TempDir dir("static_cantilever");
  const auto chain = cantilever_chain();
  test::write_sid_file(chain.sid, dir / "chain.sid.h5");
  const Model model = test::model_from(cantilever_json(R"({"analysis": "static"})"), dir.path);
  Data data(model);
  for (const auto& n : initialize(model, data)) std::printf("note: %s\n", n.c_str());
  const auto q = output(model, data, "q");
  const Eigen::VectorXd ref = chain.sid.Ke.ldlt().solve(chain.sid.Ct.M0 * Eigen::Vector3d(0, 0, -g));
  double worst = 0;
  for (int k = 0; k < ref.size(); ++k) worst = std::max(worst, std::abs(q[static_cast<std::size_t>(k)] - ref(k)));
  const double tip = output(model, data, "tip")[2];
  const double w = 3.6 * g / 1.2, roark = -w * std::pow(1.2, 4) / (8 * 400);
  const auto R = output(model, data, "R");
  std::printf("cantilever: modal coordinates worst |q - Ke^-1 Ct g| = %.3e of %.3e; tip %.9f m, Roark %.9f m (%.2e relative); "
              "clamp F_z %.6f N, T_y %.6f N m\n",
              worst, ref.cwiseAbs().maxCoeff(), tip, roark, std::abs(tip / roark - 1), R[2], R[4]);
  EXPECT_LT(worst, 1e-9 * ref.cwiseAbs().maxCoeff());
  EXPECT_NEAR(tip / roark, 1.0, 2e-3);
  EXPECT_NEAR(R[2], 3.6 * g, 1e-8 * 3.6 * g);
  // The weight's moment about the clamp, m g l/2, held by the clamp's torque about y (T = -r_G x W,
  // r_G = l/2 along x, W = -m g z: T_y = -m g l / 2); the sag shortens the arm by ~(tip/l)^2.
  EXPECT_NEAR(R[4], -3.6 * g * 0.6, 1e-4 * 3.6 * g * 0.6);
}

// With initial_equilibrium the dynamic run starts settled: it stays at rest (the tip moves by
// round-off), where the same run without it swings through twice the sag.
TEST(Static, SettledRunStaysAtRest) {
  test::TempDir dir("static_settled");
  test::write_sid_file(cantilever_chain().sid, dir / "chain.sid.h5");
  double swing[2] = {0, 0}, sag = 0;
  for (int settled = 0; settled < 2; ++settled) {
    const std::string solver = std::string(R"({"end": 0.2, "step": 1e-3)") + (settled ? R"(, "initial_equilibrium": true})" : "}");
    const Model model = test::model_from(cantilever_json(solver.c_str()), dir.path);
    Data data(model);
    initialize(model, data);
    const double tip0 = output(model, data, "tip")[2];
    if (settled) sag = tip0;
    for (int i = 0; i < 200; ++i) {
      step(model, data);
      swing[settled] = std::max(swing[settled], std::abs(output(model, data, "tip")[2] - tip0));
    }
  }
  std::printf("sag %.6e m; largest tip motion over 0.2 s: %.3e m unsettled, %.3e m settled\n", sag, swing[0], swing[1]);
  EXPECT_GT(swing[0], 0.5 * std::abs(sag));
  EXPECT_LT(swing[1], 1e-9 * std::abs(sag));
}

// No stable equilibrium, refused with what to try: an upright pendulum (an equilibrium, unstable),
// a block on a frictionless inclined guide (its sliding meets no stiffness and gravity drives it),
// a free body falling (no equilibrium at all). A wheel on a horizontal axle with its centre of mass
// on the axle is no longer refused: every angle is an equilibrium (gravity has no moment about the
// axle), a neutral motion with no force along it (FORMULATION.md 14), accepted with a note
// naming it.
TEST(Static, RefusesModelsWithoutStableEquilibrium) {
  const std::string upright = refusal(test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "bob", "type": "rigid", "mass": 2, "com": [0, 0, 0.6], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.002]]}],
    "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bob", "at": [0, 0, 0], "axis": [0, 1, 0]}],
    "solver": {"analysis": "static"}
  })"));
  std::printf("upright: %s\n", upright.c_str());
  EXPECT_NE(upright.find("unstable"), std::string::npos);
  EXPECT_NE(upright.find("body 'bob'"), std::string::npos);
  const std::string wheel = refusal(test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "wheel", "type": "rigid", "mass": 2, "com": [0, 0, 0], "inertia": [[0.012, 0, 0], [0, 0.02, 0], [0, 0, 0.012]]}],
    "joints": [{"name": "axle", "type": "revolute", "body1": "ground", "body2": "wheel", "at": [0, 0, 0], "axis": [0, 1, 0]}],
    "solver": {"end": 1, "step": 1e-3, "initial_equilibrium": true}
  })"));
  std::printf("wheel: %s\n", wheel.c_str());
  EXPECT_EQ(wheel, "");
  {
    const Model model = test::model_from(R"({
      "gravity": [0, 0, -9.81],
      "bodies": [{"name": "wheel", "type": "rigid", "mass": 2, "com": [0, 0, 0], "inertia": [[0.012, 0, 0], [0, 0.02, 0], [0, 0, 0.012]]}],
      "joints": [{"name": "axle", "type": "revolute", "body1": "ground", "body2": "wheel", "at": [0, 0, 0], "axis": [0, 1, 0]}],
      "solver": {"analysis": "static"}
    })");
    Data data(model);
    const auto notes = initialize(model, data);
    ASSERT_EQ(notes.size(), 2u);
    std::printf("wheel: %s\n", notes[1].c_str());
    EXPECT_NE(notes[1].find("1 neutral motion"), std::string::npos);
    EXPECT_NE(notes[1].find("body 'wheel', its rotation"), std::string::npos);
  }
  // A 2 kg block on a prismatic guide inclined 30 degrees in the x-z plane, nothing along it:
  // gravity's component m g sin 30 drives the sliding, which meets no stiffness.
  const std::string block = refusal(test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "block", "type": "rigid", "mass": 2, "com": [0, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]}],
    "joints": [{"name": "guide", "type": "prismatic", "body1": "ground", "body2": "block", "at": [0, 0, 0], "axis": [0.8660254037844386, 0, 0.5]}],
    "solver": {"analysis": "static"}
  })"));
  std::printf("block: %s\n", block.c_str());
  EXPECT_NE(block.find("a force remains along it"), std::string::npos);
  EXPECT_NE(block.find("body 'block', its position along x"), std::string::npos);
  EXPECT_NE(block.find("hold that motion"), std::string::npos);
  const std::string falling = refusal(test::model_from(R"({
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "stone", "type": "rigid", "mass": 2, "com": [0, 0, 0], "inertia": [[0.012, 0, 0], [0, 0.02, 0], [0, 0, 0.012]]}],
    "solver": {"analysis": "static"}
  })"));
  std::printf("falling: %s\n", falling.c_str());
  EXPECT_NE(falling.find("equilibrium"), std::string::npos);
  EXPECT_NE(falling.find("static equilibrium at t = 0 s"), std::string::npos);
  EXPECT_NE(falling.find("singular"), std::string::npos);
}

// Bad solver keys: exit-2 material (ModelError naming the field).
TEST(Static, BadSolverKeysAreRefused) {
  const char* cases[][2] = {
      {R"({"analysis": "quasi"})", "unknown analysis"},
      {R"({"analysis": "static", "step": 1e-3})", "step"},
      {R"({"analysis": "static", "end": 1})", "end"},
      {R"({"end": 1, "step": 1e-3, "initial_equilibrium": "yes"})", "initial_equilibrium"},
  };
  for (const auto& c : cases) {
    const std::string json = std::string(R"({"bodies": [{"name": "b", "type": "rigid", "mass": 1, "com": [0, 0, 0],
      "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}], "solver": )") + c[0] + "}";
    try {
      test::model_from(json);
      ADD_FAILURE() << "accepted: " << c[0];
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find(c[1]), std::string::npos) << e.what();
    }
  }
}

// ffr-sim: a static analysis writes one sample (here the CSV: a header and one row, at the start
// time); a model without a stable equilibrium exits 1 with the message and writes nothing.
TEST(Static, FfrSimWritesOneSampleOrRefuses) {
  test::TempDir dir("static_cli");
  const std::string body = R"("gravity": [0, 0, -9.81],
    "bodies": [{"name": "bob", "type": "rigid", "mass": 2, "com": [0, 0, %s], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.002]]}],
    "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bob", "at": [0, 0, 0], "axis": [0, 1, 0]}],
    "solver": {"analysis": "static", "start": 0.5},
    "outputs": [{"name": "R", "type": "joint_reaction", "joint": "hinge"}])";
  for (const char* z : {"-0.6", "0.6"}) {
    char buf[1024];
    std::snprintf(buf, sizeof buf, body.c_str(), z);
    test::write_text(dir / "m.json", std::string("{") + buf + "}");
    std::filesystem::remove(dir / "out.h5");
    std::filesystem::remove(dir / "out.csv");
    const auto r = test::run_ffr_sim((dir / "m.json").string() + " -o " + (dir / "out.h5").string() + " --csv " + (dir / "out.csv").string());
    std::printf("bob at z = %s: status %d\n%s\n", z, r.status, r.output.c_str());
    if (std::string(z) == "-0.6") {
      ASSERT_EQ(r.status, 0) << r.output;
      std::ifstream in(dir / "out.csv");
      std::string header, row, extra;
      std::getline(in, header);
      std::getline(in, row);
      EXPECT_FALSE(std::getline(in, extra) && !extra.empty());
      std::vector<double> v;
      std::stringstream ss(row);
      for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
      ASSERT_EQ(v.size(), 7u) << row;
      EXPECT_EQ(v[0], 0.5);
      EXPECT_NEAR(v[3], 2 * g, 1e-9 * 2 * g) << row;  // the hinge carries m g
    } else {
      EXPECT_EQ(r.status, 1) << r.output;
      EXPECT_NE(r.output.find("unstable"), std::string::npos) << r.output;
      EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
    }
  }
}
