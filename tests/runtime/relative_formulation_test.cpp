// The relative (joint-coordinate) formulation (FORMULATION.md 18) against the absolute one and
// against the outside references the absolute tests use:
//  - the compound pendulum: its independent one-degree-of-freedom oracle (support.hpp, RK4);
//  - the four-bar: an independent one-degree-of-freedom model of the same mechanism (crank angle
//    the only coordinate, closed-form loop closure, Lagrange's equation, classical RK4 at a much
//    smaller step; the same construction as four_bar_test.cpp), with one loop closed by a cut joint;
//  - the flexible slider-crank of the IVP Test Set (B. Simeon 1996; F. Mazzia, C. Magherini,
//    F. Iavernaro, Test Set for IVP Solvers, release 2.3, problem "crank": the published
//    reference solution at t = 0.1, as in slider_crank_test.cpp);
//  - a 20-link pendulum chain: no outside reference; the two formulations are two different
//    discretisations of the same equations, so their difference must shrink as h^2 (the
//    trapezoidal rule's order) and the energy of both must be kept to the integrator's error.
#include "simeon_crank.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "formulation_models.hpp"  // tools/bench/formulations
#include "four_bar_oracle.hpp"

#include "ffr/runtime/relative.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

using namespace ffr::runtime;

namespace {

using formulations::num;
using formulations::with_formulation;

// ---- the compound pendulum -----------------------------------------------------------------

TEST(RelativeFormulation, CompoundPendulumMatchesOneDofOracle) {
  const double end = 1.0;
  const double ref = test::compound_pendulum_oracle(end);
  double err[2];
  int i = 0;
  for (const double h : {2e-3, 1e-3}) {
    const Model model = test::model_from(test::compound_pendulum_json(R"({"formulation": "relative", "end": 1.0, "step": )" + num(h) + "}"));
    ASSERT_TRUE(model.relative);
    EXPECT_EQ(model.relative->ns, 1);
    EXPECT_EQ(model.relative->kept_rows, 0);
    Data data(model);
    initialize(model, data);
    for (std::int64_t k = 0; k < step_count(model); ++k) step(model, data);
    const double th = test::output(model, data, "angle")[0];
    err[i++] = std::abs(th - ref);
    std::printf("pendulum relative h = %g: theta(1 s) = %.10f (oracle %.10f)\n", h, th, ref);
  }
  EXPECT_LT(err[1], 1e-4);
  EXPECT_NEAR(err[0] / err[1], 4.0, 0.8);  // second order
}

// ---- the four-bar ----------------------------------------------------------------------------

using namespace formulations::four_bar;

constexpr double kTh0 = kTheta0, kFourBarEnd = 1.0;

std::string four_bar_json(double h, const char* formulation) { return formulations::four_bar::json(h, kFourBarEnd, formulation); }

struct FourBarRun {
  std::vector<double> theta;
  double worst_violation = 0, dE = 0, E0 = 0;
};

FourBarRun run_four_bar(double h, const char* formulation) {
  const Model model = test::model_from(four_bar_json(h, formulation));
  Data data(model);
  initialize(model, data);
  FourBarRun r;
  r.E0 = energy(model, data).total();
  for (std::int64_t s = 0; s < step_count(model); ++s) {
    step(model, data);
    r.theta.push_back(kTh0 + joint_coordinate(model, data, 0, JointCoordinate::Angle));
    r.worst_violation = std::max(r.worst_violation, data.stats.last_violation);
    r.dE = std::max(r.dE, std::abs(energy(model, data).total() - r.E0));
  }
  return r;
}

std::vector<double> four_bar_oracle(double h) {
  return test::four_bar_oracle::crank_angles(h, static_cast<int>(kFourBarEnd / h + 0.5));
}

double worst_difference(const std::vector<double>& x, const std::vector<double>& y) {
  double w = 0;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) w = std::max(w, std::abs(x[i] - y[i]));
  return w;
}

TEST(RelativeFormulation, FourBarMatchesAbsoluteAndOneDofModel) {
  {
    const Model model = test::model_from(four_bar_json(1e-3, "relative"));
    // Three bodies placed by three joints; the fourth joint is the cut one (5 rows kept).
    EXPECT_EQ(model.relative->ns, 3);
    EXPECT_EQ(model.relative->kept_rows, 5);
  }
  double err_rel[2], diff[2];
  int i = 0;
  for (const double h : {1e-3, 5e-4}) {
    const auto ref = four_bar_oracle(h);
    const FourBarRun abs = run_four_bar(h, "absolute"), rel = run_four_bar(h, "relative");
    const double ea = worst_difference(abs.theta, ref), er = worst_difference(rel.theta, ref);
    err_rel[i] = er;
    diff[i] = worst_difference(abs.theta, rel.theta);
    std::printf("four-bar h = %g: worst |theta - oracle| absolute %.3e, relative %.3e; |absolute - relative| %.3e rad; "
                "violation %.2e; energy drift relative %.2e J of %.3f\n",
                h, ea, er, diff[i], rel.worst_violation, rel.dE, rel.E0);
    EXPECT_LT(rel.worst_violation, 1e-11);
    EXPECT_LT(rel.dE, 2e-4 * std::abs(rel.E0));
    ++i;
  }
  EXPECT_LT(err_rel[1], 1e-4);
  EXPECT_NEAR(err_rel[0] / err_rel[1], 4.0, 0.8);  // second order
  EXPECT_LT(diff[1], 1e-4);
  EXPECT_NEAR(diff[0] / diff[1], 4.0, 1.0);  // the two discretisations differ by O(h^2)
}

