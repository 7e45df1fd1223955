// Bodies placed at a joint's point by the relative formulation (FORMULATION.md 18: spherical
// joints, and joints at flexible nodes, assembled without multipliers or constraint rows for the
// point), against references computed without that assembly:
//  - a 3-D spherical double pendulum against the absolute formulation (natural coordinates, the
//    spherical joints as constraint rows): two discretisations of the same equations, so their
//    difference must be small and shrink with the step; and the invariants of the continuous motion, energy and the
//    angular momentum about the vertical through the fixed pivot (gravity exerts no moment about
//    it), kept to the integrator's error;
//  - a rigid body hung on an ANCF or geometrically exact beam's end node, and on a clamped ANCF
//    plate's centre node, by an assembled spherical joint (seed 003's coupling by assembly): the
//    static tip equals that of the body's weight applied as a point force at the node (statics of
//    a pin: the weight passes, no moment), the relative steps hold that equilibrium, and released
//    from the unloaded configuration it moves as the absolute formulation's model does.
#include "relative_assembly_models.hpp"
#include "simeon_rod.hpp"
#include "synthetic_bodies.hpp"
#include "support.hpp"

#include "ffr/runtime/energy.hpp"
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

struct Trace {
  Eigen::MatrixXd tip;  // [steps, 3]
  double dE = 0, E0 = 0, dLz = 0;
};

Trace run(const Model& model) {
  Data data(model);
  initialize(model, data);
  Trace r;
  const auto n = step_count(model);
  r.tip.resize(n, 3);
  r.E0 = energy(model, data).total();
  const double Lz0 = angular_momentum(model, data)(2);
  for (std::int64_t i = 0; i < n; ++i) {
    step(model, data);
    const auto x = test::output(model, data, "tip");
    r.tip.row(i) << x[0], x[1], x[2];
    r.dE = std::max(r.dE, std::abs(energy(model, data).total() - r.E0));
    r.dLz = std::max(r.dLz, std::abs(angular_momentum(model, data)(2) - Lz0));
  }
  return r;
}

TEST(RelativeAssembly, SphericalDoublePendulumMatchesAbsolute) {
  using relative_assembly::spherical_double_pendulum_json;
  const Model probe = test::model_from(spherical_double_pendulum_json(1e-3, 1.0, "relative"));
  ASSERT_TRUE(probe.relative);
  // Both bars placed at their points: 2 x 9 frame coordinates, their 2 x 6 frame rows kept, no
  // joint rows (absolute: 24 coordinates, 12 frame rows and 6 joint rows).
  EXPECT_EQ(probe.relative->ns, 18);
  EXPECT_EQ(probe.relative->kept_rows, 12);
  for (const auto& n : probe.notes) std::printf("note: %s\n", n.c_str());
  EXPECT_TRUE(has_note(probe, "joint 'shoulder' assembled (spherical, body 'bar1' placed at its point on the ground)"));
  EXPECT_TRUE(has_note(probe, "joint 'elbow' assembled (spherical, body 'bar2' placed at its point on 'bar1')"));
  double diff[2];
  int i = 0;
  for (const double h : {1e-3, 5e-4}) {
    const Trace rel = run(test::model_from(spherical_double_pendulum_json(h, 1.0, "relative")));
    const Trace abs = run(test::model_from(spherical_double_pendulum_json(h, 1.0, "absolute")));
    diff[i] = (rel.tip - abs.tip).rowwise().norm().maxCoeff();
    const double spread = rel.tip.col(1).cwiseAbs().maxCoeff();  // out of the initial plane
    std::printf("spherical double pendulum h = %g: tip apart by %.3e m (out-of-plane excursion %.3f m); energy drift relative %.3e "
                "absolute %.3e J of %.3f; Lz drift relative %.3e absolute %.3e\n",
                h, diff[i], spread, rel.dE, abs.dE, std::abs(rel.E0), rel.dLz, abs.dLz);
    EXPECT_GT(spread, 0.1);  // a 3-D motion
    EXPECT_LT(rel.dE, 1e-3 * 0.5 * (1.0 * 9.81 * 0.2 + 0.7 * 9.81 * 0.6));
    EXPECT_LT(rel.dLz, 1e-3);
    ++i;
  }
  // The placement is linear in the coordinates (r = P - A x), so both integrate the same
  // trapezoidal equations; they part by their iterations' tolerances, which the motion's
  // sensitivity amplifies, and must come closer as the step (and so each step's error) shrinks.
  EXPECT_LT(diff[0], 1e-3);
  EXPECT_LT(diff[1], diff[0] / 3);
}

