// Geometric (initial-stress) stiffness K_G.
//  - symmetric, and for a uniform stress sigma and any linear displacement field u = H x
//    the energy d^T K_G d = int sigma_ij u_k,i u_k,j dV = V tr(H sigma H^T) exactly; for a rigid
//    rotation u = w x x this is V (|w|^2 tr sigma - w^T sigma w), for a translation 0
//    (V from the polyhedron oracle of support.hpp).
//  - Euler buckling of a clamped-free column: the smallest lambda of (K + lambda K_G) x = 0
//    matches P_cr = pi^2 E I / (2L)^2 (Timoshenko & Gere, Theory of Elastic Stability, 2nd ed.
//    1961, sec. 2.1) with Engesser's shear correction P = P_e / (1 + P_e / (kappa G A)) (ibid.
//    sec. 2.18), kappa from Cowper (1966).
#include "support.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {
const Material kMat{2.0e5, 0.3, 1.0};

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}
Eigen::VectorXd linear_field(const Eigen::MatrixX3d& xe, const Eigen::Matrix3d& H, const Eigen::Vector3d& b) {
  Eigen::VectorXd d(3 * xe.rows());
  for (int a = 0; a < xe.rows(); ++a) d.segment<3>(3 * a) = H * xe.row(a).transpose() + b;
  return d;
}
}  // namespace

TEST(GeometricStiffness, UniformStressEnergyOfLinearFields) {
  Eigen::Matrix3d S;
  S << 3.0, -1.0, 0.5, -1.0, -2.0, 0.7, 0.5, 0.7, 1.5;
  Eigen::Matrix<double, 6, 1> sv;
  sv << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
  const Eigen::Vector3d w(0.3, -0.5, 0.8);
  Eigen::Matrix3d H;
  H << 0.2, -0.1, 0.4, 0.3, 0.1, -0.2, -0.5, 0.25, 0.15;
  for (ElementType t : all_solid_types()) {
    const Eigen::MatrixX3d corners = projective_corners(t);
    const Eigen::MatrixX3d xe = straight_element(t, corners);
    const double V = polyhedron_moments(corners, corner_faces(t)).V;
    const int ng = solid_shape(t).stiffness_rule.size();
    const Eigen::MatrixXd KG = solid_geometric_stiffness(t, xe, sv.replicate(1, ng));
    const double scale = V * S.norm();
    EXPECT_LT((KG - KG.transpose()).norm(), 1e-14 * KG.norm()) << name(t);
    const Eigen::VectorXd dt = linear_field(xe, Eigen::Matrix3d::Zero(), {1.0, -2.0, 0.5});
    EXPECT_NEAR(dt.dot(KG * dt), 0.0, 1e-12 * scale) << name(t);
    const Eigen::VectorXd dr = linear_field(xe, skew(w), {0.1, 0.2, 0.3});
    const double rot = V * (w.squaredNorm() * S.trace() - w.dot(S * w));
    EXPECT_NEAR(dr.dot(KG * dr), rot, 1e-12 * scale) << name(t);
    const Eigen::VectorXd dh = linear_field(xe, H, Eigen::Vector3d::Zero());
    EXPECT_NEAR(dh.dot(KG * dh), V * (H * S * H.transpose()).trace(), 1e-12 * scale) << name(t);
  }
}

TEST(GeometricStiffness, FromDisplacementMatchesFromStress) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1e-3, 1e-3);
  for (ElementType t : all_solid_types()) {
    const Eigen::MatrixX3d xe = straight_element(t, projective_corners(t));
    Eigen::VectorXd d(3 * xe.rows());
    for (int i = 0; i < d.size(); ++i) d[i] = U(rng);
    const Eigen::MatrixXd a = solid_geometric_stiffness(t, xe, kMat, d);
    const Eigen::MatrixXd b = solid_geometric_stiffness(t, xe, solid_stress(t, xe, kMat, d).sigma);
    EXPECT_EQ((a - b).norm(), 0.0) << name(t);
    EXPECT_LT((a - a.transpose()).norm(), 1e-14 * a.norm()) << name(t);
  }
}

namespace {
// Clamped at x = 0, unit compressive resultant on the face x = L; returns the smallest
// buckling factor of (K + lambda K_G) x = 0.
double buckling_load(ElementType t, int nx, int nyz, double L, double h) {
  const Patch p = make_box(t, nx, nyz, nyz, {L, h, h});
  const Eigen::VectorXd f = face_loads(p, 0, L, 1.0, [&](const Eigen::Vector3d&, const Eigen::Vector3d&) {
    return Eigen::Vector3d(-1.0 / (h * h), 0, 0);
  });
  std::map<int, double> fixed;
  std::vector<int> free;
  for (std::size_t n = 0; n < p.x.size(); ++n)
    for (int i = 0; i < 3; ++i) {
      if (std::abs(p.x[n].x()) < 1e-12) fixed[3 * static_cast<int>(n) + i] = 0;
      else free.push_back(3 * static_cast<int>(n) + i);
    }
  const Sparse K = assemble_stiffness(p, kMat);
  const Eigen::VectorXd d = solve_dirichlet(K, f, fixed);
  const Eigen::MatrixXd Kd(K), KGd(assemble_geometric(p, kMat, d));
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd Kf(nf, nf), Gf(nf, nf);
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < nf; ++j) {
      Kf(i, j) = Kd(free[i], free[j]);
      Gf(i, j) = KGd(free[i], free[j]);
    }
  // K x = -lambda K_G x  <=>  L^-1 K_G L^-T y = mu y with mu = -1/lambda; buckling: mu < 0.
  Eigen::LLT<Eigen::MatrixXd> llt(Kf);
  Eigen::MatrixXd C = llt.matrixL().solve(Gf);
  C = llt.matrixL().solve(C.transpose()).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (C + C.transpose()), Eigen::EigenvaluesOnly);
  return -1.0 / es.eigenvalues().minCoeff();
}

double euler_engesser(double L, double h) {
  const double I = h * h * h * h / 12, A = h * h, G = kMat.E / (2 * (1 + kMat.nu));
  const double kappa = 10 * (1 + kMat.nu) / (12 + 11 * kMat.nu);
  const double Pe = M_PI * M_PI * kMat.E * I / (4 * L * L);
  return Pe / (1 + Pe / (kappa * G * A));
}
}  // namespace

TEST(GeometricStiffness, EulerBucklingClampedFreeHex20) {
  const double L = 20, h = 1, ref = euler_engesser(L, h);
  const double P = buckling_load(ElementType::Hex20, 10, 1, L, h);
  std::cout << "[ HEX20 ] P_cr / reference = " << P / ref << "\n";
  EXPECT_NEAR(P / ref, 1.0, 0.02);
}

TEST(GeometricStiffness, EulerBucklingClampedFreeTet10) {
  const double L = 20, h = 1, ref = euler_engesser(L, h);
  const double P = buckling_load(ElementType::Tet10, 20, 1, L, h);
  std::cout << "[ TET10 ] P_cr / reference = " << P / ref << "\n";
  EXPECT_NEAR(P / ref, 1.0, 0.02);
}
