// A free-free beam (2-node Timoshenko beam elements from a gmsh line mesh) carrying a rigid
// body at its tip, with an offset centre of mass and its own inertia: the case of Wagner & Pfeiffer, 'On the Dynamics of Washing Machines'.
//  - m, first moment and inertia about O equal the beam's plus the body's by the
//    parallel-axis theorem, exactly;
//  - the invariants are consistent with the mass matrix the modes were computed with: free-free
//    modes give Ct.M0 = Cr.M0 = 0 and Me = I. That holds only if the body's points move with
//    u + psi x e (the Wagner–Pfeiffer correction) in the integrals too: the test shows the
//    naive invariants (the body as a point on the node's translation) violate it.
// The frequencies themselves are checked against the continuous beam's frequency equation in
// tests/beams (BeamModal.FreeFreeBeamWithOffsetTipBodyMatchesContinuousSolution).
#include "ffr/preproc/pipeline.hpp"
#include "../reduce/support.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

using namespace ffr;

namespace {
constexpr double L = 1.0, rho = 7850, A = 1e-3, Iy = 2e-7, Iz = 8e-7, J = 6e-7;
constexpr double m_body = 4.0;
const Eigen::Vector3d kOffset(0.06, 0.04, -0.03);
const Eigen::Matrix3d kInertia = (Eigen::Matrix3d() << 0.002, 0.0003, 0, 0.0003, 0.0015, 0, 0, 0, 0.003).finished();

formats::Sid reduce(const test::TempDir& dir) {
  test::write_text(dir / "beam.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("beam") = {1};
)");
  test::write_text(dir / "beam.json", R"({"geometry": "beam.geo", "mesh": {"order": 1},
    "beams": [{"group": "beam", "E": 2.1e11, "nu": 0.3, "rho": 7850, "y_axis": [0, 1, 0],
               "section": {"A": 1e-3, "Iy": 2e-7, "Iz": 8e-7, "J": 6e-7, "ky": 0.8333, "kz": 0.8333}}],
    "point_masses": [{"name": "body", "at": [1, 0, 0], "mass": 4.0, "com_offset": [0.06, 0.04, -0.03],
                      "inertia": [[0.002, 0.0003, 0], [0.0003, 0.0015, 0], [0, 0, 0.003]]}],
    "output_nodes": [{"name": "tip", "at": [1, 0, 0]}],
    "reduction": {"method": "free", "modes": 10}, "visual": false})");
  return preproc::run_pipeline(preproc::load_part(dir / "beam.json"));
}
}  // namespace

TEST(TipBody, RigidPropertiesFollowTheParallelAxisTheorem) {
  test::TempDir dir("tipbody");
  const formats::Sid sid = reduce(dir);
  const Eigen::Matrix3d E = Eigen::Matrix3d::Identity();
  // Beam on x in [0, L]: section second moments Iy = int z^2, Iz = int y^2 (contract).
  const double mb = rho * A * L;
  Eigen::Matrix3d Jb = Eigen::Matrix3d::Zero();
  Jb(0, 0) = rho * L * (Iy + Iz);
  Jb(1, 1) = mb * L * L / 3 + rho * L * Iy;
  Jb(2, 2) = mb * L * L / 3 + rho * L * Iz;
  const Eigen::Vector3d c = Eigen::Vector3d(L, 0, 0) + kOffset;
  const Eigen::Matrix3d Jc = kInertia + m_body * (c.squaredNorm() * E - c * c.transpose());
  EXPECT_NEAR(sid.refmod.mass, mb + m_body, 1e-12 * (mb + m_body));
  EXPECT_LT((sid.mdCM.M0 - (Eigen::Vector3d(mb * L / 2, 0, 0) + m_body * c)).norm(), 1e-12 * mb * L);
  EXPECT_LT((sid.J.M0 - (Jb + Jc)).cwiseAbs().maxCoeff(), 1e-12 * sid.J.M0.norm()) << sid.J.M0 << "\nvs\n" << Jb + Jc;
}

TEST(TipBody, InvariantsIncludeTheOffsetKinematics) {
  test::TempDir dir("tipbody");
  const formats::Sid sid = reduce(dir);
  const auto nq = sid.nq();
  EXPECT_LT((sid.Me - Eigen::MatrixXd::Identity(nq, nq)).cwiseAbs().maxCoeff(), 1e-8);
  const double sm = std::sqrt(sid.refmod.mass), sj = std::sqrt(sid.J.M0.trace());
  EXPECT_LT(sid.Ct.M0.cwiseAbs().maxCoeff(), 1e-8 * sm);
  EXPECT_LT(sid.Cr.M0.cwiseAbs().maxCoeff(), 1e-8 * sj);

  // The naive invariants treat the body as a point at its centre moving with the node's
  // translation only (no psi x e, no rotary inertia): they break the free-free identities.
  const auto p = sid.find_node("tip");
  ASSERT_GE(p, 0);
  const auto& node = sid.nodes[static_cast<std::size_t>(p)];
  const Eigen::Vector3d c = node.origin + kOffset;
  double worst_t = 0, worst_r = 0;
  for (Eigen::Index k = 0; k < nq; ++k) {
    const Eigen::Vector3d phi = node.phi.col(k), psi = node.psi.col(k);
    const Eigen::Vector3d u_c = phi + psi.cross(kOffset);  // the body's centre: u + psi x e
    const Eigen::Vector3d ct_naive = sid.Ct.M0.row(k).transpose() - m_body * u_c + m_body * phi;
    const Eigen::Vector3d cr_naive =
        sid.Cr.M0.row(k).transpose() - (m_body * c.cross(u_c) + kInertia * psi) + m_body * c.cross(phi);
    worst_t = std::max(worst_t, ct_naive.norm());
    worst_r = std::max(worst_r, cr_naive.norm());
  }
  EXPECT_GT(worst_t, 1e-3 * sm) << "the offset must matter for this body";
  EXPECT_GT(worst_r, 1e-3 * sj);
}
