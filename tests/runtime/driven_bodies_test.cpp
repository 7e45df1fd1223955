// Driven bodies (FORMULATION.md section 9): a rigid body held by a fixed joint to the ground, or
// turned (slid) by a revolute (prismatic) joint whose coordinate a motion prescribes, follows its
// drive instead of being integrated. The reference is the same model with every body integrated
// (SolverSettings::eliminate_driven = false), where the drive is enforced through the joint and
// motion rows like any other constraint: both solve the same equations, so they must agree to
// the solver's tolerance. The drive's Phi_t and gamma are checked against central differences in
// time, and drives that contradict each other are reported as such.
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "models.hpp"  // tools/models: the benchmark's slider-crank
#include "ffr/runtime/energy.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ffr::runtime;

namespace {

// A table slid along x by a prescribed displacement (the table is the prismatic joint's body1:
// the drive's sign logic for marker 1), an arm hinged on it and swinging under gravity, a post
// welded to the ground (a fixed drive) pulling the arm through a spring-damper.
const char* kTableArmPost = R"({
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "table", "type": "rigid", "mass": 2.0, "com": [0, 0, 0],
     "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]},
    {"name": "arm", "type": "rigid", "mass": 0.5, "com": [0.1, 0, 0],
     "inertia": [[1e-4, 0, 0], [0, 2e-3, 0], [0, 0, 2e-3]], "angular_velocity": [0, 0, 3]},
    {"name": "post", "type": "rigid", "mass": 1.0, "com": [0.3, 0.2, 0],
     "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]]}
  ],
  "joints": [
    {"name": "rail", "type": "prismatic", "body1": "table", "body2": "ground", "at": [0, 0, 0], "axis": [1, 0, 0]},
    {"name": "hinge", "type": "revolute", "body1": "table", "body2": "arm", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "weld", "type": "fixed", "body1": "ground", "body2": "post", "at": [0.3, 0.2, 0]}
  ],
  "forces": [{"type": "spring_damper", "body1": "post", "at1": [0.3, 0.2, 0], "body2": "arm", "at2": [0.2, 0, 0],
              "k": 200, "c": 0.5, "length0": 0.15}],
  "motions": [{"joint": "rail", "table": {"t": [0, 0.1, 0.2, 0.3, 0.4], "value": [0, 0.01, 0.03, 0.02, 0.0]}}],
  "solver": {"end": 0.4, "step": 1e-3}
})";

Model with_drives(Model m, bool eliminate) {
  m.settings.eliminate_driven = eliminate;
  finalize(m);
  return m;
}

// Runs both versions step by step; returns the largest difference of the given coordinates
// (looked up by body name: its frame origin and frame vectors, and modal coordinates).
double largest_difference(const Model& model, const std::vector<std::string>& bodies) {
  const Model reduced = with_drives(model, true), whole = with_drives(model, false);
  Data a(reduced), b(whole);
  initialize(reduced, a);
  initialize(whole, b);
  double worst = 0;
  for (std::int64_t i = 0; i < step_count(reduced); ++i) {
    step(reduced, a);
    step(whole, b);
    for (const auto& name : bodies) {
      const Body& ba = reduced.bodies[static_cast<std::size_t>(reduced.find_body(name))];
      const Body& bb = whole.bodies[static_cast<std::size_t>(whole.find_body(name))];
      worst = std::max(worst, (a.state.q.segment(ba.offset, ba.ncoord()) - b.state.q.segment(bb.offset, bb.ncoord())).cwiseAbs().maxCoeff());
    }
  }
  return worst;
}

Model benchmark_crank(const test::TempDir& dir, double end) {
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 10));
  bench::add_section_inertia(chain.sid, 0.008, 0.008);
  test::write_sid_file(chain.sid, dir / "rod.sid.h5");
  return test::model_from(bench::slider_crank_json("rod.sid.h5", 1e-3, end, 150.0), dir.path);
}

}  // namespace

