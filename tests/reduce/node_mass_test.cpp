// The block Lanczos's products with M from the solids' node mass Ms (reduce/node_mass.hpp)
// against the products with the constrained M the reduction forms by the transform: equal to
// rounding where M is a principal submatrix of a part of solids alone (clamped on the only
// interface; Craig-Bampton's interior with rigid interfaces), for a block of four columns (the
// vectorised kernel) and of three (the general one); refused where M is not Ms (x) I3 on its
// rows: a point mass in the part, or a free spider coupling its nodes.
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/constraints.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/reduce/reduction.hpp"
#include "ffr/preproc/threads.hpp"
#include "reduce/node_mass.hpp"
#include "reduce/pattern_analysis.hpp"
#include "reduce/setup.hpp"
#include "reduce/sparse_ops.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

using namespace ffr;
using preproc::Index;
using preproc::SparseMatrix;

namespace {

preproc::ReductionSpec clamped_left() { return test::clamped_spec("L", 4); }

// The grid with its interface L alone (held by clamped_left, a principal submatrix then).
void keep_left_only(test::HexGrid& grid) {
  auto& itf = grid.part.interfaces;
  itf.erase(std::remove_if(itf.begin(), itf.end(), [](const auto& i) { return i.name != "L"; }), itf.end());
}
preproc::ReductionSpec craig_bampton() { return test::craig_bampton_spec(4); }
preproc::ReductionSpec free_free() { return test::free_free_spec(4); }

// The eigen-solve's M as the reduction forms it (reduction.cpp): the transform's congruence,
// and for Craig-Bampton its interior block; full storage.
SparseMatrix eigen_mass(const preproc::FeModel& model, const preproc::Assembled& fe, const preproc::DofTransform& t,
                        const preproc::ReductionSpec& spec) {
  SparseMatrix M = preproc::detail::constrained(t, fe.M, true);
  if (spec.method != preproc::ReductionSpec::Method::CraigBampton) return M;
  const auto interior = preproc::detail::interior_of(M.rows(), preproc::detail::boundary_dofs(model, t, spec));
  return preproc::detail::congruence(preproc::detail::selection(M.rows(), interior), M);
}

}  // namespace

TEST(NodeMassProduct, EqualsTheProductWithTheConstrainedMass) {
  struct Case {
    const char* what;
    bool right_rigid, left_only;
    preproc::ReductionSpec spec;
    int nx, ny, nz;
    unsigned threads;
  };
  const unsigned before = preproc::max_threads();
  // The last case is large enough (97 000 entries of Ms, four columns) for two threads, whose
  // parts add into buffers of their own; at sixteen columns its gather and scatter of the rows
  // are split between the threads too.
  for (const Case& c : {Case{"clamped, L alone", false, true, clamped_left(), 6, 3, 2, 1},
                        Case{"craig-bampton, R rigid", true, false, craig_bampton(), 6, 3, 2, 1},
                        Case{"clamped, L alone, two threads", false, true, clamped_left(), 40, 12, 12, 2}}) {
    SCOPED_TRACE(c.what);
    preproc::set_max_threads(c.threads);
    test::HexGrid grid(c.nx, c.ny, c.nz);
    auto& itf = grid.part.interfaces;
    if (c.right_rigid)
      for (auto& i : itf) i.coupling = "rigid";
    if (c.left_only) keep_left_only(grid);
    const auto model = preproc::build_model(grid.mesh, grid.part);
    const preproc::Assembled fe = preproc::assemble(model);
    const preproc::DofTransform t = preproc::build_transform(model, preproc::detail::states_for(model, c.spec));
    const auto rows = preproc::detail::factorized_rows(model, t, c.spec);
    const auto product = preproc::detail::NodeMassProduct::make(model, fe, rows);
    ASSERT_NE(product, nullptr);
    const SparseMatrix M = eigen_mass(model, fe, t, c.spec);
    ASSERT_EQ(product->rows(), M.rows());
    for (const Index p : {Index{4}, Index{3}, Index{16}}) {
      const Eigen::MatrixXd X = Eigen::MatrixXd::Random(M.rows(), p);
      const Eigen::MatrixXd expect = M * X;
      Eigen::MatrixXd Y;
      product->apply(X, Y);
      product->apply(X, Y);  // a second call on the kept buffers gives the same
      ASSERT_EQ(Y.rows(), M.rows());
      ASSERT_EQ(Y.cols(), p);
      EXPECT_LT((Y - expect).cwiseAbs().maxCoeff(), 1e-14 * expect.cwiseAbs().maxCoeff()) << p << " columns";
    }
  }
  preproc::set_max_threads(before);
}

