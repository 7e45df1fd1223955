// Patch tests (MacNeal & Harder, Finite Elem. Anal. Des. 1 (1985) 3–20, the distorted 5-element
// patch 0.24 x 0.12, E = 1e6, nu = 0.25, t = 0.001): the exact field is imposed on the four
// boundary nodes and the interior nodes must reproduce it to round-off; the resultants must be
// the exact constant ones. Membrane, bending, and a membrane field with a non-zero rotation
// (drilling), for QUAD4 and for the same patch split into TRI3; all in a plane tilted in 3D.
// Also in-plane pure bending on a rectangular mesh of aspect ratio 3 (exact for the
// incompatible-mode quad, and the optimality property of Felippa's OPT triangle).

#include "ffr/preproc/elements/shell.hpp"

#include "fe_driver.hpp"
#include "test_util.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <functional>

using namespace ffr::preproc;
using ffr::test::Assembler;

namespace {

using Field = std::function<Eigen::Matrix<double, 6, 1>(double x, double y)>;  // local (u,v,w,rx,ry,rz)

struct Patch {
  Eigen::MatrixX3d x2d;  // in-plane coordinates (z = 0)
  std::vector<std::vector<int>> elems;
  ElementType type;
  std::vector<int> boundary;
};

Patch macneal_patch(bool triangles) {
  Patch p;
  p.x2d.resize(8, 3);
  p.x2d << 0, 0, 0, 0.24, 0, 0, 0.24, 0.12, 0, 0, 0.12, 0, 0.04, 0.02, 0, 0.18, 0.03, 0, 0.16, 0.08, 0, 0.08, 0.08, 0;
  const std::vector<std::vector<int>> quads = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
  p.boundary = {0, 1, 2, 3};
  if (!triangles) {
    p.elems = quads;
    p.type = ElementType::Quad4;
  } else {
    for (const auto& q : quads) {
      p.elems.push_back({q[0], q[1], q[2]});
      p.elems.push_back({q[0], q[2], q[3]});
    }
    p.type = ElementType::Tri3;
  }
  return p;
}

/// nx x ny rectangles of size a x b (optionally split into triangles); boundary = outer nodes.
Patch rect_patch(int nx, int ny, double a, double b, bool triangles) {
  Patch p;
  auto g = ffr::test::make_grid(nx, ny, [&](double u, double v) { return Eigen::Vector3d(u * nx * a, v * ny * b, 0); });
  p.x2d = g.x;
  p.elems = triangles ? g.triangles() : g.quads();
  p.type = triangles ? ElementType::Tri3 : ElementType::Quad4;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      if (i == 0 || j == 0 || i == nx || j == ny) p.boundary.push_back(g.node(i, j));
  return p;
}

const Eigen::Matrix3d kTilt =
    (Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, -2, 0.5).normalized()) * Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()))
        .toRotationMatrix();
const Eigen::Vector3d kShift(1.0, -2.0, 0.5);

/// Imposes `exact` (given in the patch plane) on the boundary of the tilted patch, solves, and
/// returns the largest interior DOF error relative to the largest exact DOF, and the resultants.
double solve_patch(const Patch& p, const ShellSection& s, const Field& exact, std::vector<ShellResultants>* res) {
  const int nn = static_cast<int>(p.x2d.rows());
  Eigen::MatrixX3d x(nn, 3);
  for (int i = 0; i < nn; ++i) x.row(i) = (kTilt * p.x2d.row(i).transpose() + kShift).transpose();
  Eigen::VectorXd ue(6 * nn);
  for (int i = 0; i < nn; ++i) {
    const auto f = exact(p.x2d(i, 0), p.x2d(i, 1));
    ue.segment<3>(6 * i) = kTilt * f.head<3>();
    ue.segment<3>(6 * i + 3) = kTilt * f.tail<3>();
  }
  Assembler as(nn);
  std::vector<Eigen::MatrixX3d> coords;
  for (const auto& e : p.elems) {
    Eigen::MatrixX3d xe(e.size(), 3);
    for (std::size_t k = 0; k < e.size(); ++k) xe.row(k) = x.row(e[k]);
    as.add(e, shell_element(p.type, xe, s));
    coords.push_back(xe);
  }
  std::vector<bool> fixed(6 * nn, false);
  for (int b : p.boundary)
    for (int k = 0; k < 6; ++k) fixed[6 * b + k] = true;
  // Move the prescribed values to the right-hand side: K_ff u_f = -K_fb u_b.
  Eigen::VectorXd ub = Eigen::VectorXd::Zero(6 * nn);
  for (int i = 0; i < 6 * nn; ++i)
    if (fixed[i]) ub(i) = ue(i);
  const ffr::test::SpMat K = as.K();
  Eigen::VectorXd u = ffr::test::solve_static(K, -(K * ub), fixed) + ub;
  if (res) {
    res->clear();
    for (std::size_t e = 0; e < p.elems.size(); ++e) {
      Eigen::VectorXd de(6 * p.elems[e].size());
      for (std::size_t k = 0; k < p.elems[e].size(); ++k) de.segment<6>(6 * k) = u.segment<6>(6 * p.elems[e][k]);
      res->push_back(shell_resultants(p.type, coords[e], s, de));
    }
  }
  return (u - ue).cwiseAbs().maxCoeff() / ue.cwiseAbs().maxCoeff();
}

