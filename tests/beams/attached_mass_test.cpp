// The rigid body hung on a node (Wagner & Pfeiffer, 'On the Dynamics of Washing Machines'): mass properties by the parallel-axis theorem,
// M from the rigid kinematics u_P = u_p + theta x (e + s), mass samples, input errors.

#include "ffr/preproc/elements/attached_mass.hpp"

#include "test_util.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

using namespace ffr::preproc;

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

// A body with principal moments (0.3, 0.5, 0.7) about rotated principal axes.
Eigen::Matrix3d inertia() {
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  return Q * Eigen::Vector3d(0.3, 0.5, 0.7).asDiagonal() * Q.transpose();
}

}  // namespace

TEST(AttachedMass, MassPropertiesByTheParallelAxisTheorem) {
  const Eigen::Vector3d p(1.0, -0.5, 2.0), e(0.1, 0.25, -0.3);
  const double m = 12.5;
  const Eigen::Matrix3d Ic = inertia();
  const ElementMatrices em = attached_mass(p, m, e, Ic);
  ASSERT_EQ(em.samples.size(), 6u);
  double w = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(6, 6);
  for (const auto& s : em.samples) {
    EXPECT_GT(s.w, 0);
    w += s.w;
    first += s.w * s.c;
    second += s.w * s.c * s.c.transpose();
    S += s.w * s.N.transpose() * s.N;
  }
  const Eigen::Vector3d r = p + e;
  EXPECT_NEAR(w, m, 1e-14 * m);
  EXPECT_LT((first - m * r).norm(), 1e-13 * m * r.norm());
  // Inertia about the origin: I_O = I_c + m (|r|^2 1 - r r^T) (parallel axes).
  const Eigen::Matrix3d IO = second.trace() * Eigen::Matrix3d::Identity() - second;
  const Eigen::Matrix3d IO_ref = Ic + m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  EXPECT_LT((IO - IO_ref).norm(), 1e-12 * IO_ref.norm());
  // Samples reproduce M; no stiffness, no rotary part.
  EXPECT_LT((S - em.M).norm(), 1e-13 * em.M.norm());
  EXPECT_EQ(em.K.norm(), 0.0);
  EXPECT_EQ(em.M_rotary.size(), 0);
  EXPECT_EQ(em.dofs_per_node, 6);
}

TEST(AttachedMass, MassMatrixIsTheRigidBodyKinematics) {
  const Eigen::Vector3d p(0.2, 0.1, -0.4), e(-0.3, 0.05, 0.12);
  const double m = 3.0;
  const Eigen::Matrix3d Ic = inertia();
  const ElementMatrices em = attached_mass(p, m, e, Ic);
  // Closed form (Wagner & Pfeiffer, ibid.): [[m 1, -m e~], [m e~, Ic - m e~ e~]].
  Eigen::MatrixXd ref(6, 6);
  ref << m * Eigen::Matrix3d::Identity(), -m * skew(e), m * skew(e), Ic - m * skew(e) * skew(e);
  EXPECT_LT((em.M - ref).norm(), 1e-13 * ref.norm());
  // Kinetic energy of node velocities (v, omega): the centre moves with v + omega x e.
  for (int k = 0; k < 5; ++k) {
    const Eigen::Matrix<double, 6, 1> q = Eigen::Matrix<double, 6, 1>::Random();
    const Eigen::Vector3d v = q.head<3>(), om = q.tail<3>();
    const double T = 0.5 * q.dot(em.M * q);
    const double T_ref = 0.5 * m * (v + om.cross(e)).squaredNorm() + 0.5 * om.dot(Ic * om);
    EXPECT_NEAR(T, T_ref, 1e-13 * T_ref);
  }
}

TEST(AttachedMass, PointMassAndFlatBody) {
  // A point mass (zero inertia) and a flat body (Iz = Ix + Iy: one principal S is zero).
  const ElementMatrices pm = attached_mass(Eigen::Vector3d(1, 2, 3), 2.0, Eigen::Vector3d::Zero(),
                                           Eigen::Matrix3d::Zero());
  for (const auto& s : pm.samples) EXPECT_LT((s.c - Eigen::Vector3d(1, 2, 3)).norm(), 1e-15);
  const Eigen::Matrix3d flat = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  const ElementMatrices fb = attached_mass(Eigen::Vector3d::Zero(), 5.0, Eigen::Vector3d(0, 0, 1), flat);
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& s : fb.samples) second += s.w * (s.c - Eigen::Vector3d(0, 0, 1)) * (s.c - Eigen::Vector3d(0, 0, 1)).transpose();
  EXPECT_LT((second.trace() * Eigen::Matrix3d::Identity() - second - flat).norm(), 1e-13);
}

TEST(AttachedMass, RefusesBadInput) {
  const Eigen::Vector3d p = Eigen::Vector3d::Zero(), e = Eigen::Vector3d::Zero();
  EXPECT_THROW_MSG(attached_mass(p, 0.0, e, inertia()), ElementError, "mass must be > 0");
  EXPECT_THROW_MSG(attached_mass(p, -2.0, e, inertia()), ElementError, "mass must be > 0");
  Eigen::Matrix3d asym = inertia();
  asym(0, 1) += 0.1;
  EXPECT_THROW_MSG(attached_mass(p, 1.0, e, asym), ElementError, "inertia must be symmetric");
  EXPECT_THROW_MSG(attached_mass(p, 1.0, e, Eigen::Matrix3d(Eigen::Vector3d(1, 1, 3).asDiagonal())), ElementError,
                   "triangle inequalities");
  EXPECT_THROW_MSG(attached_mass(p, 1.0, e, Eigen::Matrix3d(Eigen::Vector3d(-1, 1, 1).asDiagonal())), ElementError,
                   "not that of a physical body");
  EXPECT_THROW_MSG(attached_mass(p, 1.0, Eigen::Vector3d(std::nan(""), 0, 0), inertia()), ElementError, "NaN");
}
