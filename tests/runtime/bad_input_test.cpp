// Bad model inputs: each is refused with a ModelError whose message names the file and the
// offending field (or the SID file and dataset), never a crash or a half-built model.
#include "support.hpp"
#include "synthetic_bodies.hpp"
#include "ffr/formats/synthetic.hpp"
#include "ffr/runtime/step_control.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace ffr::runtime;

namespace {

const char* kRigid = R"({"name": "bar", "type": "rigid", "mass": 1.0, "com": [0.5, 0, 0],
  "inertia": [[1e-3, 0, 0], [0, 0.08, 0], [0, 0, 0.08]]})";

std::string model(const std::string& bodies, const std::string& rest = "") {
  return R"({"gravity": [0, 0, -9.81], "bodies": [)" + bodies + "]" + (rest.empty() ? "" : ", " + rest) +
         R"(, "solver": {"end": 1, "step": 0.001}})";
}

using test::error_of;
using test::expect_error;

// A flexible body "rod" whose mass lies on a line (a synthetic chain along x, line.sid.h5
// written into `dir`): no rotary inertia about that line. Its model-file entry.
std::string line_of_mass(const std::filesystem::path& dir) {
  ffr::formats::synthetic::ChainParams p;
  test::write_sid_file(ffr::formats::synthetic::spring_chain(p).sid, dir / "line.sid.h5");
  return R"({"name": "rod", "type": "flexible", "sid": "line.sid.h5"})";
}

}  // namespace

TEST(BadInput, MalformedJson) { expect_error(R"({"bodies": [)", "", "malformed JSON"); }

TEST(BadInput, UnknownBodyInJoint) {
  expect_error(model(kRigid, R"("joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "nope", "at": [0,0,0], "axis": [0,0,1]}])"),
               "joints[0].body2", "unknown body 'nope'");
}

TEST(BadInput, NonFiniteNumber) {
  // JSON has no NaN or infinity; an overflowing literal is caught while parsing.
  expect_error(model(R"({"name": "bar", "type": "rigid", "mass": 1e999, "inertia": [[1,0,0],[0,1,0],[0,0,1]]})"),
               "1e999", "not a finite number");
}

TEST(BadInput, NegativeMass) {
  expect_error(model(R"({"name": "bar", "type": "rigid", "mass": -1, "inertia": [[1,0,0],[0,1,0],[0,0,1]]})"),
               "bodies[0].mass", "expected a positive number");
}

TEST(BadInput, TypoInKey) {
  expect_error(model(kRigid, R"("joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "bar", "at": [0,0,0], "axsi": [0,0,1]}])"),
               "joints[0].axsi", "unknown field");
}

TEST(BadInput, ImpossibleInertia) {
  expect_error(model(R"({"name": "bar", "type": "rigid", "mass": 1, "inertia": [[1,0,0],[0,1,0],[0,0,3]]})"),
               "bodies[0].inertia", "triangle inequality");
}

TEST(BadInput, NotARotation) {
  expect_error(model(R"({"name": "bar", "type": "rigid", "mass": 1, "inertia": [[1,0,0],[0,1,0],[0,0,1]], "orientation": [[1,0,0],[0,2,0],[0,0,1]]})"),
               "bodies[0].orientation", "rotation matrix");
}

TEST(BadInput, MotionOnSphericalJoint) {
  expect_error(model(kRigid, R"("joints": [{"name": "j", "type": "spherical", "body1": "ground", "body2": "bar", "at": [0,0,0]}],
      "motions": [{"joint": "j", "table": {"t": [0, 1], "value": [0, 1]}}])"),
               "motions[0].joint", "no joint coordinate");
}

TEST(BadInput, TableTimesNotIncreasing) {
  expect_error(model(kRigid, R"("joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "bar", "at": [0,0,0], "axis": [0,0,1]}],
      "motions": [{"joint": "j", "table": {"t": [0, 1, 1], "value": [0, 1, 2]}}])"),
               "motions[0].table.t", "strictly increasing");
}

TEST(BadInput, DuplicateBodyName) { expect_error(model(std::string(kRigid) + ", " + kRigid), "bodies[1].name", "duplicate"); }

TEST(BadInput, UniversalAxesNotPerpendicular) {
  expect_error(model(kRigid, R"("joints": [{"name": "j", "type": "universal", "body1": "ground", "body2": "bar", "at": [0,0,0], "axis1": [1,0,0], "axis2": [1,1,0]}])"),
               "joints[0].axis2", "perpendicular");
}