// The elbow a universal joint: bar2 placed at its point, the joint's one rotation row kept.
TEST(RelativeAssembly, UniversalJointPlacesAtItsPointAndMatchesAbsolute) {
  using relative_assembly::spherical_double_pendulum_json;
  const Model probe = test::model_from(spherical_double_pendulum_json(1e-3, 1.0, "relative", true));
  ASSERT_TRUE(probe.relative);
  EXPECT_EQ(probe.relative->ns, 18);
  EXPECT_EQ(probe.relative->kept_rows, 13);
  EXPECT_TRUE(has_note(probe, "joint 'elbow' assembled (universal, body 'bar2' placed at its point on 'bar1'; its rotation rows stay constraints)"));
  double diff[2];
  int i = 0;
  for (const double h : {1e-3, 5e-4}) {
    const Trace rel = run(test::model_from(spherical_double_pendulum_json(h, 1.0, "relative", true)));
    const Trace abs = run(test::model_from(spherical_double_pendulum_json(h, 1.0, "absolute", true)));
    diff[i] = (rel.tip - abs.tip).rowwise().norm().maxCoeff();
    std::printf("universal elbow h = %g: tip apart by %.3e m; energy drift relative %.3e absolute %.3e J; Lz drift relative %.3e absolute %.3e\n",
                h, diff[i], rel.dE, abs.dE, rel.dLz, abs.dLz);
    EXPECT_LT(rel.dE, 1e-3 * 0.5 * (1.0 * 9.81 * 0.2 + 0.7 * 9.81 * 0.6));
    EXPECT_LT(rel.dLz, 1e-3);
    ++i;
  }
  EXPECT_LT(diff[0], 1e-3);
  EXPECT_LT(diff[1], diff[0] / 3);
}

// The hung bob: assembled at the node, the static tip of the weight as a point force, held by the
// relative steps; released from the unloaded configuration, the absolute model's motion. The
// tip starts at z = 0, so |z| of the point-force tip is the static deflection.
void hung_body_checks(const std::string& what, const std::string& static_rel, const std::string& dyn_rel, const std::string& dyn_abs,
                      const std::string& point_force, const std::string& note) {
  SCOPED_TRACE(what);
  const Model loaded = test::model_from(point_force);
  Data dl(loaded);
  initialize(loaded, dl);
  const auto tl = test::output(loaded, dl, "tip");
  const double deflection = std::abs(tl[2]);
  // Static: initial_equilibrium settles it (statics in natural coordinates: the equilibrium does
  // not depend on the coordinates the steps take), then the relative steps must keep it.
  const Model rel = test::model_from(static_rel);
  ASSERT_TRUE(rel.relative);
  for (const auto& n : rel.notes) std::printf("note: %s\n", n.c_str());
  EXPECT_TRUE(has_note(rel, note));
  Data dr(rel);
  initialize(rel, dr);
  const auto t0 = test::output(rel, dr, "tip");
  double drift = 0;
  for (std::int64_t k = 0; k < step_count(rel); ++k) {
    step(rel, dr);
    const auto x = test::output(rel, dr, "tip");
    for (int c = 0; c < 3; ++c) drift = std::max(drift, std::abs(x[c] - t0[c]));
  }
  std::printf("%s: static tip (%.12f, %.12f), weight as a point force (%.12f, %.12f); %lld relative steps moved it by %.3e m\n",
              what.c_str(), t0[0], t0[2], tl[0], tl[2], static_cast<long long>(step_count(rel)), drift);
  EXPECT_GT(deflection, 1e-4);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(t0[c], tl[c], 1e-9 * deflection + 1e-12);
  EXPECT_LT(drift, 1e-6 * deflection);
  // Dynamic: released from the unloaded configuration, relative against absolute at one step.
  const Trace r = run(test::model_from(dyn_rel)), a = run(test::model_from(dyn_abs));
  const double apart = (r.tip - a.tip).rowwise().norm().maxCoeff();
  const double moved = r.tip.col(2).cwiseAbs().maxCoeff();
  std::printf("%s released: tip apart by %.3e m over a motion of %.3e m\n", what.c_str(), apart, moved);
  EXPECT_GT(moved, 0.3 * deflection);
  EXPECT_LT(apart, 1e-3 * moved);
}

