// Consistent initial conditions with a flexible body (FORMULATION.md section 10): when turning
// the body frames can satisfy the joints and motions, the modal coordinates and velocities keep
// their given values (zero here) instead of absorbing part of the correction, which would start
// the body vibrating in its stiffest modes. Only when the frames cannot do it do the modes move.
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"

#include <gtest/gtest.h>

using namespace ffr::runtime;

namespace {

// A lumpy flexible body pinned at its node A to a hub driven at 20 rad/s, its node B pinned to a
// rigid link that slides along x (a slider-crank with the flexible body as the crank), all given
// at rest: every velocity must be made up by the initial projection.
std::string driven(const std::string& extra_joint) {
  return R"({
  "bodies": [
    {"name": "flex", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0, 0, 0]}
  ],
  "joints": [
    {"name": "hub", "type": "revolute", "body1": "ground", "body2": "flex", "node2": "A", "axis": [0, 0, 1]})" +
         extra_joint + R"(
  ],
  "motions": [{"joint": "hub", "table": {"t": [0, 1], "value": [0, 20]}}],
  "solver": {"end": 0.01, "step": 1e-3}
})";
}

// max |Phi_q q_dot + Phi_t|
double velocity_violation(const Model& model, const Data& data) {
  VectorXd c = VectorXd::Zero(model.nconstraints);  // constraint_times writes into a sized vector
  constraint_times(model, data, data.state.qd, c);
  return (c + data.Phit).cwiseAbs().maxCoeff();
}

struct InitialConditions : ::testing::Test {
  test::TempDir dir{"ic"};
  void SetUp() override { test::write_sid_file(test::lumpy_body(3), dir / "lumpy.sid.h5"); }
};

}  // namespace

TEST_F(InitialConditions, FramesTakeTheCorrectionAndTheModesStayAtRest) {
  const Model model = test::model_from(driven(""), dir.path);
  Data data(model);
  initialize(model, data);
  const Body& b = model.bodies[0];
  // The hub's motion is met by turning the frame: modal velocities stay zero (to the AL
  // iteration's round-off), and the hub's rate is the prescribed 20 rad/s.
  EXPECT_LT(data.state.qd.segment(b.offset + 12, b.nq).cwiseAbs().maxCoeff(), 1e-9)
      << data.state.qd.segment(b.offset + 12, b.nq).transpose();
  EXPECT_LT(data.state.q.segment(b.offset + 12, b.nq).cwiseAbs().maxCoeff(), 1e-12);
  evaluate_constraints(model, data, data.state.t);
  EXPECT_LT(data.Phi.cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT(velocity_violation(model, data), 1e-8);
}

TEST_F(InitialConditions, ModesMoveOnlyWhenTheFramesCannotSatisfyTheJoints) {
  // Node B also fixed to the ground at its initial place: the driven hub can then only turn by
  // deforming the body, so the projection must give modal velocities (and not fail).
  const std::string fixedB = R"(,
    {"name": "holdB", "type": "spherical", "body1": "flex", "body2": "ground", "node1": "B"})";
  const Model model = test::model_from(driven(fixedB), dir.path);
  Data data(model);
  initialize(model, data);
  const Body& b = model.bodies[0];
  EXPECT_GT(data.state.qd.segment(b.offset + 12, b.nq).cwiseAbs().maxCoeff(), 1e-3);
  evaluate_constraints(model, data, data.state.t);
  EXPECT_LT(velocity_violation(model, data), 1e-8);
}