TEST(BadInput, StepNotDividingTheRun) {
  const std::string json = R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"end": 1, "step": 0.3}})";
  expect_error(json, "solver.step", "whole number of steps");
}

// A bound on Newton's iterations that makes a stalled step run for hours is refused (it took up
// to 1e9; with "newton_tolerance": 1e-30 every step stalls at round-off).
TEST(BadInput, NewtonIterationsBeyondAThousandAreRefused) {
  const auto solver = [](const std::string& n) {
    return R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"end": 1, "step": 0.001, "max_iterations": )" + n + "}}";
  };
  EXPECT_EQ(test::model_from(solver("1000")).settings.max_iterations, 1000);
  expect_error(solver("1001"), "solver.max_iterations", "must be at most 1000");
  expect_error(solver("1000000000"), "solver.max_iterations", "a smaller step is the remedy");
}

// Settings no step can meet: a constraint tolerance below the coordinates' rounding (1e-300
// failed the first step, asking for a smaller one), a largest adaptive step below the error
// control's smallest (every step was rejected, the message asking to loosen rtol).
TEST(BadInput, TolerancesAndStepsBelowWhatTheSolverResolvesAreRefused) {
  const auto solver = [](const std::string& keys) {
    return R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"end": 1, )" + keys + "}}";
  };
  EXPECT_EQ(test::model_from(solver(R"("step": 0.001, "tolerance": 1e-15)")).settings.tolerance, 1e-15);
  expect_error(solver(R"("step": 0.001, "tolerance": 1e-300)"), "solver.tolerance", "below what double precision can reach");
  // A loose one left violations that cost accuracy without a word (Andrews' mechanism: 1e-3
  // ended 1.3e-4 rad off, andrews_options_test.cpp).
  EXPECT_EQ(test::model_from(solver(R"("step": 0.001, "tolerance": 1e-8)")).settings.tolerance, 1e-8);
  expect_error(solver(R"("step": 0.001, "tolerance": 1e-3)"), "solver.tolerance", "must be at most 1e-08 of the model length");
  expect_error(R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"analysis": "static", "tolerance": 1e-16}})",
               "solver.tolerance", "below what double precision can reach");
  // A penalty whose rounding costs accuracy (kMaxPenalty, andrews_options_test.cpp); 1e20 ended in
  // "the mass matrix with the joints' constraints is singular" at the start.
  EXPECT_EQ(test::model_from(solver(R"("step": 0.001, "penalty": 1e9)")).settings.penalty, 1e9);
  expect_error(solver(R"("step": 0.001, "penalty": 1e20)"), "solver.penalty", "must be at most 1e+09");
  expect_error(R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"analysis": "static", "penalty": 1e10}})",
               "solver.penalty", "must be at most 1e+09");
  EXPECT_EQ(test::model_from(solver(R"("step": "auto", "max_step": 1e-10)")).settings.max_step, 1e-10);
  expect_error(solver(R"("step": "auto", "max_step": 1e-300)"), "solver.max_step",
               "is below the smallest step the error control takes, 1e-10 s (1e-10 of the run)");
}