// ---- the flexible slider-crank (IVP Test Set) --------------------------------------------------

struct CrankResult {
  double phi2, x3, q[4];
  double worst_violation = 0;
};

CrankResult run_crank(double h, const char* formulation) {
  test::TempDir dir(std::string("crank_") + formulation);
  test::write_sid_file(test::simeon_rod_sid(), dir / "rod.sid.h5");
  const Model model = test::model_from(with_formulation(test::simeon_crank_json(h), formulation), dir.path);
  Data data(model);
  initialize(model, data);
  CrankResult r{};
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    r.worst_violation = std::max(r.worst_violation, data.stats.last_violation);
  }
  const Body& rod = model.bodies[1];
  const Vector3d u = data.state.q.segment<3>(rod.offset + 3);
  r.phi2 = std::atan2(u(1), u(0));
  r.x3 = data.state.q(model.bodies[2].offset);
  for (int k = 0; k < 4; ++k) r.q[k] = data.state.q(rod.offset + 12 + k);
  return r;
}

TEST(RelativeFormulation, FlexibleSliderCrankMatchesIvpTestSetReference) {
  // Test Set reference at t = 0.1 (phi2, x3, q1..q4), as in slider_crank_test.cpp.
  const double ref_phi2 = -0.331173498825626, ref_x3 = 0.169737332842786;
  const double ref_q[4] = {0.1893192899613509e-3, 0.2375751249879174e-4, -0.5323896770569702e-5, -0.8363313279112129e-5};
  {
    // The rod's joints are at its nodes: it is placed at its node on the crank (its frame and
    // modal coordinates its own, the joint's rotation rows kept), the slider joint cut.
    test::TempDir dir("crank_tree");
    test::write_sid_file(test::simeon_rod_sid(), dir / "rod.sid.h5");
    const Model m = test::model_from(with_formulation(test::simeon_crank_json(1e-5), "relative"), dir.path);
    for (const auto& n : m.notes) std::printf("note: %s\n", n.c_str());
    ASSERT_TRUE(m.relative);
    EXPECT_TRUE(m.relative->bodies[1].point);
    EXPECT_EQ(m.relative->bodies[1].parent, 0);
    EXPECT_EQ(m.relative->ns, 15);
  }
  const CrankResult rel = run_crank(1e-5, "relative"), abs = run_crank(1e-5, "absolute");
  std::printf("crank t = 0.1 relative: phi2 %.12f x3 %.12f (absolute %.12f %.12f, ref %.12f %.12f)\n", rel.phi2, rel.x3, abs.phi2,
              abs.x3, ref_phi2, ref_x3);
  for (int k = 0; k < 4; ++k)
    std::printf("  q%d relative %.9e absolute %.9e ref %.9e (relative rel. error %.2e, relative vs absolute %.2e)\n", k + 1, rel.q[k],
                abs.q[k], ref_q[k], rel.q[k] / ref_q[k] - 1, rel.q[k] / abs.q[k] - 1);
  EXPECT_NEAR(rel.phi2, ref_phi2, 1e-7);
  EXPECT_NEAR(rel.x3, ref_x3, 1e-7);
  EXPECT_NEAR(rel.q[0] / ref_q[0], 1.0, 3e-4);
  EXPECT_NEAR(rel.q[1] / ref_q[1], 1.0, 1e-3);
  EXPECT_NEAR(rel.q[2] / ref_q[2], 1.0, 1e-2);
  EXPECT_NEAR(rel.q[3] / ref_q[3], 1.0, 1e-2);
  EXPECT_LT(rel.worst_violation, 1e-12);
  // Both formulations at the same step: the same motion to the integrator's error.
  EXPECT_NEAR(rel.phi2, abs.phi2, 1e-8);
  EXPECT_NEAR(rel.x3, abs.x3, 1e-8);
  EXPECT_NEAR(rel.q[0] / abs.q[0], 1.0, 1e-4);
}

// ---- the 20-link pendulum chain ------------------------------------------------------------------

