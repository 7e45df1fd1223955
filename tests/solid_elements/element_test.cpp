// Single-element properties for every solid type: rigid-body null space (exactly six zero
// modes), symmetry, and mass exactness. The mass reference is independent of the element
// code: the volume and first/second moments of the element's polyhedron (planar faces, from a
// projective map of the reference shape) by tetrahedral decomposition.
#include "support.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <random>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {
const Material kSteel{210e9, 0.3, 7850};

// Straight-sided element with randomly moved corners (non-planar faces allowed).
Eigen::MatrixX3d distorted(ElementType t, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-0.15, 0.15);
  Eigen::MatrixX3d c = reference_corners(t);
  for (int i = 0; i < c.rows(); ++i)
    for (int j = 0; j < 3; ++j) c(i, j) += U(rng);
  return straight_element(t, c);
}

// Rigid-body motions of the nodes: 3 translations and 3 rotations about the origin.
Eigen::MatrixXd rigid_modes(const Eigen::MatrixX3d& xe) {
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * xe.rows(), 6);
  for (int a = 0; a < xe.rows(); ++a)
    for (int k = 0; k < 3; ++k) {
      R(3 * a + k, k) = 1;
      R.block<3, 1>(3 * a, 3 + k) = Eigen::Vector3d::Unit(k).cross(xe.row(a).transpose());
    }
  return R;
}
}  // namespace

TEST(SolidElement, ExactlySixZeroEnergyModes) {
  for (ElementType t : all_solid_types())
    for (bool incompatible : {true, false}) {
      if (!incompatible && t != ElementType::Hex8) continue;
      const Eigen::MatrixX3d xe = distorted(t, 7);
      const ElementMatrices em = solid_element(t, xe, kSteel, {incompatible, true});
      const Eigen::MatrixXd& K = em.K;
      EXPECT_LT((K - K.transpose()).norm(), 1e-14 * K.norm()) << name(t);
      EXPECT_LT((K * rigid_modes(xe)).norm(), 1e-10 * K.norm()) << name(t);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
      const Eigen::VectorXd ev = es.eigenvalues();
      const double emax = ev.maxCoeff();
      int zeros = 0;
      for (int i = 0; i < ev.size(); ++i) zeros += std::abs(ev[i]) < 1e-10 * emax;
      EXPECT_EQ(zeros, 6) << name(t);
      // The smallest deformation mode is well separated from round-off (no spurious mode).
      EXPECT_GT(ev[6], 1e-4 * emax) << name(t);
      EXPECT_GT(ev.minCoeff(), -1e-10 * emax) << name(t);
    }
}

TEST(SolidElement, MassSamplesReproducePolyhedronMoments) {
  for (ElementType t : all_solid_types()) {
    const Eigen::MatrixX3d corners = projective_corners(t);
    const Eigen::MatrixX3d xe = straight_element(t, corners);
    const Moments ref = polyhedron_moments(corners, corner_faces(t));
    const double rho = kSteel.rho;
    const ElementMatrices em = solid_element(t, xe, kSteel);
    double m = 0;
    Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
    Eigen::Matrix3d s2 = Eigen::Matrix3d::Zero();
    Eigen::MatrixXd Ms = Eigen::MatrixXd::Zero(em.M.rows(), em.M.cols());
    for (const MassSample& s : em.samples) {
      EXPECT_GT(s.w, 0);
      m += s.w;
      s1 += s.w * s.c;
      s2 += s.w * s.c * s.c.transpose();
      Ms += s.w * s.N.transpose() * s.N;
      // N maps the nodal coordinates to the sample position (u = N d_e for d_e = x).
      Eigen::VectorXd xflat(3 * xe.rows());
      for (int a = 0; a < xe.rows(); ++a) xflat.segment<3>(3 * a) = xe.row(a).transpose();
      EXPECT_LT((s.N * xflat - s.c).norm(), 1e-13) << name(t);
    }
    EXPECT_NEAR(m, rho * ref.V, 1e-12 * rho * ref.V) << name(t);
    EXPECT_LT((s1 - rho * ref.S1).norm(), 1e-12 * rho * ref.S1.norm()) << name(t);
    EXPECT_LT((s2 - rho * ref.S2).norm(), 1e-12 * rho * ref.S2.norm()) << name(t);
    EXPECT_EQ(em.M_rotary.size(), 0);
    EXPECT_LT((Ms - em.M).norm(), 1e-14 * em.M.norm()) << name(t);
    // The consistent M itself carries the rigid-body inertia: R^T M R = [[m I, -m c~], [., J]].
    const Eigen::MatrixXd R = rigid_modes(xe);
    const Eigen::MatrixXd RMR = R.transpose() * em.M * R;
    EXPECT_NEAR(RMR(0, 0), rho * ref.V, 1e-12 * rho * ref.V);
    const Eigen::Matrix3d J = rho * (ref.S2.trace() * Eigen::Matrix3d::Identity() - ref.S2);
    EXPECT_LT((RMR.bottomRightCorner<3, 3>() - J).norm(), 1e-12 * J.norm()) << name(t);
    const Eigen::Vector3d S1 = rho * ref.S1;
    EXPECT_NEAR(RMR(0, 4), S1.z(), 1e-12 * S1.norm());  // e_x . (e_y x int c dm) = int c_z dm
    // Positive-definite consistent mass.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(em.M);
    EXPECT_GT(es.eigenvalues().minCoeff(), 0) << name(t);
  }
}