// Far from t = 0 doubles are far apart (0.125 s at 1e15 s): a step of 0.01 s left t where it
// was, the fixed-step run wrote 101 samples all at t = 1e15 and the adaptive one never ended.
// A step must span 1e5 such spacings (time_resolution_step, model.hpp).
TEST(BadInput, StepsFinerThanTheRunsTimesResolveAreRefused) {
  const auto run = [](const std::string& keys) { return R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {)" + keys + "}}"; };
  expect_error(run(R"("start": 1e15, "end": 1000000000000001, "step": 0.01)"), "solver.start",
               "times near 1e+15 s are resolved only to 0.125 s (the spacing of doubles there), and the step, 0.01 s, "
               "spans fewer than 1e+05 of them (at least 1.25e+04 s): start the run nearer to t = 0");
  expect_error(run(R"("start": 1e9, "end": 1000000001, "step": "auto", "output_interval": 0.01)"), "solver.start",
               "the longest step this run takes (max_step or output_interval), 0.01 s, spans fewer than 1e+05 of them");
  expect_error(run(R"("start": 1e9, "end": 1000001000, "step": "auto", "max_step": 1e-3)"), "solver.start",
               "(at least 0.0119 s)");
  // Where the spacing is fine enough, the same runs load.
  EXPECT_EQ(test::model_from(run(R"("start": 1000, "end": 1001, "step": 1e-4)")).settings.start, 1000);
  EXPECT_EQ(test::model_from(run(R"("start": 1e9, "end": 1000001000, "step": 0.5)")).settings.step, 0.5);
  EXPECT_EQ(test::model_from(run(R"("start": 1e9, "end": 1000001000, "step": "auto")")).settings.output_interval, 10);
  // An adaptive step that shrinks below that bound gives up naming it and the remedy.
  const std::string shrinking = R"({"gravity": [0, 0, -9.81], "bodies": [)" + std::string(kRigid) +
                                R"(], "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bar",
      "at": [0, 0, 0], "axis": [0, 1, 0]}], "solver": {"start": 1e6, "end": 1000001, "step": "auto", "rtol": 1e-12}})";
  const Model m = test::model_from(shrinking);
  Data d(m);
  try {
    initialize(m, d);
    StepControl control(m, d);
    advance_to(m, d, control, m.settings.end);
    ADD_FAILURE() << "a run from t = 1e6 s at rtol 1e-12 ended";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("fell below the minimum 1.16e-05 s (what times this far from t = 0 resolve) at t = 1000000 s"),
              std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("start the run nearer to t = 0"), std::string::npos) << e.what();
  }
}

TEST(BadInput, StepLongerThanTheRun) {
  // (end - start) / step rounded to 0 steps passed as a whole number: the run did nothing, exit 0.
  const std::string json = R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"end": 0.05, "step": 1000}})";
  expect_error(json, "solver.step", "longer than the run");
}

TEST(BadInput, HugeAxisIsRefusedAndTinyOneIsADirection) {
  // [0, 1e200, 0] squared to infinity and normalised to a zero axis.
  const std::string joint = R"("joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "bar", "at": [0,0,0], "axis": %s}])";
  char buf[512];
  std::snprintf(buf, sizeof buf, joint.c_str(), "[0, 1e200, 0]");
  expect_error(model(kRigid, buf), "joints[0].axis[1]", "magnitude beyond 1e30");
  std::snprintf(buf, sizeof buf, joint.c_str(), "[0, 1e-200, 0]");
  const Model m = test::model_from(model(kRigid, buf));
  const Marker& ground = m.markers[static_cast<std::size_t>(m.joints[0].m1)];
  EXPECT_NEAR((ground.E.col(0) - Vector3d(0, 1, 0)).norm(), 0.0, 1e-15);
}

TEST(BadInput, UnknownOutputType) {
  expect_error(model(kRigid, R"("outputs": [{"name": "x", "type": "stress"}])"), "outputs[0].type", "unknown output type");
}

TEST(BadInput, MissingSidFile) {
  test::TempDir dir("bad");
  const std::string msg = error_of(model(R"({"name": "rod", "type": "flexible", "sid": "nope.sid.h5"})"), dir.path);
  EXPECT_NE(msg.find("nope.sid.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bodies[0].sid"), std::string::npos) << msg;
}

TEST(BadInput, SidThatIsNotHdf5) {
  test::TempDir dir("bad");
  test::write_text(dir / "junk.sid.h5", "this is not an HDF5 file");
  const std::string msg = error_of(model(R"({"name": "rod", "type": "flexible", "sid": "junk.sid.h5"})"), dir.path);
  EXPECT_NE(msg.find("junk.sid.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not an HDF5 file"), std::string::npos) << msg;
}