TEST(DrivenBodies, TheDrivenCrankLeavesTheUnknowns) {
  test::TempDir dir("driven_counts");
  const Model m = benchmark_crank(dir, 0.01);
  const Body& crank = m.bodies[static_cast<std::size_t>(m.find_body("crank"))];
  EXPECT_EQ(crank.drive.kind, DriveKind::Revolute);
  EXPECT_EQ(m.ncoord, 46);
  EXPECT_EQ(m.nfree, 34);         // rod (12 + 10 modes) and slider (12)
  EXPECT_EQ(m.nconstraints, 39);
  // The crank's frame, its hub and the hub's motion drop out, and the slider's frame (frame-locked
  // by its guide) with the guide's three rotational rows (both its frames known).
  EXPECT_EQ(m.nactive, 18);
  EXPECT_EQ(crank.offset, 34);    // the driven coordinates after the integrated ones
  EXPECT_TRUE(m.bodies[static_cast<std::size_t>(m.find_body("slider"))].frame_locked);
  EXPECT_EQ(m.nunknown, 25);      // the slider's frame vectors are known
  Data data(m);
  initialize(m, data);
  EXPECT_EQ(data.nf, 34);
  EXPECT_EQ(data.unknowns.size(), 25u);
  EXPECT_EQ(data.na, 18);
  const Model whole = with_drives(m, false);
  EXPECT_EQ(whole.nfree, 46);
  EXPECT_EQ(whole.nunknown, 46);
  EXPECT_EQ(whole.nactive, 39);
}

// The benchmark's flexible slider-crank, crank at 150 rad/s: the rod's and the slider's
// coordinates with the crank eliminated against the crank integrated, 0.1 s.
TEST(DrivenBodies, EliminatedCrankAgreesWithTheIntegratedOne) {
  test::TempDir dir("driven_crank");
  const Model m = benchmark_crank(dir, 0.1);
  const double d = largest_difference(m, {"crank", "rod", "slider"});
  std::printf("largest coordinate difference over 100 steps: %.3g\n", d);
  EXPECT_LT(d, 1e-8);
  EXPECT_GT(d, 0.0);  // two computations, not one
}

TEST(DrivenBodies, PrismaticAndFixedDrivesAgreeWithTheIntegratedBodies) {
  const Model m = test::model_from(kTableArmPost);
  EXPECT_EQ(m.bodies[0].drive.kind, DriveKind::Prismatic);
  EXPECT_EQ(m.bodies[0].drive.side, 1);
  EXPECT_EQ(m.bodies[2].drive.kind, DriveKind::Fixed);
  EXPECT_EQ(m.nfree, 12);  // the arm alone
  const double d = largest_difference(m, {"table", "arm", "post"});
  std::printf("largest coordinate difference over 400 steps: %.3g\n", d);
  EXPECT_LT(d, 1e-8);
}

// An elliptic trammel: a link hinged to two sliders on perpendicular rails, swinging under
// gravity. Both sliders are frame-locked (prismatic joints to the ground without motions): 18
// frame coordinates and 12 frame rows leave the step; the motion must be the integrated one's.
TEST(DrivenBodies, FrameLockedSlidersAgreeWithTheIntegratedBodies) {
  const Model m = test::model_from(R"({
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "a", "type": "rigid", "mass": 0.5, "com": [0, 0, 0], "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]],
     "position": [0.21213203435596426, 0, 0]},
    {"name": "b", "type": "rigid", "mass": 0.3, "com": [0, 0, 0], "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]],
     "position": [0, 0.21213203435596426, 0]},
    {"name": "link", "type": "rigid", "mass": 0.2, "com": [0, 0, 0],
     "inertia": [[7.6e-4, 7.5e-4, 0], [7.5e-4, 7.6e-4, 0], [0, 0, 1.51e-3]],
     "position": [0.10606601717798213, 0.10606601717798213, 0], "angular_velocity": [0, 0, 4]}
  ],
  "joints": [
    {"name": "rail_a", "type": "prismatic", "body1": "ground", "body2": "a", "at": [0.21213203435596426, 0, 0], "axis": [1, 0, 0]},
    {"name": "rail_b", "type": "prismatic", "body1": "b", "body2": "ground", "at": [0, 0.21213203435596426, 0], "axis": [0, 1, 0]},
    {"name": "pin_a", "type": "revolute", "body1": "a", "body2": "link", "at": [0.21213203435596426, 0, 0], "axis": [0, 0, 1]},
    {"name": "pin_b", "type": "revolute", "body1": "link", "body2": "b", "at": [0, 0.21213203435596426, 0], "axis": [0, 0, 1]}
  ],
  "solver": {"end": 0.4, "step": 1e-3}
})");
  EXPECT_TRUE(m.bodies[0].frame_locked);
  EXPECT_TRUE(m.bodies[1].frame_locked);  // its rail's ground side is marker 2
  EXPECT_FALSE(m.bodies[2].frame_locked);
  EXPECT_EQ(m.nfree, 36);
  EXPECT_EQ(m.nunknown, 18);
  EXPECT_EQ(m.nactive, 3 * 6 + 2 * 5 + 2 * 5 - 2 * 6 - 2 * 3);  // less the rails' rotational rows
  const double d = largest_difference(m, {"a", "b", "link"});
  std::printf("largest coordinate difference over 400 steps: %.3g\n", d);
  EXPECT_LT(d, 1e-8);
  EXPECT_GT(d, 0.0);  // two computations, not one
  // The sliders did slide (the check is not of a model at rest), with their frames out of the
  // unknowns (no body is driven here).
  Data data(m);
  initialize(m, data);
  EXPECT_EQ(data.unknowns.size(), 18u);
  EXPECT_EQ(data.na, m.nactive);
  const Vector3d a0 = data.state.q.segment<3>(m.bodies[0].offset);
  for (int i = 0; i < 200; ++i) step(m, data);
  EXPECT_GT((data.state.q.segment<3>(m.bodies[0].offset) - a0).norm(), 1e-2);
}

