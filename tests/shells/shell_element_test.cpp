// Single-element checks of the shell kernels: symmetry, exactly six rigid-body modes (also for
// a warped quad, through the rigid links), no spurious zero-energy modes, a definite mass, mass
// samples that reproduce M, M checked against an independent high-order quadrature, and the
// input errors.

#include "ffr/preproc/elements/shell.hpp"

#include "test_util.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>

using namespace ffr::preproc;
using ffr::test::rigid_modes;

namespace {

ShellSection steel(double t) { return {t, {2.1e11, 0.3, 7850}}; }

Eigen::MatrixX3d rotate(const Eigen::MatrixX3d& x) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
                             Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  return ((x * R.transpose()).rowwise() + Eigen::RowVector3d(0.3, -1.2, 2.0)).eval();
}

Eigen::MatrixX3d quad_flat() {
  Eigen::MatrixX3d x(4, 3);
  x << 0, 0, 0, 1.1, 0.1, 0, 1.3, 0.9, 0, 0.2, 0.7, 0;  // a general convex quad
  return rotate(x);
}

Eigen::MatrixX3d quad_warped() {
  Eigen::MatrixX3d x(4, 3);
  x << 0, 0, 0.05, 1.1, 0.1, -0.05, 1.3, 0.9, 0.05, 0.2, 0.7, -0.05;
  return rotate(x);
}

Eigen::MatrixX3d tri() {
  Eigen::MatrixX3d x(3, 3);
  x << 0, 0, 0, 1.2, 0.2, 0, 0.3, 0.9, 0;
  return rotate(x);
}

void check_rigid_and_rank(ElementType type, const Eigen::MatrixX3d& x) {
  const ElementMatrices em = shell_element(type, x, steel(0.05));
  const int n = static_cast<int>(em.K.rows());
  EXPECT_EQ(em.dofs_per_node, 6);
  EXPECT_LT((em.K - em.K.transpose()).norm(), 1e-12 * em.K.norm());
  const Eigen::MatrixXd R = rigid_modes(x);
  // K r = 0 for every rigid motion, to round-off.
  EXPECT_LT((em.K * R).norm(), 1e-12 * em.K.norm() * R.norm()) << name(type);
  // Exactly six zero eigenvalues: no spurious zero-energy (hourglass, drilling) modes.
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(em.K).eigenvalues();
  const double kmax = ev.maxCoeff();
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev(i)), 1e-11 * kmax) << name(type) << " eigenvalue " << i;
  EXPECT_GT(ev(6), 1e-8 * kmax) << name(type) << ": spurious zero-energy mode";
  EXPECT_EQ(n, 6 * x.rows());
}

}  // namespace

TEST(ShellElement, Quad4RigidModesAndRank) { check_rigid_and_rank(ElementType::Quad4, quad_flat()); }
TEST(ShellElement, WarpedQuad4RigidModesAndRank) { check_rigid_and_rank(ElementType::Quad4, quad_warped()); }
TEST(ShellElement, Tri3RigidModesAndRank) { check_rigid_and_rank(ElementType::Tri3, tri()); }

TEST(ShellElement, MassSamplesReproduceMAndMIsDefinite) {
  for (auto [type, x] : {std::pair{ElementType::Quad4, quad_warped()}, std::pair{ElementType::Tri3, tri()}}) {
    const ElementMatrices em = shell_element(type, x, steel(0.05));
    Eigen::MatrixXd S = em.M_rotary;
    for (const auto& s : em.samples) S += s.w * s.N.transpose() * s.N;
    EXPECT_LT((S - em.M).norm(), 1e-13 * em.M.norm());
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(em.M).eigenvalues();
    EXPECT_GT(ev.minCoeff(), 0.0) << name(type) << ": M must be positive definite";
    // M_rotary holds only the drilling inertia: zero for rotations about in-plane axes.
    EXPECT_GT(em.M_rotary.norm(), 0.0);
  }
}