std::string solver(const char* formulation, const char* rest) {
  return std::string(R"({"formulation": ")") + formulation + "\", " + rest + "}";
}

TEST(RelativeAssembly, RigidBodyHungOnABeamEndByAnAssembledSphericalJoint) {
  using relative_assembly::hung_bob_json;
  for (const std::string form : {"ancf", "geometrically_exact"}) {
    const std::string note = form == "ancf" ? "joint 'hang' assembled (spherical, body 'bob' placed at node 'end' of 'beam')"
                                            : "joint 'hang' assembled (spherical, body 'bob' placed at its point on 'beam:n16')";
    hung_body_checks("beam " + form, hung_bob_json(form, solver("relative", R"("initial_equilibrium": true, "end": 0.05, "step": 1e-3)")),
                     hung_bob_json(form, solver("relative", R"("end": 0.06, "step": 5e-4)")),
                     hung_bob_json(form, solver("absolute", R"("end": 0.06, "step": 5e-4)")),
                     hung_bob_json(form, R"({"analysis": "static"})", false), note);
  }
}

// A geometrically exact beam's node is a rigid body (FORMULATION.md 17): a body welded to it by a
// fixed joint is placed wholly (no coordinate of its own); its centre of mass at the node, its
// weight loads the tip as a point force there.
TEST(RelativeAssembly, RigidBodyWeldedToAGeometricallyExactBeamEnd) {
  using relative_assembly::welded_bob_json;
  const Model m = test::model_from(welded_bob_json(solver("relative", R"("end": 0.01, "step": 1e-3)")));
  ASSERT_TRUE(m.relative);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (m.bodies[b].name == "bob") {
      EXPECT_TRUE(!m.relative->bodies[b].free && !m.relative->bodies[b].point);
    }
  }
  hung_body_checks("welded on a geometrically exact beam", welded_bob_json(solver("relative", R"("initial_equilibrium": true, "end": 0.05, "step": 1e-3)")),
                   welded_bob_json(solver("relative", R"("end": 0.06, "step": 5e-4)")),
                   welded_bob_json(solver("absolute", R"("end": 0.06, "step": 5e-4)")),
                   relative_assembly::hung_bob_json("geometrically_exact", R"({"analysis": "static"})", false),
                   "joint 'weld' assembled (fixed, body 'bob' placed on 'beam:n16' by 0 joint coordinate(s))");
}

TEST(RelativeAssembly, RigidBodyHungOnAPlateNodeByAnAssembledSphericalJoint) {
  using relative_assembly::plate_bob_json;
  hung_body_checks("plate", plate_bob_json(solver("relative", R"("initial_equilibrium": true, "end": 0.05, "step": 1e-3)")),
                   plate_bob_json(solver("relative", R"("end": 0.06, "step": 5e-4)")),
                   plate_bob_json(solver("absolute", R"("end": 0.06, "step": 5e-4)")), plate_bob_json(R"({"analysis": "static"})", false),
                   "joint 'hang' assembled (spherical, body 'bob' placed at node 'n2_2' of 'plate')");
}