// Phi_t and gamma of the rows that join integrated to driven bodies are the first and second
// time derivatives of Phi at fixed unknowns (with their rates zero): central differences of the
// driven bodies' exact motion.
TEST(DrivenBodies, RatesAndBiasesAreTimeDerivativesOfTheDrive) {
  test::TempDir dir("driven_fd");
  for (const bool crank : {true, false}) {
    const Model m = crank ? benchmark_crank(dir, 0.01) : test::model_from(kTableArmPost);
    Data data(m);
    initialize(m, data);
    for (int i = 0; i < 5; ++i) step(m, data);
    const double t = crank ? data.state.t : 0.15;  // the table at a point of its spline with curvature
    data.state.qd.head(m.nfree).setZero();
    data.state.qdd.head(m.nfree).setZero();
    const auto phi_at = [&](double time) {
      drive_bodies(m, data, time);
      update_bodies(m, data);
      update_markers(m, data);
      evaluate_constraints(m, data, time);
      return Eigen::VectorXd(data.Phi.head(m.nactive));
    };
    const double dt = 1e-5;
    const Eigen::VectorXd p1 = phi_at(t + dt), p_1 = phi_at(t - dt), p0 = phi_at(t);
    const Eigen::VectorXd rate = (p1 - p_1) / (2 * dt), acc = (p1 - 2 * p0 + p_1) / (dt * dt);
    const Eigen::VectorXd Phit = data.Phit.head(m.nactive), gamma = data.gamma.head(m.nactive);
    const double scale_v = std::max(1e-3, Phit.cwiseAbs().maxCoeff()), scale_a = std::max(1e-3, gamma.cwiseAbs().maxCoeff());
    std::printf("%s: |Phi_t| %.3g, error %.3g; |gamma| %.3g, error %.3g\n", crank ? "crank" : "table", scale_v,
                (rate - Phit).cwiseAbs().maxCoeff(), scale_a, (acc - gamma).cwiseAbs().maxCoeff());
    EXPECT_GT(Phit.cwiseAbs().maxCoeff(), 1e-3);  // the drive moves these rows
    EXPECT_LT((rate - Phit).cwiseAbs().maxCoeff(), 1e-6 * scale_v);
    EXPECT_LT((acc - gamma).cwiseAbs().maxCoeff(), 1e-3 * scale_a);
  }
}