// Independent oracle: integrate rho (N^T N) over the flat trapezoid's volume with 5 x 5 x 3
// Gauss points, N written out here from the kinematics u = sum N_i (u_i + theta_i x z n).
TEST(ShellElement, QuadMassMatchesIndependentQuadrature) {
  const Eigen::MatrixX3d x = quad_flat();
  const double t = 0.05, rho = 7850;
  const ElementMatrices em = shell_element(ElementType::Quad4, x, steel(t));
  const Eigen::Vector3d n = (x.row(2) - x.row(0)).cross(x.row(3) - x.row(1)).normalized();
  const double g5[5] = {-0.906179845938664, -0.538469310105683, 0, 0.538469310105683, 0.906179845938664};
  const double w5[5] = {0.236926885056189, 0.478628670499366, 0.568888888888889, 0.478628670499366,
                        0.236926885056189};
  const double g3[3] = {-0.774596669241483, 0, 0.774596669241483}, w3[3] = {5. / 9, 8. / 9, 5. / 9};
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(24, 24);
  double mass = 0;
  for (int a = 0; a < 5; ++a)
    for (int b = 0; b < 5; ++b)
      for (int c = 0; c < 3; ++c) {
        const double xi = g5[a], eta = g5[b], z = 0.5 * t * g3[c];
        Eigen::Vector3d dxi = Eigen::Vector3d::Zero(), deta = Eigen::Vector3d::Zero();
        double N[4];
        for (int i = 0; i < 4; ++i) {
          N[i] = 0.25 * (1 + sx[i] * xi) * (1 + sy[i] * eta);
          dxi += 0.25 * sx[i] * (1 + sy[i] * eta) * x.row(i).transpose();
          deta += 0.25 * sy[i] * (1 + sx[i] * xi) * x.row(i).transpose();
        }
        const double dV = dxi.cross(deta).norm() * w5[a] * w5[b] * 0.5 * t * w3[c];
        Eigen::MatrixXd Nm = Eigen::MatrixXd::Zero(3, 24);
        for (int i = 0; i < 4; ++i) {
          Nm.block<3, 3>(0, 6 * i).setIdentity();
          Nm.block<3, 3>(0, 6 * i) *= N[i];
          for (int k = 0; k < 3; ++k)  // theta_k e_k x (z n)
            Nm.block<3, 1>(0, 6 * i + 3 + k) = N[i] * Eigen::Vector3d::Unit(k).cross(z * n);
        }
        M += rho * dV * Nm.transpose() * Nm;
        mass += rho * dV;
      }
  EXPECT_LT((em.M - em.M_rotary - M).norm(), 1e-12 * M.norm());
  double w = 0;
  for (const auto& s : em.samples) w += s.w;
  EXPECT_NEAR(w, mass, 1e-12 * mass);
}

TEST(ShellElement, RefusesBadInput) {
  Eigen::MatrixX3d q = quad_flat();
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, q, steel(0)), ElementError, "thickness must be > 0");
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, q, steel(-1e-3)), ElementError, "thickness must be > 0");
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, q, ShellSection{0.01, {2e11, 0.5, 7800}}), ElementError,
                   "nu must lie in (-1, 0.5)");
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, q, ShellSection{0.01, {0, 0.3, 7800}}), ElementError,
                   "E must be > 0");
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, q, ShellSection{0.01, {2e11, 0.3, -1}}), ElementError,
                   "rho must be >= 0");
  Eigen::MatrixX3d coincident = q;
  coincident.row(3) = coincident.row(2);
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, coincident, steel(0.01)), ElementError, "degenerate");
  Eigen::MatrixX3d collinear(4, 3);
  collinear << 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0;
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, collinear, steel(0.01)), ElementError, "degenerate");
  Eigen::MatrixX3d reentrant(4, 3);
  reentrant << 0, 0, 0, 2, 0, 0, 0.5, 0.5, 0, 0, 2, 0;
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, reentrant, steel(0.01)), ElementError, "non-convex");
  Eigen::MatrixX3d folded(4, 3);
  folded << 0, 0, 0, 1, 0, 0, 1, 1, 1.2, 0, 1, -1.2;
  EXPECT_THROW_MSG(shell_element(ElementType::Quad4, folded, steel(0.01)), ElementError, "too warped");
  EXPECT_THROW_MSG(shell_element(ElementType::Quad8, Eigen::MatrixX3d::Zero(8, 3), steel(0.01)), ElementError,
                   "second-order shell elements are not supported");
  EXPECT_THROW_MSG(shell_element(ElementType::Tet4, Eigen::MatrixX3d::Zero(4, 3), steel(0.01)), ElementError,
                   "not a shell element type");
  EXPECT_THROW_MSG(shell_element(ElementType::Tri3, q, steel(0.01)), ElementError, "expected 3 node rows");
  Eigen::MatrixX3d line(3, 3);
  line << 0, 0, 0, 1, 1, 1, 2, 2, 2;
  EXPECT_THROW_MSG(shell_element(ElementType::Tri3, line, steel(0.01)), ElementError, "zero area");
}
