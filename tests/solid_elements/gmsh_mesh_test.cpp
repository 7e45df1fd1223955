// Node ordering against real gmsh output. The meshes in data/ were written by gmsh 4.8 from
// the .geo files beside them (box 1 x 0.8 x 0.6; command line in each .geo; MSH 2.2 ASCII).
// If a kernel misread gmsh's node order, its elements would be reported inverted, their
// volumes would not add up to the box, or neighbours would not conform and the patch test
// on the mesh would fail.
#include "support.hpp"

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {
struct MshElement {
  ElementType type;
  std::vector<int> conn;  // 0-based node indices
};
struct Msh {
  std::vector<Eigen::Vector3d> x;
  std::vector<MshElement> elems;
};

// Minimal MSH 2.2 ASCII reader (nodes and volume elements).
Msh read_msh22(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Msh m;
  std::map<long, int> index;
  std::string line;
  while (std::getline(in, line)) {
    if (line == "$Nodes") {
      long n;
      in >> n;
      for (long i = 0; i < n; ++i) {
        long id;
        Eigen::Vector3d p;
        in >> id >> p.x() >> p.y() >> p.z();
        index[id] = static_cast<int>(m.x.size());
        m.x.push_back(p);
      }
    } else if (line == "$Elements") {
      long n;
      in >> n;
      std::getline(in, line);
      for (long i = 0; i < n; ++i) {
        std::getline(in, line);
        std::istringstream ls(line);
        long id, type, ntags, tag;
        ls >> id >> type >> ntags;
        for (long k = 0; k < ntags; ++k) ls >> tag;
        const ElementType t = from_gmsh(static_cast<int>(type));
        if (dimension(t) != 3) continue;
        MshElement e{t, {}};
        long node;
        while (ls >> node) e.conn.push_back(index.at(node));
        EXPECT_EQ(static_cast<int>(e.conn.size()), num_nodes(t));
        m.elems.push_back(e);
      }
    }
  }
  return m;
}

Eigen::MatrixX3d coords(const Msh& m, const MshElement& e) {
  Eigen::MatrixX3d xe(e.conn.size(), 3);
  for (std::size_t a = 0; a < e.conn.size(); ++a) xe.row(a) = m.x[e.conn[a]].transpose();
  return xe;
}

class GmshBox : public ::testing::TestWithParam<std::string> {};
}  // namespace

TEST_P(GmshBox, ValidElementsExactMassAndPatchTest) {
  const Msh m = read_msh22(std::string(FFR_SOURCE_DIR) + "/tests/solid_elements/data/" + GetParam());
  ASSERT_FALSE(m.elems.empty());
  const Material mat{1000, 0.3, 2.0};
  const Eigen::Vector3d L(1.0, 0.8, 0.6);
  double mass = 0;
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d s2 = Eigen::Matrix3d::Zero();
  const int ndof = 3 * static_cast<int>(m.x.size());
  std::vector<Eigen::Triplet<double>> trip;
  for (const MshElement& e : m.elems) {
    const Eigen::MatrixX3d xe = coords(m, e);
    ElementMatrices em;
    ASSERT_NO_THROW(em = solid_element(e.type, xe, mat)) << name(e.type);
    EXPECT_GT(solid_quality(e.type, xe).min_scaled_jacobian, 0.0) << name(e.type) << " " << xe;
    for (const MassSample& s : em.samples) {
      mass += s.w;
      s1 += s.w * s.c;
      s2 += s.w * s.c * s.c.transpose();
    }
    for (std::size_t a = 0; a < e.conn.size(); ++a)
      for (std::size_t b = 0; b < e.conn.size(); ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) trip.emplace_back(3 * e.conn[a] + i, 3 * e.conn[b] + j, em.K(3 * a + i, 3 * b + j));
  }
  // Box moments: V = abc, int x = V L/2, int x_i x_j = V L_i L_j / 4 (i != j), V L_i^2 / 3.
  const double V = L.prod();
  Eigen::Matrix3d S2 = V * L * L.transpose() / 4;
  S2.diagonal() = V * L.cwiseProduct(L) / 3;
  EXPECT_NEAR(mass, mat.rho * V, 1e-12 * mat.rho * V);
  EXPECT_LT((s1 - mat.rho * V * L / 2).norm(), 1e-12 * mat.rho * V);
  EXPECT_LT((s2 - mat.rho * S2).norm(), 1e-12 * mat.rho * S2.norm());

  // Patch test on the gmsh mesh: K u_exact has no force at interior nodes.
  Sparse K(ndof, ndof);
  K.setFromTriplets(trip.begin(), trip.end());
  Eigen::Matrix3d A;
  A << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 6e-4, 4e-4;
  Eigen::VectorXd u(ndof);
  for (std::size_t n = 0; n < m.x.size(); ++n) u.segment<3>(3 * n) = A * m.x[n];
  const Eigen::VectorXd r = K * u;
  int interior = 0;
  for (std::size_t n = 0; n < m.x.size(); ++n) {
    bool inner = true;
    for (int k = 0; k < 3; ++k) inner = inner && m.x[n][k] > 1e-9 && m.x[n][k] < L[k] - 1e-9;
    if (!inner) continue;
    ++interior;
    EXPECT_LT(r.segment<3>(3 * n).norm(), 1e-10 * mat.E * 1e-3) << "node " << n;
  }
  EXPECT_GT(interior, 0);
  // The boundary forces are those of the constant stress (they sum to zero).
  EXPECT_LT(std::abs(r.sum()), 1e-10 * r.norm());
}

INSTANTIATE_TEST_SUITE_P(Meshes, GmshBox,
                         ::testing::Values("box_tet4.msh", "box_tet10.msh", "box_hex8.msh", "box_hex20.msh",
                                           "box_hex27.msh", "box_wedge6.msh", "box_wedge15.msh",
                                           "box_pyramid5_mixed.msh"),
                         [](const auto& info) {
                           std::string s = info.param.substr(4, info.param.size() - 8);
                           return s;
                         });