// A second joint with its own motion on the crank, given the same table (the initial conditions
// need both met with the same velocities) and then, as a simulator would through the C API, an
// input at odds with the first: no unknown can meet both, and the message says which joint and
// why.
TEST(DrivenBodies, DisagreeingDrivesAreReported) {
  test::TempDir dir("driven_disagree");
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 4));
  test::write_sid_file(chain.sid, dir / "rod.sid.h5");
  std::string json = bench::slider_crank_json("rod.sid.h5", 1e-3, 0.05, 20.0);
  const auto joints = json.find("\"joints\": [");
  json.insert(joints + 11, R"({"name": "hub2", "type": "revolute", "body1": "ground", "body2": "crank", "at": [0, 0, 0], "axis": [0, 0, 1]},)");
  const auto motions = json.find("\"motions\": [");
  json.insert(motions + 12, R"({"joint": "hub2", "table": {"t": [0, 1], "value": [0, 20]}},)");
  const Model m = test::model_from(json, dir.path);
  Data data(m);
  initialize(m, data);
  step(m, data);  // the two agree
  data.motion_external[0] = 1;  // hub2's motion: held at its present angle from here on
  data.motion_value[0] = Eigen::Vector3d(20.0 * data.state.t, 0, 0);
  try {
    for (std::int64_t i = 1; i < step_count(m); ++i) step(m, data);
    FAIL() << "two motions at odds on one body ran to the end";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("'hub'"), std::string::npos) << what;
    EXPECT_NE(what.find("disagree"), std::string::npos) << what;
  }
}

// An ancf beam's frame, held at the global frame, is known while driven bodies are eliminated:
// its twelve coordinates leave the step, and so do S_a(y), Jc(y) and the frame's blocks of M,
// which only the frame reads (FORMULATION.md 15), and the step's passes over the tangent cover
// the beam's band alone (tangent_blocks.hpp, for_each_body_block). A soft pendulum of twelve
// elements on a spherical pin, released from the horizontal, against the same model with the
// frame integrated (where all of them are computed, over the whole dense tangent): the nodes, the
// energy and the angular momentum about the pin (whose S_a the output computes itself) must agree
// to the solver's tolerance.
TEST(DrivenBodies, KnownAncfFrameAgreesWithTheIntegratedOne) {
  const Model m = test::model_from(R"({
  "gravity": [0, 0, -9.81],
  "bodies": [{"name": "beam", "type": "beam", "formulation": "ancf", "start": [0, 0, 0], "end": [1.2, 0, 0], "elements": 12,
              "E": 5e6, "rho": 5540, "section": {"A": 0.0018, "Iy": 1.215e-8, "Iz": 1.215e-8}}],
  "joints": [{"name": "pin", "type": "spherical", "body1": "ground", "body2": "beam", "node2": "start"}],
  "solver": {"end": 0.3, "step": 1e-3}
})");
  const Model known = with_drives(m, true), whole = with_drives(m, false);
  ASSERT_EQ(whole.nunknown - known.nunknown, 12);
  Data a(known), b(whole);
  initialize(known, a);
  initialize(whole, b);
  EXPECT_TRUE(a.tangent_blocks_pay);  // the band's blocks
  EXPECT_FALSE(b.tangent_blocks_pay);
  const Body& beam = known.bodies[0];
  double dq = 0, dE = 0, dH = 0, H_max = 0;
  for (std::int64_t i = 0; i < step_count(known); ++i) {
    step(known, a);
    step(whole, b);
    dq = std::max(dq, (a.state.q.segment(12, beam.nq) - b.state.q.segment(12, beam.nq)).cwiseAbs().maxCoeff());
    const Energy ea = energy(known, a), eb = energy(whole, b);
    dE = std::max(dE, std::abs(ea.kinetic + ea.potential - eb.kinetic - eb.potential) / std::abs(eb.potential));
    const Vector3d Ha = angular_momentum(known, a), Hb = angular_momentum(whole, b);
    dH = std::max(dH, (Ha - Hb).norm());
    H_max = std::max(H_max, Hb.norm());
  }
  std::printf("largest differences over 300 steps: nodal coordinates %.3g m, energy %.3g, angular momentum %.3g of %.3g\n",
              dq, dE, dH, H_max);
  EXPECT_GT(H_max, 1.0);  // it swings: about 20 kg m^2/s by the end
  EXPECT_LT(dq, 1e-8);
  EXPECT_LT(dE, 1e-8);
  EXPECT_LT(dH, 1e-8 * H_max);
}
