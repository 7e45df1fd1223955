// Global assembly against an independent sum: the element matrices of every element added at
// its DOFs through Eigen triplets (no pattern, no colouring, no threads). The threaded assembly
// scatters colour classes of elements with no node in common without a lock, one class after
// another, so it must also give the same bits on one thread and on two. The visual surface
// built from the same grid must not depend on the node numbering.
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/threads.hpp"
#include "ffr/preproc/visual/visual.hpp"
#include "support.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include <vector>

using namespace ffr;
using preproc::Index;

namespace {

preproc::SparseMatrix triplet_sum(const preproc::FeModel& model, bool mass) {
  std::vector<Eigen::Triplet<double>> trip;
  for (const auto& ref : preproc::all_elements(model)) {
    const auto em = preproc::element_matrices(model, ref);
    const Eigen::MatrixXd& A = mass ? em.M : em.K;
    const auto dofs = preproc::element_dofs(model, ref);
    for (std::size_t b = 0; b < dofs.size(); ++b)
      for (std::size_t a = 0; a < dofs.size(); ++a)
        trip.emplace_back(dofs[a], dofs[b], A(static_cast<Index>(a), static_cast<Index>(b)));
  }
  preproc::SparseMatrix S(model.num_dofs, model.num_dofs);
  S.setFromTriplets(trip.begin(), trip.end());
  return S;
}

double relative_difference(const preproc::SparseMatrix& A, const preproc::SparseMatrix& B) {
  return preproc::SparseMatrix(A - B).norm() / B.norm();
}

}  // namespace

TEST(Assembly, MatchesTheElementSumAndIsTheSameOnTwoThreads) {
  test::HexGrid grid(9, 7, 5);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  preproc::AssemblyOptions one, two;
  one.threads = 1;
  two.threads = 2;
  // Blocks of 4 of the 315 elements: colour classes of many blocks, which the two threads
  // share (with the default 64, this grid has 5 blocks, one or two a class).
  one.block_elements = two.block_elements = 4;
  const auto a1 = preproc::assemble(model, one);
  const auto a2 = preproc::assemble(model, two);
  EXPECT_LT(relative_difference(a1.K, triplet_sum(model, false)), 1e-14);
  EXPECT_LT(relative_difference(a1.M, triplet_sum(model, true)), 1e-14);
  // Every entry is summed in the order of the colour classes and, within a block, of its
  // elements, whatever the thread count; the patterns (filled by two threads for a2: 117k
  // entries) are the same.
  ASSERT_EQ(a1.K.nonZeros(), a2.K.nonZeros());
  ASSERT_EQ(a1.M.nonZeros(), a2.M.nonZeros());
  EXPECT_TRUE(std::equal(a1.K.outerIndexPtr(), a1.K.outerIndexPtr() + a1.K.cols() + 1, a2.K.outerIndexPtr()));
  EXPECT_TRUE(std::equal(a1.K.innerIndexPtr(), a1.K.innerIndexPtr() + a1.K.nonZeros(), a2.K.innerIndexPtr()));
  EXPECT_TRUE(std::equal(a1.M.innerIndexPtr(), a1.M.innerIndexPtr() + a1.M.nonZeros(), a2.M.innerIndexPtr()));
  EXPECT_TRUE(std::equal(a1.K.valuePtr(), a1.K.valuePtr() + a1.K.nonZeros(), a2.K.valuePtr()));
  EXPECT_TRUE(std::equal(a1.M.valuePtr(), a1.M.valuePtr() + a1.M.nonZeros(), a2.M.valuePtr()));
  // Mass: density times volume. The grid is the linear image of 9 x 7 x 5 unit cubes under
  // [[1, 0.1, 0], [0, 1, 0.05], [0.02, 0, 1]], whose determinant is 1.0001.
  EXPECT_NEAR(a2.mass, 7850.0 * 315 * 1.0001, 1e-12 * 7850.0 * 315);
  EXPECT_EQ(a1.worst_element, a2.worst_element);
}