TEST(BadInput, SidFailingDefinitenessIsRefusedOtherIdentitiesAreNoted) {
  test::TempDir dir("bad");
  // A negative-definite Ke read without complaint and gave motion (found by fuzzing ffr-sim).
  ffr::formats::Sid sid = test::lumpy_body();
  sid.Ke = -sid.Ke;
  test::write_sid_file(sid, dir / "neg.sid.h5");
  const std::string body = R"({"name": "b", "type": "flexible", "sid": "%s"})";
  char buf[256];
  std::snprintf(buf, sizeof buf, body.c_str(), "neg.sid.h5");
  const std::string msg = error_of(model(buf), dir.path);
  EXPECT_NE(msg.find("neg.sid.h5: /sid/Ke/M0: fails the SID validation: Ke positive semi-definite"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bodies[0].sid"), std::string::npos) << msg;
  // The lumpy test body's modes are called free but not orthogonal to the rigid motion: the
  // formulation takes the members as given, so that is a note, not a refusal.
  test::write_sid_file(test::lumpy_body(), dir / "lumpy.sid.h5");
  std::snprintf(buf, sizeof buf, body.c_str(), "lumpy.sid.h5");
  const Model m = test::model_from(model(buf), dir.path);
  bool noted = false;
  for (const auto& n : m.notes) noted = noted || n.find("SID validation check(s) fail, first free: Ct.M0 = 0") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(BadInput, SidWithoutModalMassIsNamedNotTheModel) {
  // The refusal named the model file with the SID's dataset (found by fuzzing).
  test::TempDir dir("bad");
  ffr::formats::Sid sid = test::lumpy_body();
  for (int a = 0; a < 3; ++a) sid.integrals.PPdm[a][a] = -sid.integrals.PPdm[a][a];
  test::write_sid_file(sid, dir / "pp.sid.h5");
  const std::string msg = error_of(model(R"({"name": "b", "type": "flexible", "sid": "pp.sid.h5"})"), dir.path);
  EXPECT_NE(msg.find("pp.sid.h5: /integrals/PPdm: the modal mass matrix is not positive definite"), std::string::npos) << msg;
  EXPECT_NE(msg.find("test-model.json: bodies[0].sid"), std::string::npos) << msg;
}

TEST(BadInput, UnknownNodeOfFlexibleBody) {
  test::TempDir dir("bad");
  test::write_sid_file(test::lumpy_body(), dir / "b.sid.h5");
  const std::string msg = error_of(
      model(R"({"name": "rod", "type": "flexible", "sid": "b.sid.h5"})",
            R"("joints": [{"name": "j", "type": "spherical", "body1": "ground", "body2": "rod", "node2": "Z"}])"),
      dir.path);
  EXPECT_NE(msg.find("joints[0].node2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("has no node 'Z' (nodes: A, B, C)"), std::string::npos) << msg;
}

TEST(BadInput, ModalCoordinatesOfWrongLength) {
  test::TempDir dir("bad");
  test::write_sid_file(test::lumpy_body(), dir / "b.sid.h5");
  expect_error(model(R"({"name": "rod", "type": "flexible", "sid": "b.sid.h5", "modal_coordinates": [1, 2]})"),
               "bodies[0].modal_coordinates", "expected 3 numbers", dir.path);
}

TEST(BadInput, MissingModelFile) {
  try {
    load_model("/nonexistent/model.json");
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/model.json: no such file"), std::string::npos) << e.what();
  }
}

TEST(BadInput, ReusedTangentIsRefused) {
  // A tangent kept over steps does not keep the integrator's accuracy (andrews_options_test.cpp):
  // refused, not silently less accurate. The default spelled out is fine.
  const std::string reuse = R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"end": 1, "step": 0.001, "reuse_jacobian": true}})";
  expect_error(reuse, "solver.reuse_jacobian", "does not keep the integrator's accuracy");
  const std::string plain = R"({"bodies": [)" + std::string(kRigid) + R"(], "solver": {"end": 1, "step": 0.001, "reuse_jacobian": false}})";
  EXPECT_EQ(error_of(plain), "");
}

TEST(BadInput, SidWhoseNormalModesHaveNoFrequencyIsRefused) {
  // Frequencies read as zeros were summarised as "validation FAILED" yet run (issue 40): a
  // normal mode without a positive frequency is now a failed property, refused at load.
  test::TempDir dir("bad");
  ffr::formats::Sid sid = test::lumpy_body();
  for (auto& t : sid.refmod.mode_type) t = ffr::formats::ModeType::Normal;
  sid.refmod.frequency_hz.setZero();
  test::write_sid_file(sid, dir / "f0.sid.h5");
  const std::string msg = error_of(model(R"({"name": "b", "type": "flexible", "sid": "f0.sid.h5"})"), dir.path);
  EXPECT_NE(msg.find("f0.sid.h5: /refmod/frequency_hz /refmod/mode_type: fails the SID validation: normal modes: frequency_hz > 0"),
            std::string::npos)
      << msg;
}

TEST(BadInput, LineOfMassOnASphericalJointIsRefusedNamingTheBody) {
  // Points on a line without rotary inertia: no inertia about the line. On a spherical joint
  // nothing holds that rotation and the first step ended in "state is not finite" (issue 40);
  // on a hinge across the line the body runs (chain_test).
  test::TempDir dir("bad");
  const std::string body = line_of_mass(dir.path);
  const std::string msg = error_of(
      model(body, R"("joints": [{"name": "ball", "type": "spherical", "body1": "ground", "body2": "rod", "node2": "A"}])"),
      dir.path);
  EXPECT_NE(msg.find("test-model.json: bodies[0]: body 'rod' (line.sid.h5)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[1, 0, 0] (body frame) has no inertia, and its joints (spherical 'ball') leave it free"), std::string::npos)
      << msg;
  // A hinge along the line leaves it free too; one across it holds it.
  EXPECT_NE(error_of(model(body, R"("joints": [{"name": "h", "type": "revolute", "body1": "ground", "body2": "rod", "node2": "A", "axis": [1, 0, 0]}])"),
                     dir.path)
                .find("body 'rod'"),
            std::string::npos);
  EXPECT_EQ(error_of(model(body, R"("joints": [{"name": "h", "type": "revolute", "body1": "ground", "body2": "rod", "node2": "A", "axis": [0, 1, 0]}])"),
                     dir.path),
            "");
}

// A bushing does not hold that rotation: the start's accelerations are solved with the mass and
// the joints alone, and a lumped chain on a bushing (torsional stiffness about the line too)
// started from non-finite accelerations, its first step failing with "the state is not finite"
// and "try a smaller step". Refused at load now; where such a motion still reaches the start (a
// universal joint is taken to hold it, its free rotation here the line), the start names it.
TEST(BadInput, LineOfMassOnABushingIsRefusedAndTheStartNamesASingularMass) {
  test::TempDir dir("bad");
  const std::string body = line_of_mass(dir.path);
  const std::string msg = error_of(
      model(body, R"("forces": [{"type": "bushing", "body1": "rod", "node1": "B", "body2": "ground",
        "stiffness": [1000, 1000, 1000, 10, 10, 10], "damping": [1, 1, 1, 0.1, 0.1, 0.1]}])"),
      dir.path);
  EXPECT_NE(msg.find("body 'rod' (line.sid.h5): its principal moments of inertia"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no joint holds it: the equations of motion are singular (a bushing does not hold it"), std::string::npos) << msg;

  const Model m = test::model_from(
      model(body, R"("joints": [{"name": "u", "type": "universal", "body1": "ground", "body2": "rod", "node2": "A",
        "axis1": [0, 0, 1], "axis2": [1, 0, 0]}])"),
      dir.path);
  Data d(m);
  try {
    (void)initialize(m, d);
    ADD_FAILURE() << "the start did not fail";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("the initial accelerations at t = 0 s are not finite: the mass matrix with the "
                                         "joints' constraints is singular"),
              std::string::npos)
        << e.what();
  }
}