TEST(SolidElement, NoSamplesOption) {
  const Eigen::MatrixX3d xe = straight_element(ElementType::Hex20, projective_corners(ElementType::Hex20));
  const ElementMatrices a = solid_element(ElementType::Hex20, xe, kSteel);
  const ElementMatrices b = solid_element(ElementType::Hex20, xe, kSteel, {true, false});
  EXPECT_TRUE(b.samples.empty());
  EXPECT_EQ((a.M - b.M).norm(), 0.0);
  EXPECT_EQ((a.K - b.K).norm(), 0.0);
}

TEST(SolidQuality, IdealShapesScoreOneAndDistortionLowersIt) {
  // Ideal: unit cube, regular tet, equilateral prism, pyramid with equilateral side triangles.
  const double s3 = std::sqrt(3.0), s2 = std::sqrt(2.0);
  Eigen::MatrixX3d tet(4, 3), wedge(6, 3), pyr(5, 3);
  tet << 0, 0, 0, 1, 0, 0, 0.5, s3 / 2, 0, 0.5, s3 / 6, std::sqrt(2.0 / 3.0);
  wedge << 0, 0, 0, 1, 0, 0, 0.5, s3 / 2, 0, 0, 0, 1, 1, 0, 1, 0.5, s3 / 2, 1;
  pyr << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1 / s2;
  const Eigen::MatrixX3d hex = straight_element(ElementType::Hex8, 0.5 * (reference_corners(ElementType::Hex8).array() + 1).matrix());
  const std::pair<ElementType, Eigen::MatrixX3d> ideal[] = {
      {ElementType::Tet4, tet}, {ElementType::Wedge6, wedge}, {ElementType::Pyramid5, pyr}, {ElementType::Hex8, hex}};
  for (const auto& [t, xe] : ideal) {
    const SolidQuality q = solid_quality(t, xe);
    EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-12) << name(t);
    if (t != ElementType::Pyramid5) {
      EXPECT_NEAR(q.jacobian_ratio, 1.0, 1e-12) << name(t);
    }
    EXPECT_GT(q.min_det_j, 0);
  }
  // A projectively distorted hex is valid but worse; the same one inverted reports <= 0.
  const Eigen::MatrixX3d d = straight_element(ElementType::Hex20, projective_corners(ElementType::Hex20));
  const SolidQuality q = solid_quality(ElementType::Hex20, d);
  EXPECT_GT(q.jacobian_ratio, 0);
  EXPECT_LT(q.jacobian_ratio, 0.99);
  EXPECT_LT(q.min_scaled_jacobian, 0.99);
  Eigen::MatrixX3d flipped = d;
  flipped.col(2) *= -1;  // mirror image: every Jacobian negative
  EXPECT_LT(solid_quality(ElementType::Hex20, flipped).min_scaled_jacobian, 0);
  EXPECT_LT(solid_quality(ElementType::Hex20, flipped).max_det_j, 0);
}

TEST(SolidElement, ClosedFormConsistentMass) {
  // Textbook consistent masses (Zienkiewicz & Taylor, The Finite Element Method, vol. 1):
  // TET4: M_ab = rho V (1 + delta_ab) / 20; rectangular HEX8: M_ab = rho V / 64 prod_k (1 + xi_ak xi_bk / 3).
  const double rho = 3.0;
  Eigen::MatrixX3d tet(4, 3);
  tet << 0.1, 0.2, 0.0, 1.3, 0.1, 0.2, 0.4, 0.9, 0.1, 0.3, 0.4, 1.1;
  const double Vt = polyhedron_moments(tet, corner_faces(ElementType::Tet4)).V;
  const Eigen::MatrixXd Mt = solid_element(ElementType::Tet4, tet, {1, 0.3, rho}).M;
  Eigen::MatrixX3d box = reference_corners(ElementType::Hex8);
  const Eigen::Vector3d size(2.0, 0.5, 1.5);
  for (int a = 0; a < 8; ++a) box.row(a) = 0.5 * box.row(a).cwiseProduct(size.transpose());
  const Eigen::MatrixXd Mh = solid_element(ElementType::Hex8, box, {1, 0.3, rho}).M;
  const Eigen::MatrixX3d ref = reference_corners(ElementType::Hex8);
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          double h = i == j ? rho * size.prod() / 64 : 0.0;
          for (int k = 0; k < 3; ++k) h *= 1 + ref(a, k) * ref(b, k) / 3;
          EXPECT_NEAR(Mh(3 * a + i, 3 * b + j), h, 1e-14 * rho * size.prod());
          if (a < 4 && b < 4) {
            EXPECT_NEAR(Mt(3 * a + i, 3 * b + j), i == j ? rho * Vt * (1 + (a == b)) / 20 : 0.0, 1e-14 * rho * Vt);
          }
        }
}