// The pipeline's element loop starts on one thread beside the early analysis and takes a second
// core once that has finished (AssemblyOptions::spare_core, asked before each colour class): a
// second thread joining halfway gives the same bits, and the same sums. Point masses on the grid
// (on solid nodes, so without offsets) make the sums of the mass samples (mass, first and second
// moments) depend on the order they are added in: per block, the blocks in their order.
TEST(Assembly, ASpareCoreJoiningHalfwayChangesNothing) {
  if (preproc::max_threads() < 2) GTEST_SKIP() << "one core: no spare core to join";
  test::HexGrid grid(9, 7, 5);
  grid.part.materials[0].mat.rho = 1e-9;  // the solids' mass (through Ms) would hide the samples' rounding
  for (int k = 0; k < 120; ++k) {
    preproc::PointMassSpec m;
    m.name = "m";
    m.name += std::to_string(k);  // appended: "m" + to_string trips GCC 12 -Wrestrict (PR105329)
    m.at = grid.mesh.x.row(static_cast<Index>(37 * k % grid.mesh.x.rows())).transpose();
    m.mass = 0.1 + 0.7 * std::sqrt(static_cast<double>(k + 2));
    grid.part.point_masses.push_back(m);
  }
  const auto model = preproc::build_model(grid.mesh, grid.part);
  preproc::AssemblyOptions one, joined;
  one.threads = joined.threads = 1;
  one.block_elements = joined.block_elements = 4;
  int asked = 0;
  joined.spare_core = [&asked] { return ++asked > 2; };  // from the third class on
  const auto a1 = preproc::assemble(model, one);
  const auto aj = preproc::assemble(model, joined);
  EXPECT_GT(asked, 3);  // the grid has more than three classes, so the second thread took part
  ASSERT_EQ(a1.K.nonZeros(), aj.K.nonZeros());
  EXPECT_TRUE(std::equal(a1.K.valuePtr(), a1.K.valuePtr() + a1.K.nonZeros(), aj.K.valuePtr()));
  EXPECT_TRUE(std::equal(a1.M.valuePtr(), a1.M.valuePtr() + a1.M.nonZeros(), aj.M.valuePtr()));
  EXPECT_EQ(a1.mass, aj.mass);
  EXPECT_EQ(a1.rdm, aj.rdm);
  EXPECT_EQ(a1.rrdm, aj.rrdm);
  EXPECT_EQ(a1.worst_element, aj.worst_element);
}

// The visual surface follows the mesh file's node tags, not the internal node numbering (a
// space-filling curve at import): the same grid with its nodes numbered in reverse, tags kept,
// gives the same vertices, triangles and mode shapes.
TEST(Surface, IsTheSameForAnyNodeNumbering) {
  test::HexGrid g(3, 2, 2);
  const Index N = g.mesh.x.rows();
  for (Index n = 0; n < N; ++n) g.mesh.node_tags.push_back(static_cast<std::size_t>(n + 1));
  preproc::Mesh r = g.mesh;  // node i of r is node N - 1 - i of g
  const auto flip = [&](Index n) { return N - 1 - n; };
  for (Index n = 0; n < N; ++n) {
    r.x.row(n) = g.mesh.x.row(flip(n));
    r.node_tags[static_cast<std::size_t>(n)] = g.mesh.node_tags[static_cast<std::size_t>(flip(n))];
  }
  for (auto& c : r.blocks[0].conn) c = flip(c);
  for (auto& [name, nodes] : r.node_groups) {
    for (auto& n : nodes) n = flip(n);
    std::sort(nodes.begin(), nodes.end());
  }
  const auto surface = [](const preproc::Mesh& mesh, const preproc::PartSpec& part) {
    const auto model = preproc::build_model(mesh, part);
    Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(model.num_dofs, 2);  // shapes given by position
    for (Index n = 0; n < mesh.x.rows(); ++n)
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 2; ++k) Phi(model.dof(n, a), k) = (k + 1) * mesh.x(n, a) + a;
    return preproc::surface_with_modes(model, Phi);
  };
  const auto s1 = surface(g.mesh, g.part), s2 = surface(r, g.part);
  ASSERT_GT(s1.triangles.rows(), 0);
  EXPECT_EQ(s1.vertices, s2.vertices);
  EXPECT_EQ(s1.triangles, s2.triangles);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(s1.modes[k], s2.modes[k]) << k;
}

// The surface of a box of nx x ny x nz hexahedra: 2 (nx ny + ny nz + nz nx) boundary quads, two
// triangles each, on every node but the (nx - 1)(ny - 1)(nz - 1) inside (counted by hand).
TEST(Surface, IsTheBoundaryOfABoxOfHexahedra) {
  test::HexGrid g(3, 2, 2);
  ASSERT_EQ(g.mesh.x.rows(), 4 * 3 * 3);
  for (Index n = 0; n < g.mesh.x.rows(); ++n) g.mesh.node_tags.push_back(static_cast<std::size_t>(n + 1));
  const auto model = preproc::build_model(g.mesh, g.part);
  const auto s = preproc::surface_with_modes(model, Eigen::MatrixXd::Zero(model.num_dofs, 1));
  EXPECT_EQ(s.triangles.rows(), 2 * 2 * (3 * 2 + 2 * 2 + 2 * 3));
  EXPECT_EQ(s.vertices.rows(), 4 * 3 * 3 - 2 * 1 * 1);
  // Every vertex is a node on the grid's boundary (HexGrid numbers node (i, j, k) as
  // (k (ny + 1) + j)(nx + 1) + i); the surface copies node positions exactly.
  std::vector<Eigen::RowVector3d> boundary;
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 3; ++i)
        if (i == 0 || i == 3 || j == 0 || j == 2 || k == 0 || k == 2) boundary.push_back(g.mesh.x.row((k * 3 + j) * 4 + i));
  for (Index v = 0; v < s.vertices.rows(); ++v) {
    const Eigen::RowVector3d p = s.vertices.row(v);
    EXPECT_TRUE(std::any_of(boundary.begin(), boundary.end(), [&](const Eigen::RowVector3d& b) { return b == p; })) << v;
  }
}