// A model without a body has no coordinate to integrate: ffr-sim ended in a segmentation fault
// (the start's projections took the largest entry of an empty vector). Each formulation refuses
// it; one body loads.
TEST(BadInput, AModelWithoutBodiesIsRefused) {
  for (const char* formulation : {"absolute", "relative", "auto"}) {
    const std::string json = R"({"gravity": [0, -9.81, 0], "bodies": [], "joints": [], "solver": {"formulation": ")" +
                             std::string(formulation) + R"(", "end": 0.01, "step": 0.001}})";
    expect_error(json, "bodies", "no body: the model has nothing to integrate");
  }
  EXPECT_EQ(error_of(model(kRigid)), "");
}

// More coordinates than the step's dense matrices are sized for: refused once the bodies are
// counted, naming the count and the largest body, before any matrix of that size is made. 416
// rigid bodies have 4992 coordinates (allowed: the model loads), 417 have 5004.
TEST(BadInput, MoreCoordinatesThanTheStepHoldsAreRefused) {
  const auto bodies = [](int n) {
    std::string s;
    for (int i = 0; i < n; ++i)
      s += std::string(i ? ", " : "") + R"({"name": "b)" + std::to_string(i) +
           R"(", "type": "rigid", "mass": 1.0, "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]]})";
    return s;
  };
  EXPECT_EQ(test::model_from(model(bodies(kMaxModelCoordinates / 12))).ncoord, 12 * (kMaxModelCoordinates / 12));
  expect_error(model(bodies(kMaxModelCoordinates / 12 + 1)), "bodies", "the model has 5004 coordinates in 417 bodies");
}
