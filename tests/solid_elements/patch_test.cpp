// Patch tests (Irons; MacNeal & Harder 1985, "A proposed standard set of problems to test
// finite element accuracy", test 1) on distorted 3 x 3 x 3-cell patches of every type: a
// linear displacement field must be reproduced to round-off, both when the whole boundary
// is prescribed (displacement-driven) and when the patch is loaded only by the boundary
// tractions sigma0 n of the constant stress state (force-driven, surface loads integrated on
// the faces independently of the element's volume quadrature).
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {
const Material kMat{1000.0, 0.3, 1.0};
const Eigen::Vector3d kL(1.0, 1.2, 0.9);

Eigen::Matrix3d stress_of(const Eigen::Matrix3d& eps) {
  const double lam = kMat.E * kMat.nu / ((1 + kMat.nu) * (1 - 2 * kMat.nu)), mu = kMat.E / (2 * (1 + kMat.nu));
  return 2 * mu * eps + lam * eps.trace() * Eigen::Matrix3d::Identity();
}
bool on_boundary(const Eigen::Vector3d& x) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(x[k]) < 1e-12 || std::abs(x[k] - kL[k]) < 1e-12) return true;
  return false;
}
Eigen::VectorXd field(const Patch& p, const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
  Eigen::VectorXd u(p.ndof());
  for (std::size_t n = 0; n < p.x.size(); ++n) u.segment<3>(3 * n) = A * p.x[n] + b;
  return u;
}
int find_node(const Patch& p, const Eigen::Vector3d& x) {
  for (std::size_t n = 0; n < p.x.size(); ++n)
    if ((p.x[n] - x).norm() < 1e-12) return static_cast<int>(n);
  return -1;
}

class Patch3 : public ::testing::TestWithParam<ElementType> {};
}  // namespace

TEST_P(Patch3, DisplacementDriven) {
  const ElementType t = GetParam();
  const Patch p = make_box(t, 3, 3, 3, kL, 0.25, 11);
  Eigen::Matrix3d A;
  A << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 6e-4, 4e-4;  // includes a small rotation
  const Eigen::Vector3d b(1e-3, -2e-3, 5e-4);
  const Eigen::VectorXd exact = field(p, A, b);
  std::map<int, double> fixed;
  int interior = 0;
  for (std::size_t n = 0; n < p.x.size(); ++n) {
    if (!on_boundary(p.x[n])) { ++interior; continue; }
    for (int i = 0; i < 3; ++i) fixed[3 * static_cast<int>(n) + i] = exact[3 * n + i];
  }
  ASSERT_GT(interior, 0);
  const Eigen::VectorXd u = solve_dirichlet(assemble_stiffness(p, kMat), Eigen::VectorXd::Zero(p.ndof()), fixed);
  EXPECT_LT((u - exact).lpNorm<Eigen::Infinity>(), 1e-12) << name(t);
  // Stress at every integration point is the constant sigma0.
  const Eigen::Matrix3d S0 = stress_of(0.5 * (A + A.transpose()));
  for (std::size_t e = 0; e < p.elems.size(); ++e) {
    Eigen::VectorXd de(3 * p.elems[e].size());
    for (std::size_t a = 0; a < p.elems[e].size(); ++a) de.segment<3>(3 * a) = u.segment<3>(3 * p.elems[e][a]);
    const SolidStress s = solid_stress(t, p.coords(static_cast<int>(e)), kMat, de);
    for (int g = 0; g < s.sigma.cols(); ++g) {
      const Eigen::Matrix<double, 6, 1> s0 = (Eigen::Matrix<double, 6, 1>() << S0(0, 0), S0(1, 1), S0(2, 2),
                                              S0(0, 1), S0(1, 2), S0(0, 2)).finished();
      ASSERT_LT((s.sigma.col(g) - s0).norm(), 1e-9 * S0.norm()) << name(t) << " element " << e;
    }
  }
}

TEST_P(Patch3, ForceDriven) {
  const ElementType t = GetParam();
  const Patch p = make_box(t, 3, 3, 3, kL, 0.25, 12);
  Eigen::Matrix3d eps;
  eps << 1e-3, 3e-4, -2e-4, 3e-4, -5e-4, 4e-4, -2e-4, 4e-4, 8e-4;
  const Eigen::Matrix3d S0 = stress_of(eps);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(p.ndof());
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side)
      f += face_loads(p, k, side ? kL[k] : 0.0, side ? 1.0 : -1.0,
                      [&](const Eigen::Vector3d&, const Eigen::Vector3d& n) { return Eigen::Vector3d(S0 * n); });
  EXPECT_LT(std::abs(f.sum()), 1e-12 * f.norm());  // self-equilibrated loads
  const Eigen::VectorXd exact = field(p, eps, Eigen::Vector3d::Zero());
  // Six constraints against rigid motion, with the exact values.
  const int n0 = find_node(p, {0, 0, 0}), n1 = find_node(p, {kL.x(), 0, 0}), n2 = find_node(p, {0, kL.y(), 0});
  ASSERT_TRUE(n0 >= 0 && n1 >= 0 && n2 >= 0);
  std::map<int, double> fixed;
  for (int i = 0; i < 3; ++i) fixed[3 * n0 + i] = exact[3 * n0 + i];
  for (int i = 1; i < 3; ++i) fixed[3 * n1 + i] = exact[3 * n1 + i];
  fixed[3 * n2 + 2] = exact[3 * n2 + 2];
  const Eigen::VectorXd u = solve_dirichlet(assemble_stiffness(p, kMat), f, fixed);
  EXPECT_LT((u - exact).lpNorm<Eigen::Infinity>(), 1e-12) << name(t);
}

TEST(PatchPlainHex8, TrilinearAlsoPasses) {
  // The plain trilinear HEX8 (the locking reference of the bending test) is a valid element too.
  const Patch p = make_box(ElementType::Hex8, 3, 3, 3, kL, 0.25, 13);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity() * 1e-3;
  A(0, 1) = 4e-4;
  std::map<int, double> fixed;
  const Eigen::VectorXd exact = field(p, A, Eigen::Vector3d::Zero());
  for (std::size_t n = 0; n < p.x.size(); ++n)
    if (on_boundary(p.x[n]))
      for (int i = 0; i < 3; ++i) fixed[3 * static_cast<int>(n) + i] = exact[3 * n + i];
  const Eigen::VectorXd u =
      solve_dirichlet(assemble_stiffness(p, kMat, {false, false}), Eigen::VectorXd::Zero(p.ndof()), fixed);
  EXPECT_LT((u - exact).lpNorm<Eigen::Infinity>(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllSolids, Patch3, ::testing::ValuesIn(all_solid_types()),
                         [](const auto& info) { return std::string(name(info.param)); });