// A body hung by a spherical joint on a reduced flexible body's node (Simeon's rod of the IVP
// Test Set slider-crank, 4 modes, hinged to the ground at its frame origin and released
// horizontal): placed at the node's point r + A (c + Phi y), against the absolute run (no outside
// reference: two discretisations of the same equations, apart by O(h^2)), at three steps.
struct RodBob {
  Eigen::Vector3d bob;
  Eigen::VectorXd y;
};
RodBob run_rod_bob(double h, const char* formulation, const std::filesystem::path& dir) {
  const std::string json = std::string(R"({"gravity": [0, -9.81, 0],
    "bodies": [{"name": "rod", "type": "flexible", "sid": "rod.sid.h5"},
      {"name": "bob", "type": "rigid", "mass": 0.05, "com": [0.2, -0.05, 0.02], "inertia": [[1e-5, 0, 0], [0, 1.2e-5, 0], [0, 0, 1.4e-5]]}],
    "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "rod", "at": [0, 0, 0], "axis": [0, 0, 1]},
               {"name": "hang", "type": "spherical", "body1": "rod", "node1": "M", "body2": "bob"}],
    "solver": {"formulation": ")") + formulation + R"(", "end": 0.2, "step": )" + relative_assembly::num(h) + R"(},
    "outputs": [{"name": "bob", "type": "node_position", "body": "bob", "at": [0.2, -0.05, 0.02]}]})";
  const Model model = test::model_from(json, dir);
  if (std::string(formulation) == "relative") {
    EXPECT_TRUE(has_note(model, "joint 'hang' assembled (spherical, body 'bob' placed at node 'M' of 'rod')"));
    EXPECT_TRUE(model.relative && model.relative->bodies[1].point);
  }
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  const auto x = test::output(model, data, "bob");
  return {Eigen::Vector3d(x[0], x[1], x[2]), data.state.q.segment(12, model.bodies[0].nq)};
}

TEST(RelativeAssembly, BodyHungOnAReducedFlexibleBodysNode) {
  test::TempDir dir("relative_rod_bob");
  test::write_sid_file(test::simeon_rod_sid(), dir / "rod.sid.h5");
  double dx[3], dy[3];
  int i = 0;
  for (const double h : {1e-3, 5e-4, 2.5e-4}) {
    const RodBob a = run_rod_bob(h, "absolute", dir.path), r = run_rod_bob(h, "relative", dir.path);
    dx[i] = (a.bob - r.bob).norm();
    dy[i] = (a.y - r.y).cwiseAbs().maxCoeff() / a.y.cwiseAbs().maxCoeff();
    std::printf("bob on the rod's node h = %g: bob at (%.6f, %.6f, %.6f), apart by %.3e m; modal coordinates apart by %.2e of their largest (%.3e)\n",
                h, r.bob(0), r.bob(1), r.bob(2), dx[i], dy[i], a.y.cwiseAbs().maxCoeff());
    ++i;
  }
  // Measured: 1.26e-6, 6.7e-7 and 1.1e-7 m (the halvings' ratios vary with the phase of the
  // fast modes; over the two, 11.5 where O(h^2) gives 16).
  EXPECT_LT(dx[2], 1e-6);
  EXPECT_GT(dx[0] / dx[2], 8);
  // (The modal coordinates at the end, a few 1e-7 of the rod's length, are dominated by the fast
  // axial modes' phase, which the step changes in either formulation: printed, not compared.)
  (void)dy;
}

// ffr-sim says which joints it assembled.
TEST(RelativeAssembly, FfrSimReportsTheAssembledJoints) {
  test::TempDir dir("relative_assembly_cli");
  test::write_text(dir / "model.json",
                   relative_assembly::hung_bob_json("ancf", R"({"formulation": "relative", "end": 0.01, "step": 1e-3})"));
  const test::SimRun run = test::run_ffr_sim((dir / "model.json").string() + " -o " + (dir / "out.h5").string());
  std::printf("%s\n", run.output.c_str());
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("joint 'hang' assembled (spherical, body 'bob' placed at node 'end' of 'beam')"), std::string::npos) << run.output;
}

}  // namespace