const ShellSection kMH{0.001, {1e6, 0.25, 1}};

Eigen::Matrix3d plane_stress(const Material& m) {
  Eigen::Matrix3d D;
  D << 1, m.nu, 0, m.nu, 1, 0, 0, 0, 0.5 * (1 - m.nu);
  return D * m.E / (1 - m.nu * m.nu);
}

// The local frame of a patch element may be rotated in-plane against the patch axes; express a
// patch-plane tensor (xx, yy, xy) in the element axes through the element's R.
Eigen::Vector3d to_element_axes(const Eigen::Vector3d& v, const Eigen::Matrix3d& R_elem) {
  const Eigen::Matrix3d Q = R_elem * kTilt;  // patch axes -> element axes
  Eigen::Matrix2d S;
  S << v(0), v(2), v(2), v(1);
  const Eigen::Matrix2d Sl = Q.topLeftCorner<2, 2>() * S * Q.topLeftCorner<2, 2>().transpose();
  return {Sl(0, 0), Sl(1, 1), Sl(0, 1)};
}

}  // namespace

class PatchTest : public ::testing::TestWithParam<bool> {};  // false: QUAD4, true: TRI3

TEST_P(PatchTest, Membrane) {
  const Patch p = macneal_patch(GetParam());
  const Field f = [](double x, double y) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d(0) = 1e-3 * (x + y / 2);
    d(1) = 1e-3 * (y + x / 2);
    return d;  // rotation (v,x - u,y)/2 = 0
  };
  std::vector<ShellResultants> res;
  EXPECT_LT(solve_patch(p, kMH, f, &res), 1e-10);
  // MacNeal–Harder: sigma_x = sigma_y = 1333, tau_xy = 400 (times t for the forces).
  const Eigen::Vector3d N = kMH.thickness * plane_stress(kMH.material) * Eigen::Vector3d(1e-3, 1e-3, 1e-3);
  EXPECT_NEAR(N(0) / kMH.thickness, 1333.333, 1e-3);
  for (const auto& r : res)
    for (const auto& Ng : r.N) EXPECT_LT((Ng - to_element_axes(N, r.R)).norm(), 1e-9 * N.norm());
}

TEST_P(PatchTest, MembraneWithDrillingRotation) {
  const Patch p = macneal_patch(GetParam());
  const Field f = [](double x, double y) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d(0) = 1e-3 * (x + 0.3 * y);
    d(1) = 1e-3 * (-0.2 * x + 0.5 * y);
    d(5) = 0.5 * 1e-3 * (-0.2 - 0.3);  // rz = (v,x - u,y)/2
    return d;
  };
  EXPECT_LT(solve_patch(p, kMH, f, nullptr), 1e-10);
}