struct ChainRun {
  Eigen::MatrixXd tip;  // [steps, 2]
  double dE = 0, E0 = 0;
};

ChainRun run_chain(double h, double end, const char* formulation) {
  const Model model = test::model_from(formulations::pendulum_chain_json(20, h, end, formulation));
  Data data(model);
  initialize(model, data);
  ChainRun r;
  const auto n = step_count(model);
  r.tip.resize(n, 2);
  r.E0 = energy(model, data).total();
  const Body& last = model.bodies.back();
  for (std::int64_t i = 0; i < n; ++i) {
    step(model, data);
    const Vector3d tip = data.state.q.segment<3>(last.offset) + 0.1 * data.state.q.segment<3>(last.offset + 3);
    r.tip.row(i) = tip.head<2>().transpose();
    r.dE = std::max(r.dE, std::abs(energy(model, data).total() - r.E0));
  }
  return r;
}

double worst_tip_difference(const ChainRun& x, const ChainRun& y) {
  return (x.tip - y.tip).rowwise().norm().maxCoeff();
}

TEST(RelativeFormulation, TwentyLinkChainMatchesAbsolute) {
  const double end = 0.3;
  {
    const Model model = test::model_from(formulations::pendulum_chain_json(20, 1e-3, end, "relative"));
    EXPECT_EQ(model.relative->ns, 20);
    EXPECT_EQ(model.relative->kept_rows, 0);
  }
  double diff[2];
  int i = 0;
  for (const double h : {1e-3, 5e-4}) {
    const ChainRun abs = run_chain(h, end, "absolute"), rel = run_chain(h, end, "relative");
    diff[i] = worst_tip_difference(abs, rel);
    std::printf("20-link chain h = %g: worst |tip absolute - tip relative| %.3e m (chain 2 m); energy drift absolute %.2e, relative %.2e J\n",
                h, diff[i], abs.dE, rel.dE);
    EXPECT_LT(rel.dE, 1e-3);
    ++i;
  }
  EXPECT_LT(diff[1], 1e-3);
  EXPECT_NEAR(diff[0] / diff[1], 4.0, 1.0);
}

// ---- a flexible body placed by its joint ----------------------------------------------------------

// Simeon's rod (4 modes) hinged to the ground at its frame origin (a marker on its frame, not on
// a node): the tree places it by its angle and carries its modal coordinates. Released horizontal
// in gravity, it swings and bends. No outside reference: the two formulations must agree to O(h^2).
struct RodRun {
  double angle = 0;
  Eigen::VectorXd y;
};

RodRun run_rod(double h, const char* formulation, const std::filesystem::path& dir) {
  const std::string json = std::string(R"({"gravity": [0, -9.81, 0],
    "bodies": [{"name": "rod", "type": "flexible", "sid": "rod.sid.h5"}],
    "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "rod", "at": [0, 0, 0], "axis": [0, 0, 1]}],
    "solver": {"formulation": ")") + formulation + R"(", "end": 0.2, "step": )" + num(h) + "}}";
  const Model model = test::model_from(json, dir);
  if (std::string(formulation) == "relative") {
    EXPECT_TRUE(model.relative && !model.relative->bodies[0].free);
    EXPECT_EQ(model.relative->ns, 1 + model.bodies[0].nq);
  }
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const Vector3d u = data.state.q.segment<3>(3);
  return {std::atan2(u(1), u(0)), data.state.q.segment(12, model.bodies[0].nq)};
}

TEST(RelativeFormulation, FlexibleBodyPlacedByItsJointMatchesAbsolute) {
  test::TempDir dir("relative_rod");
  test::write_sid_file(test::simeon_rod_sid(), dir / "rod.sid.h5");
  double da[2], dy[2];
  int i = 0;
  for (const double h : {1e-3, 5e-4}) {
    const RodRun a = run_rod(h, "absolute", dir.path), r = run_rod(h, "relative", dir.path);
    da[i] = std::abs(a.angle - r.angle);
    dy[i] = (a.y - r.y).cwiseAbs().maxCoeff() / a.y.cwiseAbs().maxCoeff();
    std::printf("flexible pendulum h = %g: angle(0.2 s) absolute %.10f relative %.10f; modal coordinates apart by %.2e of their largest (%.3e)\n",
                h, a.angle, r.angle, dy[i], a.y.cwiseAbs().maxCoeff());
    ++i;
  }
  EXPECT_LT(da[1], 1e-5);
  EXPECT_GT(da[0] / da[1], 2.5);  // O(h^2): the two discretisations of the same equations converge
  EXPECT_LT(dy[1], 1e-3);
}

// ---- ffr-sim: results file and energy output from the reconstructed absolute state -------------

