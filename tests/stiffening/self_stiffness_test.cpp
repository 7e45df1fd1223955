// Ke.M1 (SPEC.md section 10.1) against an independent oracle written here: the St Venant-
// Kirchhoff strain energy of the same finite-element model at u = Phi q,
//   W(u) = int [lambda/2 (tr E)^2 + mu E:E] dV,  E = (H + H^T + H^T H)/2,  H = du/dX,
// with this file's own TET4/TET10 shape functions (barycentric, gmsh node order) and its own
// collapsed-Gauss quadrature. W(q) - W(-q) = 2 U3(q) exactly (U3 is the only odd part of the
// quartic W), so the reduced cubic energy 1/2 sum_k q_k q^T Ke.M1[k] q must equal
// (W(q) - W(-q))/2 to rounding, for free, clamped and Craig-Bampton bases (constraint modes
// included). The even part checks the oracle itself against 1/2 q^T Ke.M0 q.
#include "ffr/formats/h5.hpp"
#include "ffr/formats/validate.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/reduce/reduction.hpp"
#include "ffr/preproc/reduce/stiffening.hpp"
#include "../reduce/support.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <array>
#include <iostream>
#include <map>
#include <random>

using namespace ffr;
using preproc::Index;

namespace {

// A tetrahedral body made from test::HexGrid (an affine map of a unit grid, so every
// tetrahedron has straight edges): each hexahedron split into six tetrahedra about its 0-6
// diagonal, with midside nodes added at the edge midpoints for TET10. Groups and interfaces
// are HexGrid's (L rigid on the left face, R averaged on the right one).
struct TetBody {
  test::HexGrid grid;
  preproc::Mesh mesh;
  preproc::PartSpec part;
  int nodes_per_element;
  TetBody(int nx, int ny, int nz, bool quadratic) : grid(nx, ny, nz), part(grid.part), nodes_per_element(quadratic ? 10 : 4) {
    mesh = grid.mesh;
    const preproc::ElementBlock hex = mesh.blocks.front();
    preproc::ElementBlock tets{quadratic ? preproc::ElementType::Tet10 : preproc::ElementType::Tet4, "body", {}, {}};
    static const int split[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    std::vector<Eigen::RowVector3d> extra;
    std::map<std::pair<Index, Index>, Index> midside;
    auto mid = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      const auto it = midside.find(key);
      if (it != midside.end()) return it->second;
      const Index n = mesh.x.rows() + static_cast<Index>(extra.size());
      extra.push_back(0.5 * (mesh.x.row(a) + mesh.x.row(b)));
      midside[key] = n;
      return n;
    };
    for (Index e = 0; e < hex.size(); ++e) {
      const Index* h = hex.element(e);
      for (const auto& s : split) {
        std::array<Index, 4> v{h[s[0]], h[s[1]], h[s[2]], h[s[3]]};
        Eigen::Matrix3d J;
        for (int c = 0; c < 3; ++c) J.col(c) = (mesh.x.row(v[c + 1]) - mesh.x.row(v[0])).transpose();
        if (J.determinant() < 0) std::swap(v[1], v[2]);
        for (Index n : v) tets.conn.push_back(n);
        if (quadratic)  // gmsh TET10: edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1
          for (auto [a, b] : {std::pair{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}) tets.conn.push_back(mid(v[a], v[b]));
      }
    }
    const Index n0 = mesh.x.rows();
    mesh.x.conservativeResize(n0 + static_cast<Index>(extra.size()), 3);
    for (std::size_t i = 0; i < extra.size(); ++i) mesh.x.row(n0 + static_cast<Index>(i)) = extra[i];
    for (Index n = n0; n < mesh.x.rows(); ++n) mesh.node_groups["body"].push_back(n);
    mesh.blocks = {tets};
  }
};

// ---- the oracle ------------------------------------------------------------------------

// Barycentric L = (1 - xi - eta - zeta, xi, eta, zeta); gradients of the shape functions in
// (xi, eta, zeta), one row per node, in gmsh order (TET10 edge nodes as in TetBody).
Eigen::MatrixXd tet_gradients(int nn, const Eigen::Vector3d& xi) {
  const double L[4] = {1 - xi.sum(), xi.x(), xi.y(), xi.z()};
  Eigen::Matrix<double, 4, 3> dL;
  dL << -1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixXd G(nn, 3);
  if (nn == 4) return dL;
  for (int a = 0; a < 4; ++a) G.row(a) = (4 * L[a] - 1) * dL.row(a);
  static const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  for (int m = 0; m < 6; ++m) {
    const int a = edge[m][0], b = edge[m][1];
    G.row(4 + m) = 4 * (L[b] * dL.row(a) + L[a] * dL.row(b));
  }
  return G;
}

// Collapsed Gauss rule on the unit tetrahedron: xi = a(1-b)(1-c), eta = b(1-c), zeta = c with
// 4-point Gauss-Legendre on [0,1] in a, b, c; exact to degree 5 (the energy is quartic here).
struct Point {
  Eigen::Vector3d xi;
  double w;
};
std::vector<Point> tet_rule() {
  const double g[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  std::vector<Point> r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        const double a = (g[i] + 1) / 2, b = (g[j] + 1) / 2, c = (g[k] + 1) / 2;
        r.push_back({{a * (1 - b) * (1 - c), b * (1 - c), c}, gw[i] * gw[j] * gw[k] / 8 * (1 - b) * (1 - c) * (1 - c)});
      }
  return r;
}

// St Venant-Kirchhoff energy of the whole model at nodal displacements u (full DOFs).
double svk_energy(const preproc::FeModel& model, const TetBody& body, const Eigen::VectorXd& u) {
  const auto& mat = body.part.materials.front().mat;
  const double lambda = mat.E * mat.nu / ((1 + mat.nu) * (1 - 2 * mat.nu)), mu = mat.E / (2 * (1 + mat.nu));
  static const std::vector<Point> rule = tet_rule();
  const auto& blk = body.mesh.blocks.front();
  const int nn = body.nodes_per_element;
  double W = 0;
  for (Index e = 0; e < blk.size(); ++e) {
    const Index* n = blk.element(e);
    Eigen::MatrixXd X(nn, 3), U(nn, 3);
    for (int a = 0; a < nn; ++a) {
      X.row(a) = body.mesh.x.row(n[a]);
      for (int c = 0; c < 3; ++c) U(a, c) = u(model.dof(n[a], c));
    }
    for (const auto& p : rule) {
      const Eigen::MatrixXd dN = tet_gradients(nn, p.xi);
      const Eigen::Matrix3d J = X.transpose() * dN;  // dX/dxi
      const Eigen::Matrix3d H = U.transpose() * dN * J.inverse();
      const Eigen::Matrix3d E = 0.5 * (H + H.transpose() + H.transpose() * H);
      W += p.w * J.determinant() * (0.5 * lambda * E.trace() * E.trace() + mu * (E.array() * E.array()).sum());
    }
  }
  return W;
}

double cubic_form(const std::vector<Eigen::MatrixXd>& M1, const Eigen::VectorXd& q) {
  double s = 0;
  for (std::size_t k = 0; k < M1.size(); ++k) s += 0.5 * q(static_cast<Index>(k)) * q.dot(M1[k] * q);
  return s;
}

struct Case {
  const char* name;
  preproc::ReductionSpec spec;
};

void check_against_energy(const TetBody& body, const Case& c) {
  SCOPED_TRACE(c.name);
  const auto model = preproc::build_model(body.mesh, body.part);
  const preproc::Assembled fe = preproc::assemble(model);
  const auto red = preproc::reduce(model, fe, c.spec);
  const auto M1 = preproc::self_geometric_stiffness(model, red.Phi);
  const Index nq = red.Phi.cols();
  ASSERT_EQ(static_cast<Index>(M1.size()), nq);
  double big = 0;
  for (const auto& m : M1) {
    ASSERT_EQ(m.rows(), nq);
    EXPECT_EQ((m - m.transpose()).cwiseAbs().maxCoeff(), 0.0) << "symmetric in (i,j) by construction";
    big = std::max(big, m.cwiseAbs().maxCoeff());
  }
  ASSERT_GT(big, 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1, 1);
  // q scaled so the largest displacement is ~10 % of the 1 m cells: the cubic part is then
  // 1e-4..1e-2 of the quadratic one, and its extraction loses up to four digits.
  const double scale = 1e-1 / red.Phi.cwiseAbs().maxCoeff();
  double worst = 0, worst2 = 0;
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::VectorXd q(nq);
    for (Index i = 0; i < nq; ++i) q(i) = scale * uni(rng);
    const double Wp = svk_energy(model, body, red.Phi * q), Wm = svk_energy(model, body, -red.Phi * q);
    const double Wp2 = svk_energy(model, body, 2 * red.Phi * q), Wm2 = svk_energy(model, body, -2 * red.Phi * q);
    const double U3 = 0.5 * (Wp - Wm);
    const double U3_ref = cubic_form(M1, q);
    worst = std::max(worst, std::abs(U3 - U3_ref) / std::abs(U3_ref));
    // Even part E(t) = a2 t^2 + a4 t^4: a2 = (16 E(1) - E(2)) / 12 is the linear energy.
    const double a2 = (16 * 0.5 * (Wp + Wm) - 0.5 * (Wp2 + Wm2)) / 12;
    const double U2_ref = 0.5 * q.dot(red.Ke * q);
    worst2 = std::max(worst2, std::abs(a2 - U2_ref) / U2_ref);
    ASSERT_GT(std::abs(U3_ref), 1e-6 * U2_ref) << "the cubic part is large enough to be tested";
  }
  std::cout << c.name << ": cubic part relative error " << worst << ", quadratic part " << worst2 << "\n";
  EXPECT_LT(worst2, 1e-9) << "oracle: quadratic part of W = 1/2 q^T Ke.M0 q";
  EXPECT_LT(worst, 1e-8) << "cubic part of W = 1/2 sum_k q_k q^T Ke.M1[k] q";
}

std::vector<Case> cases() {
  return {{"free", test::free_free_spec(6)},
          {"clamped", test::clamped_spec("L", 6)},
          {"craig-bampton", test::craig_bampton_spec(4)}};
}

}  // namespace

TEST(SelfStiffness, Tet4CubicEnergyOfEveryBasis) {
  const TetBody body(4, 2, 2, false);
  for (const auto& c : cases()) check_against_energy(body, c);
}

TEST(SelfStiffness, Tet10CubicEnergyOfEveryBasis) {
  const TetBody body(3, 1, 1, true);
  for (const auto& c : cases()) check_against_energy(body, c);
}

// The error translation of compute_stiffening: a stress field that cannot be used (here a
// non-finite mode) is the part's "stiffening" request failing, named with the part file.
TEST(SelfStiffness, ANonFiniteResultIsRefusedNamingThePartFileAndField) {
  const TetBody body(2, 1, 1, false);
  const auto model = preproc::build_model(body.mesh, body.part);
  const preproc::Assembled fe = preproc::assemble(model);
  auto red = preproc::reduce(model, fe, test::clamped_spec("L", 3));
  red.Phi(model.dof(5, 1), 1) = NAN;
  try {
    preproc::compute_stiffening(model, fe, red.Phi, true);
    FAIL() << "accepted a non-finite mode";
  } catch (const formats::FormatError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.file(), body.part.file.string());
    EXPECT_EQ(e.object(), "stiffening");
    EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
  }
}
