// Membrane resultants and the geometric stiffness of shells.
//  - A uniform stretch gives the exact constant membrane forces in every element.
//  - K_G is symmetric and does no work in rigid translations.
//  - A simply supported square plate under equal biaxial membrane force N (tension or
//    compression): the exact thin-plate result (e.g. Timoshenko & Gere, Theory of Elastic
//    Stability, plate with in-plane forces) is
//        rho t omega_mn^2 = D k^4 + N k^2,   k^2 = (m pi / a)^2 + (n pi / a)^2,
//    so the frequency shift rho t (omega^2(N) - omega^2(0)) = N k^2 tests K_G alone, and
//    omega -> 0 at the buckling force N = -D k^2.

#include "ffr/preproc/elements/shell.hpp"

#include "fe_driver.hpp"
#include "test_util.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

const ShellSection kSteel{0.01, {2.0e11, 0.3, 7800}};

/// Uniform stretch u = eps (x, y, 0) in the plate plane as element DOFs.
Eigen::VectorXd stretch(const Eigen::MatrixX3d& xe, double ex, double ey) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(6 * xe.rows());
  for (int i = 0; i < xe.rows(); ++i) {
    d(6 * i) = ex * xe(i, 0);
    d(6 * i + 1) = ey * xe(i, 1);
  }
  return d;
}

/// Lowest transverse frequencies^2 of the simply supported a x a plate prestressed by the
/// membrane forces of a uniform biaxial strain eps (in-plane DOFs held, so only w and the
/// bending rotations move).
Eigen::VectorXd prestressed_plate(ElementType type, int n, double eps, double* N_out) {
  const double a = 1.0;
  Grid g = make_grid(n, n, [&](double u, double v) { return Eigen::Vector3d(a * u, a * v, 0); });
  Assembler as(static_cast<int>(g.x.rows()));
  double N = 0;
  for (const auto& e : type == ElementType::Quad4 ? g.quads() : g.triangles()) {
    const Eigen::MatrixX3d xe = g.coords(e);
    const ElementMatrices em = shell_element(type, xe, kSteel);
    const ShellResultants r = shell_resultants(type, xe, kSteel, stretch(xe, eps, eps));
    N = r.N[0](0);
    as.add(e, em.K + shell_geometric_stiffness(type, xe, r), em.M);
  }
  std::vector<bool> fixed(as.size(), false);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const int p = g.node(i, j);
      for (int d : {0, 1, 5}) fixed[6 * p + d] = true;  // in-plane motion held
      if (i == 0 || j == 0 || i == n || j == n) fixed[6 * p + 2] = true;  // w = 0 on the edges
    }
  if (N_out) *N_out = N;
  return eigenvalues(as.K(), as.M(), fixed, 3, -1.0);
}

}  // namespace

class ShellGeometric : public ::testing::TestWithParam<ElementType> {};

TEST_P(ShellGeometric, UniformStretchGivesExactMembraneForces) {
  const ElementType type = GetParam();
  Eigen::MatrixX3d xe(num_nodes(type), 3);
  if (type == ElementType::Quad4)
    xe << 0, 0, 0, 1.1, 0.1, 0, 1.3, 0.9, 0, 0.2, 0.7, 0;
  else
    xe << 0, 0, 0, 1.2, 0.2, 0, 0.3, 0.9, 0;
  const double ex = 1e-4, ey = -3e-5, E = kSteel.material.E, nu = kSteel.material.nu, t = kSteel.thickness;
  const ShellResultants r = shell_resultants(type, xe, kSteel, stretch(xe, ex, ey));
  // Element axes: e1 is rotated against x by some angle c; rotate the exact tensor.
  const Eigen::Matrix2d Q = r.R.topLeftCorner<2, 2>();
  Eigen::Matrix2d S;
  S << E * t / (1 - nu * nu) * (ex + nu * ey), 0, 0, E * t / (1 - nu * nu) * (ey + nu * ex);
  const Eigen::Matrix2d Sl = Q * S * Q.transpose();
  double area = 0;
  for (std::size_t g = 0; g < r.N.size(); ++g) {
    EXPECT_LT((r.N[g] - Eigen::Vector3d(Sl(0, 0), Sl(1, 1), Sl(0, 1))).norm(), 1e-9 * S.norm());
    EXPECT_LT(r.M[g].norm(), 1e-9 * S.norm());
    area += r.area[g];
  }
  EXPECT_NEAR(area, type == ElementType::Quad4 ? 0.795 : 0.51, 1e-12);

  const Eigen::MatrixXd KG = shell_geometric_stiffness(type, xe, kSteel, stretch(xe, ex, ey));
  EXPECT_LT((KG - KG.transpose()).norm(), 1e-12 * KG.norm());
  Eigen::MatrixXd T = rigid_modes(xe).leftCols(3);
  EXPECT_LT((KG * T).norm(), 1e-12 * KG.norm());
}

TEST_P(ShellGeometric, PrestressedSimplySupportedPlate) {
  const ElementType type = GetParam();
  const double t = kSteel.thickness, rho = kSteel.material.rho, a = 1.0;
  const double D = kSteel.material.E * t * t * t / (12 * (1 - 0.09));
  const double k2 = 2 * kPi * kPi / (a * a);  // mode (1,1)
  double N = 0;
  const Eigen::VectorXd l0 = prestressed_plate(type, 24, 0.0, nullptr);
  const Eigen::VectorXd lt = prestressed_plate(type, 24, 2e-5, &N);
  EXPECT_NEAR(N, kSteel.material.E * t * 2e-5 / (1 - 0.3), 1e-6 * std::abs(N));
  std::printf("  %s 24x24: omega^2(0) / plate theory %.5f, tension shift / N k^2 %.5f\n", name(type),
              rho * t * l0(0) / (D * k2 * k2), rho * t * (lt(0) - l0(0)) / (N * k2));
  // Unstressed frequency against thin-plate theory, and the tension shift against N k^2.
  EXPECT_NEAR(rho * t * l0(0) / (D * k2 * k2), 1.0, 0.01);
  EXPECT_NEAR(rho * t * (lt(0) - l0(0)) / (N * k2), 1.0, 0.01);
  // At the buckling force N_cr = -D k^2 the (1,1) frequency vanishes (to discretisation error).
  const double eps_cr = -D * k2 * (1 - 0.3) / (kSteel.material.E * t);
  const Eigen::VectorXd lc = prestressed_plate(type, 24, eps_cr, nullptr);
  std::printf("  %s 24x24: omega^2 at the buckling force / omega^2(0) = %.5f\n", name(type), lc(0) / l0(0));
  EXPECT_LT(std::abs(lc(0)) / l0(0), 0.02);
}

INSTANTIATE_TEST_SUITE_P(Shells, ShellGeometric, ::testing::Values(ElementType::Quad4, ElementType::Tri3),
                         [](const auto& info) { return std::string(name(info.param)); });