TEST(RelativeFormulation, FfrSimWritesTheSameOutputs) {
  test::TempDir dir("relative_cli");
  std::string values[2];
  int i = 0;
  for (const char* f : {"absolute", "relative"}) {
    std::string json = test::compound_pendulum_json(std::string(R"({"formulation": ")") + f + R"(", "end": 0.5, "step": 0.001})");
    const std::string out = R"("outputs": [)";
    json.insert(json.find(out) + out.size(), R"({"name": "energy", "type": "energy"}, )");
    test::write_text(dir / "m.json", json);
    const test::SimRun run = test::run_ffr_sim((dir / "m.json").string() + " -o " + (dir / "out.h5").string() + " --csv " +
                                               (dir / "out.csv").string());
    ASSERT_EQ(run.status, 0) << run.output;
    if (std::string(f) == "relative") {
      EXPECT_NE(run.output.find("note: relative formulation: 1 coordinates"), std::string::npos) << run.output;
    }
    std::ifstream csv(dir / "out.csv");
    std::string line, last;
    std::getline(csv, line);
    EXPECT_EQ(line, "time,energy[0],energy[1],energy[2],angle[0]");
    while (std::getline(csv, line)) last = line;
    values[i++] = last;
  }
  // time, kinetic, potential, total energy, angle at 0.5 s: the same to the integrator's error
  // (the angle's against the RK4 oracle too).
  double a[5], r[5];
  ASSERT_EQ(std::sscanf(values[0].c_str(), "%lf,%lf,%lf,%lf,%lf", &a[0], &a[1], &a[2], &a[3], &a[4]), 5) << values[0];
  ASSERT_EQ(std::sscanf(values[1].c_str(), "%lf,%lf,%lf,%lf,%lf", &r[0], &r[1], &r[2], &r[3], &r[4]), 5) << values[1];
  std::printf("ffr-sim at t = %g: absolute %s\n                 relative %s (oracle angle %.10f)\n", a[0], values[0].c_str(), values[1].c_str(),
              test::compound_pendulum_oracle(0.5));
  EXPECT_EQ(a[0], r[0]);
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(a[k], r[k], 1e-4);
  EXPECT_NEAR(r[4], test::compound_pendulum_oracle(0.5), 1e-5);
}

// ---- bad input ---------------------------------------------------------------------------------

TEST(RelativeFormulation, RefusesWhatItCannotRun) {
  const std::string pendulum = test::compound_pendulum_json(R"({"formulation": "relative", "end": 1.0, "step": "auto", "rtol": 1e-6})");
  test::expect_error(pendulum, "solver.formulation", "fixed steps only");
  test::expect_error(test::compound_pendulum_json(R"({"formulation": "joint", "end": 1.0, "step": 0.001})"), "formulation",
                     "unknown formulation 'joint'");
  std::string reaction = test::compound_pendulum_json(R"({"formulation": "relative", "end": 1.0, "step": 0.001})");
  const std::string out = R"("outputs": [)";
  reaction.insert(reaction.find(out) + out.size(), R"({"name": "r", "type": "joint_reaction", "joint": "hinge"}, )");
  test::expect_error(reaction, "outputs[0] ('r')", "joint_reaction of joint 'hinge'");
  // ffr-sim: exit status 2 and the file and field named.
  test::TempDir dir("relative_bad");
  test::write_text(dir / "model.json", pendulum);
  const test::SimRun run = test::run_ffr_sim((dir / "model.json").string() + " -o " + (dir / "out.h5").string());
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("solver.formulation"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

TEST(RelativeFormulation, AutoSaysWhatItChose) {
  // The rule (FORMULATION.md 18): relative when it has at most a third of the absolute coordinates in a tree, a fifth with loops.
  const Model chain = test::model_from(formulations::pendulum_chain_json(20, 1e-3, 0.01, "auto"));
  test::TempDir dir("relative_auto");
  test::write_sid_file(test::simeon_rod_sid(), dir / "rod.sid.h5");
  const Model crank = test::model_from(with_formulation(test::simeon_crank_json(1e-4, 0.01), "auto"), dir.path);
  ASSERT_FALSE(chain.notes.empty());
  ASSERT_FALSE(crank.notes.empty());
  std::printf("chain: %s\ncrank: %s\n", chain.notes.back().c_str(), crank.notes.back().c_str());
  EXPECT_TRUE(chain.relative);
  EXPECT_NE(chain.notes.back().find("relative (solver.formulation \"auto\": 20 relative coordinates against 240"), std::string::npos);
  // The flexible rod's joints are at its nodes: it is placed at its point on the crank (its frame
  // and modes its own coordinates), 15 of 40 coordinates.
  EXPECT_FALSE(crank.relative);
  EXPECT_NE(crank.notes.back().find("absolute (solver.formulation \"auto\": 15 relative coordinates against 40"), std::string::npos);
}

}  // namespace