TEST(NodeMassProduct, DeclinesWhereMIsNotTheNodeMass) {
  // The rows the reduction's eigen-solve takes for `spec`, and the product for them.
  const auto rows_and_product = [](const test::HexGrid& grid, const preproc::ReductionSpec& spec) {
    const auto model = preproc::build_model(grid.mesh, grid.part);
    const preproc::Assembled fe = preproc::assemble(model);
    const preproc::DofTransform t = preproc::build_transform(model, preproc::detail::states_for(model, spec));
    const auto rows = preproc::detail::factorized_rows(model, t, spec);
    return std::make_pair(rows, preproc::detail::NodeMassProduct::make(model, fe, rows) != nullptr);
  };
  // A point mass adds to M and not to Ms.
  {
    test::HexGrid grid(4, 2, 2);
    keep_left_only(grid);
    preproc::PointMassSpec m;
    m.name = "tip";
    m.at = grid.mesh.x.row(grid.mesh.x.rows() - 1).transpose();
    m.mass = 2.0;
    grid.part.point_masses.push_back(m);
    const auto [rows, made] = rows_and_product(grid, clamped_left());
    EXPECT_FALSE(rows.empty());
    EXPECT_FALSE(made);
  }
  // Free-free with both spiders free: the transform couples their nodes (no principal
  // submatrix, so no rows to take).
  {
    const auto [rows, made] = rows_and_product(test::HexGrid(4, 2, 2), free_free());
    EXPECT_TRUE(rows.empty());
    EXPECT_FALSE(made);
  }
}

// M's values on the eigen-solve's structure from Ms (node_mass_values, for an assembly without
// M: AssemblyOptions::node_mass_only) against the assembled M's, entry for entry and bit for
// bit, and the reduction from such an assembly against the one from the full assembly: the
// same eigenvalues and modes, exactly. Where M is not Ms (x) I3 (a point mass) the assembly
// keeps M; rows that are not a node's translations give no values.
TEST(NodeMassValues, AreTheAssembledMassBitForBit) {
  test::HexGrid grid(8, 3, 3);
  keep_left_only(grid);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  const auto spec = clamped_left();
  const preproc::DofTransform t = preproc::build_transform(model, preproc::detail::states_for(model, spec));
  const auto rows = preproc::detail::factorized_rows(model, t, spec);
  ASSERT_FALSE(rows.empty());
  const preproc::Assembled full = preproc::assemble(model);
  preproc::AssemblyOptions opt;
  opt.node_mass_only = true;
  const preproc::Assembled lean = preproc::assemble(model, opt);
  EXPECT_EQ(lean.M.rows(), 0);
  ASSERT_EQ(lean.K.nonZeros(), full.K.nonZeros());

  const SparseMatrix K = preproc::detail::constrained(t, full.K, false);
  const SparseMatrix M = preproc::detail::constrained(t, full.M, false);
  ASSERT_TRUE(preproc::detail::same_structure(K, M));
  const std::vector<double> values = preproc::detail::node_mass_values(model, lean.Ms, K, rows);
  ASSERT_EQ(values.size(), static_cast<std::size_t>(M.nonZeros()));
  for (Index e = 0; e < M.nonZeros(); ++e) ASSERT_EQ(values[static_cast<std::size_t>(e)], M.valuePtr()[e]) << "entry " << e;

  const auto a = preproc::reduce(model, full, spec);
  const auto b = preproc::reduce(model, lean, spec);
  ASSERT_EQ(a.lambda.size(), b.lambda.size());
  EXPECT_EQ((a.lambda - b.lambda).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((a.Phi - b.Phi).cwiseAbs().maxCoeff(), 0.0);

  // A row outside the mesh's translations (an interface node's DOF): no values.
  std::vector<Index> bad = rows;
  bad.back() = model.mesh_dofs();
  ASSERT_LT(bad.back(), model.num_dofs);  // the held interface's node
  EXPECT_TRUE(preproc::detail::node_mass_values(model, lean.Ms, K, bad).empty());

  // A point mass: M is not Ms (x) I3, and the assembly keeps it.
  test::HexGrid massive(4, 2, 2);
  preproc::PointMassSpec m;
  m.name = "tip";
  m.at = massive.mesh.x.row(massive.mesh.x.rows() - 1).transpose();
  m.mass = 2.0;
  massive.part.point_masses.push_back(m);
  EXPECT_GT(preproc::assemble(preproc::build_model(massive.mesh, massive.part), opt).M.rows(), 0);
}
