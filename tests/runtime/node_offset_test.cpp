// Points offset from a SID node (offset1/offset2): carried rigidly by the node's translation and
// small rotation, p = r0 + A (x_node + Phi y + o + (Psi y) x o) (the SID's linear node
// kinematics, formats/SPEC.md: Phi the node's translation and Psi its small rotation per unit
// modal amplitude), and `at` with a node refused.
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace ffr::runtime;

namespace {

std::string error_of(const std::string& json, const std::filesystem::path& dir) {
  try {
    test::model_from(json, dir);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& json, const std::filesystem::path& dir, const std::string& field, const std::string& what) {
  const std::string msg = error_of(json, dir);
  EXPECT_NE(msg.find("test-model.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find(field), std::string::npos) << "field '" << field << "' not in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "'" << what << "' not in: " << msg;
}

std::string flap_model(const std::string& joint, const std::string& force) {
  return R"({"bodies": [
      {"name": "flap", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0, 0.5, 0],
       "orientation": [[0, -1, 0], [1, 0, 0], [0, 0, 1]], "modal_coordinates": [0.01, -0.02, 0.015]},
      {"name": "arm", "type": "rigid", "mass": 1, "com": [1, 1, 1], "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]}],
    "joints": [)" + joint + R"(],
    "forces": [)" + force + R"(],
    "solver": {"end": 0.1, "step": 1e-3}})";
}

}  // namespace

TEST(NodeOffset, PointCarriedByTheNodesTranslationAndRotation) {
  test::TempDir dir("node_offset");
  test::write_sid_file(test::lumpy_body(3, 4, true, 0.01), dir / "lumpy.sid.h5");
  const Model model = test::model_from(
      flap_model(R"({"name": "j", "type": "spherical", "body1": "flap", "node1": "A", "offset1": [0.02, 0.03, -0.01], "body2": "arm"})",
                 R"({"type": "spring_damper", "body1": "ground", "at1": [3, 3, 3], "body2": "flap", "node2": "B", "offset2": [0.1, -0.05, 0.2], "k": 10})"),
      dir.path);
  Data data(model);
  // Move the flap away from its initial configuration: other modal amplitudes and a turned frame.
  const Body& b = model.bodies[0];
  Eigen::VectorXd y(3);
  y << -0.03, 0.02, 0.05;
  data.state.q.segment(b.offset + 12, 3) = y;
  const Eigen::Matrix3d A = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int a = 0; a < 3; ++a) data.state.q.segment<3>(b.offset + 3 + 3 * a) = A.col(a);
  data.state.q.segment<3>(b.offset) = Eigen::Vector3d(0.2, 0.4, -0.1);
  update_bodies(model, data);
  update_markers(model, data);
  struct Case {
    int marker;
    std::string node;
    Eigen::Vector3d o;
  } cases[2] = {{model.joints[0].m1, "A", {0.02, 0.03, -0.01}}, {model.springs[0].m2, "B", {0.1, -0.05, 0.2}}};
  for (const Case& c : cases) {
    const NodeSlice& n = b.nodes[static_cast<std::size_t>(b.find_node(c.node))];
    const Eigen::Vector3d theta = n.psi * y;
    const Eigen::Vector3d p = data.state.q.segment<3>(b.offset) + A * (n.origin + n.phi * y + c.o + theta.cross(c.o));
    EXPECT_LT((data.markers[static_cast<std::size_t>(c.marker)].p - p).norm(), 1e-14) << c.node;
  }
  // The joint's point: both sides at node A + offset in the initial configuration.
  Data d0(model);
  update_bodies(model, d0);
  update_markers(model, d0);
  EXPECT_LT((d0.markers[static_cast<std::size_t>(model.joints[0].m1)].p - d0.markers[static_cast<std::size_t>(model.joints[0].m2)].p).norm(), 1e-14);
}

TEST(NodeOffset, BadInputRefused) {
  test::TempDir dir("node_offset_bad");
  test::write_sid_file(test::lumpy_body(3, 4, true, 0.01), dir / "lumpy.sid.h5");
  expect_error(flap_model(R"({"name": "j", "type": "spherical", "body1": "flap", "node1": "A", "at": [0, 0, 0], "body2": "arm"})", ""),
               dir.path, "joints[0].at", "give either at or node1");
  expect_error(flap_model(R"({"name": "j", "type": "spherical", "body1": "arm", "body2": "flap", "node2": "A", "at": [0, 0, 0]})", ""),
               dir.path, "joints[0].at", "give either at or node2");
  expect_error(flap_model(R"({"name": "j", "type": "spherical", "body1": "flap", "offset1": [0, 0, 1], "at": [0, 0, 0], "body2": "arm"})", ""),
               dir.path, "joints[0].offset1", "give the node too");
  expect_error(flap_model(R"({"name": "j", "type": "spherical", "body1": "flap", "node1": "A", "body2": "arm"})",
                          R"({"type": "spring_damper", "body1": "ground", "at1": [3, 3, 3], "body2": "arm", "offset2": [0, 0, 1], "k": 1})"),
               dir.path, "forces[0].offset2", "give node2 too");
}
