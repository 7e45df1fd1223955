// Rigid-body properties of a meshed polyhedral part (m, first moment, inertia about O) equal
// OpenCASCADE's exact mass properties of the same geometry (through gmsh), for TET4 and
// TET10 meshes: a polyhedron is meshed exactly, and the consistent mass integrates exactly.
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

namespace {
const char* kGeo = R"(SetFactory("OpenCASCADE");
// An L-shaped, chamfered, pocketed block placed away from the origin (all faces planar).
Box(1) = {0.1, -0.05, 0.02, 0.12, 0.06, 0.03};
Box(2) = {0.1, -0.05, 0.05, 0.03, 0.06, 0.05};
Wedge(3) = {0.13, -0.05, 0.05, 0.04, 0.06, 0.03};
Box(4) = {0.16, -0.03, 0.03, 0.04, 0.02, 0.03};
BooleanUnion(10) = { Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
BooleanDifference(11) = { Volume{10}; Delete; }{ Volume{4}; Delete; };
Physical Volume("body") = {11};
)";
}  // namespace

class MassProperties : public ::testing::TestWithParam<int> {};

TEST_P(MassProperties, EqualOpenCascadeExactProperties) {
  const int order = GetParam();
  test::TempDir dir("massprops");
  test::write_text(dir / "part.geo", kGeo);
  const double rho = 7850;
  test::write_text(dir / "part.json", R"({"geometry": "part.geo", "mesh": {"size": 0.012, "order": )" +
                                          std::to_string(order) + R"(},
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "reduction": {"method": "free", "modes": 4}, "visual": false})");
  const formats::Sid sid = preproc::run_pipeline(preproc::load_part(dir / "part.json"));
  const preproc::GeometryMass occ = preproc::occ_mass_properties(dir / "part.geo");

  const double m = rho * occ.volume;
  const Eigen::Vector3d md = m * occ.centroid;
  const Eigen::Vector3d& c = occ.centroid;
  const Eigen::Matrix3d J = rho * occ.inertia_about_centroid + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  EXPECT_NEAR(sid.refmod.mass, m, 1e-9 * m);
  EXPECT_LT((sid.mdCM.M0 - md).norm(), 1e-9 * md.norm()) << sid.mdCM.M0.transpose() << " vs " << md.transpose();
  EXPECT_LT((sid.J.M0 - J).norm(), 1e-9 * J.norm()) << sid.J.M0 << "\nvs\n" << J;
}

INSTANTIATE_TEST_SUITE_P(Tet4AndTet10, MassProperties, ::testing::Values(1, 2));