TEST_P(PatchTest, Bending) {
  const Patch p = macneal_patch(GetParam());
  const Field f = [](double x, double y) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d(2) = 1e-3 * (x * x + x * y + y * y) / 2;
    d(3) = 1e-3 * (y + x / 2);    // rx = w,y
    d(4) = -1e-3 * (x + y / 2);   // ry = -w,x
    return d;
  };
  std::vector<ShellResultants> res;
  EXPECT_LT(solve_patch(p, kMH, f, &res), 1e-10);
  // kappa = (beta_x,x, beta_y,y, beta_x,y + beta_y,x) with beta = -grad w.
  const double t = kMH.thickness;
  const Eigen::Vector3d M = t * t * t / 12 * plane_stress(kMH.material) * Eigen::Vector3d(-1e-3, -1e-3, -1e-3);
  for (const auto& r : res) {
    for (const auto& Mg : r.M) EXPECT_LT((Mg - to_element_axes(M, r.R)).norm(), 1e-9 * M.norm());
    for (const auto& Qg : r.Q) EXPECT_LT(Qg.norm(), 1e-9 * M.norm() / 0.01);
  }
}

INSTANTIATE_TEST_SUITE_P(Shells, PatchTest, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Tri3" : "Quad4"; });

TEST(PatchTest, Quad4InPlanePureBendingOnElongatedRectangles) {
  // Exact plane-stress pure bending: u = -k x y, v = k (x^2 + nu y^2)/2, rotation k x; the
  // incompatible modes and the drilling field represent it exactly on rectangles.
  const Patch p = rect_patch(4, 3, 0.3, 0.1, false);
  const double k = 1e-3, nu = kMH.material.nu;
  const Field f = [&](double x, double y) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d(0) = -k * x * y;
    d(1) = 0.5 * k * (x * x + nu * y * y);
    d(5) = k * x;
    return d;
  };
  EXPECT_LT(solve_patch(p, kMH, f, nullptr), 1e-9);
}

// Felippa (CMAME 192 (2003), section 5.1, "the bending test"): a rectangular mesh unit of two
// triangles under the exact pure-bending field stores exactly the exact strain energy, for
// every aspect ratio, either diagonal, bending about either axis and any nu (beta0 =
// (1 - 4 nu^2)/2). This is what makes OPT "optimal"; it checks the whole template (alpha_b,
// beta_1..9, beta0 and the scaling of the higher-order stiffness).
TEST(PatchTest, OptTriangleIsExactInPureBending) {
  for (double nu : {0.0, 0.25, 0.35})
    for (double a : {0.2, 1.0, 3.0, 10.0})
      for (int diag : {0, 1})
        for (int dir : {0, 1}) {
          const double b = 1.0, k = 1e-3;
          const ShellSection s{0.1, {1.0, nu, 1}};
          Eigen::MatrixX3d P(4, 3);
          P << -a / 2, -b / 2, 0, a / 2, -b / 2, 0, a / 2, b / 2, 0, -a / 2, b / 2, 0;
          const std::vector<std::vector<int>> tris = diag == 0 ? std::vector<std::vector<int>>{{0, 1, 2}, {0, 2, 3}}
                                                               : std::vector<std::vector<int>>{{0, 1, 3}, {1, 2, 3}};
          double U = 0;
          for (const auto& tr : tris) {
            Eigen::MatrixX3d xe(3, 3);
            Eigen::VectorXd d = Eigen::VectorXd::Zero(18);
            for (int i = 0; i < 3; ++i) {
              xe.row(i) = P.row(tr[i]);
              const double x = xe(i, 0), y = xe(i, 1);
              if (dir == 0) {  // sigma_xx = -E k y
                d(6 * i) = -k * x * y, d(6 * i + 1) = 0.5 * k * (x * x + nu * y * y), d(6 * i + 5) = k * x;
              } else {  // sigma_yy = -E k x
                d(6 * i + 1) = -k * x * y, d(6 * i) = 0.5 * k * (y * y + nu * x * x), d(6 * i + 5) = -k * y;
              }
            }
            U += 0.5 * d.dot(shell_element(ElementType::Tri3, xe, s).K * d);
          }
          const double exact = 0.5 * k * k * s.thickness * (dir == 0 ? a * b * b * b : b * a * a * a) / 12;
          EXPECT_NEAR(U / exact, 1.0, 1e-10) << "nu " << nu << " aspect " << a << " diag " << diag << " dir " << dir;
        }
}
