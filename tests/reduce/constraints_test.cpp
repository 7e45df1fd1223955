// Interface couplings as a DOF transformation: both spiders carry rigid-body motion exactly
// (an RBE2 by construction, an RBE3 because the least-squares fit of a rigid motion is that
// motion), held interfaces remove the DOFs, and an averaged interface node moves with the
// mean of its group.
#include "ffr/formats/h5.hpp"
#include "ffr/preproc/model/constraints.hpp"

#include <Eigen/Geometry>
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr;
using preproc::Index;

namespace {

// Two HEX8 cells along x (12 nodes): groups "left" (x = 0) and "right" (x = 2).
struct Bar {
  preproc::Mesh mesh;
  preproc::PartSpec part;
  Bar(const std::string& left_coupling, const std::string& right_coupling) {
    mesh.x.resize(12, 3);
    int n = 0;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k) mesh.x.row(n++) << i, (k == 1 || k == 2) ? 1.0 : 0.0, k >= 2 ? 1.0 : 0.0;
    preproc::ElementBlock b{preproc::ElementType::Hex8, "body", {}, {}};
    for (int c = 0; c < 2; ++c) {
      const int o = 4 * c, p = 4 * (c + 1);
      for (int v : {o + 0, p + 0, p + 1, o + 1, o + 3, p + 3, p + 2, o + 2}) b.conn.push_back(v);
    }
    mesh.blocks.push_back(b);
    mesh.node_groups["body"] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    mesh.node_groups["left"] = {0, 1, 2, 3};
    mesh.node_groups["right"] = {8, 9, 10, 11};
    part.file = "bar.json";
    part.materials.push_back({"body", {1e3, 0.3, 1.0}});
    part.interfaces.push_back({"L", "left", left_coupling, {}});
    part.interfaces.push_back({"R", "right", right_coupling, {}});
  }
};

Eigen::VectorXd rigid_full(const preproc::FeModel& m, const Eigen::Vector3d& u, const Eigen::Vector3d& th) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(m.num_dofs);
  for (Index n = 0; n < m.mesh->num_nodes(); ++n) v.segment<3>(m.dof(n, 0)) = u + th.cross(Eigen::Vector3d(m.mesh->x.row(n)));
  for (const auto& i : m.interfaces) {
    v.segment<3>(i.dof) = u + th.cross(i.x);
    v.segment<3>(i.dof + 3) = th;
  }
  return v;
}

}  // namespace

TEST(Constraints, RigidAndAveragedSpidersCarryRigidMotion) {
  for (const char* coupling : {"rigid", "averaged"}) {
    Bar bar(coupling, coupling);
    const auto model = preproc::build_model(bar.mesh, bar.part);
    const auto t = preproc::build_transform(model, {preproc::InterfaceState::Free, preproc::InterfaceState::Boundary});
    const Eigen::MatrixXd R = preproc::rigid_body_modes(model, t);
    for (int j = 0; j < 6; ++j) {
      Eigen::Vector3d u = Eigen::Vector3d::Zero(), th = Eigen::Vector3d::Zero();
      if (j < 3) u(j) = 1.0;
      else th(j - 3) = 1.0;
      const Eigen::VectorXd full = t.T * R.col(j);
      EXPECT_LT((full - rigid_full(model, u, th)).cwiseAbs().maxCoeff(), 1e-12) << coupling << " rigid mode " << j;
    }
  }
}

TEST(Constraints, HeldRigidInterfaceRemovesItsGroup) {
  Bar bar("rigid", "rigid");
  const auto model = preproc::build_model(bar.mesh, bar.part);
  const auto t = preproc::build_transform(model, {preproc::InterfaceState::Held, preproc::InterfaceState::Free});
  // 12 nodes x 3 + 2 x 6 interface DOFs; left group (12 DOFs) and L (6) held; right group (12) follows R.
  EXPECT_EQ(t.num_ind(), 36 + 12 - 12 - 6 - 12);
  for (Index n : {0, 1, 2, 3})
    for (int a = 0; a < 3; ++a) EXPECT_EQ(t.T.row(model.dof(n, a)).norm(), 0.0);
}

TEST(Constraints, AveragedInterfaceFollowsTheGroupMean) {
  Bar bar("averaged", "averaged");
  const auto model = preproc::build_model(bar.mesh, bar.part);
  const auto t = preproc::build_transform(model, {preproc::InterfaceState::Free, preproc::InterfaceState::Free});
  // Push only node 8 of the right group in y: R moves by a quarter of it (equal weights).
  Eigen::VectorXd ind = Eigen::VectorXd::Zero(t.num_ind());
  ind(t.ind_of_full[static_cast<std::size_t>(model.dof(8, 1))]) = 1.0;
  const Eigen::VectorXd full = t.T * ind;
  EXPECT_NEAR(full(model.interfaces[1].dof + 1), 0.25, 1e-14);
}

TEST(Constraints, OverlappingGroupsAreRefused) {
  Bar bar("rigid", "rigid");
  bar.mesh.node_groups["right"] = {3, 8, 9, 10, 11};  // node 3 is also in "left"
  const auto model = preproc::build_model(bar.mesh, bar.part);
  try {
    preproc::build_transform(model, {preproc::InterfaceState::Free, preproc::InterfaceState::Free});
    FAIL() << "overlap not detected";
  } catch (const formats::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("must not overlap"), std::string::npos) << e.what();
  }
}
