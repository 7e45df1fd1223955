// The eigen-solve's symbolic analysis started before the assembly (EarlyAnalysis) against the
// one made afterwards from the assembled K and M: the same factor structure, no second
// analysis at the factorization, and bit for bit the same modes, for a clamped (rigid spider
// held), a free-free and a Craig-Bampton reduction. It starts with two threads only; bad input
// reaches the reduction as before. Also on two threads: the factorization by subtrees gives
// the one-thread modes for the three reductions. And the structure the analysis writes from the
// mesh's node graph (reduce/pattern_analysis.hpp) against the constrained matrix formed by the
// transform, entry for entry.
#include "ffr/formats/h5.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/reduce/reduction.hpp"
#include "ffr/preproc/threads.hpp"
#include "reduce/pattern_analysis.hpp"
#include "solver/nodal_ordering.hpp"
#include "reduce/setup.hpp"
#include "reduce/sparse_ops.hpp"
#include "solver/pattern_hash.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace ffr;
using preproc::SparseMatrix;

namespace {

// Two threads for the test (EarlyAnalysis starts only with two or more), restored after it.
struct TwoThreads {
  unsigned before = preproc::max_threads();
  TwoThreads() { preproc::set_max_threads(2); }
  ~TwoThreads() { preproc::set_max_threads(before); }
};

preproc::ReductionSpec clamped() { return test::clamped_spec("L", 6); }
preproc::ReductionSpec free_free() { return test::free_free_spec(6); }
preproc::ReductionSpec craig_bampton() { return test::craig_bampton_spec(6); }

const char* name(const preproc::ReductionSpec& s) {
  switch (s.method) {
    case preproc::ReductionSpec::Method::Free: return "free";
    case preproc::ReductionSpec::Method::Clamped: return "clamped";
    case preproc::ReductionSpec::Method::CraigBampton: return "craig-bampton";
  }
  return "?";
}

}  // namespace

// The grid's interfaces: as HexGrid makes them (L rigid, R averaged), with R rigid too, or L
// alone. A spider left free, or an averaged interface, couples its nodes in the transform, and
// the analysis then forms the matrix by it; held spiders and Craig-Bampton's rigid boundary
// leave the eigen-solve's matrix a principal submatrix of the assembled one, which the
// analysis writes from the node graph (clamped with L alone, Craig-Bampton with R rigid).
enum class Interfaces { Averaged, Rigid, LeftOnly };

test::HexGrid grid_with(int nx, int ny, int nz, Interfaces which) {
  test::HexGrid grid(nx, ny, nz);
  auto& itf = grid.part.interfaces;
  if (which == Interfaces::Rigid)
    for (auto& i : itf) i.coupling = "rigid";
  if (which == Interfaces::LeftOnly)
    itf.erase(std::remove_if(itf.begin(), itf.end(), [](const auto& i) { return i.name != "L"; }), itf.end());
  return grid;
}

const char* name(Interfaces w) {
  return w == Interfaces::Averaged ? ", R averaged" : w == Interfaces::Rigid ? ", R rigid" : ", L alone";
}

// The reductions a grid's interfaces allow (Craig-Bampton needs R).
std::vector<preproc::ReductionSpec> specs_for(Interfaces w) {
  if (w == Interfaces::LeftOnly) return {clamped(), free_free()};
  return {clamped(), free_free(), craig_bampton()};
}

TEST(EarlyAnalysis, GivesTheSameFactorAndModesWithoutAnalysingAgain) {
  TwoThreads two;
  for (const auto which : {Interfaces::Averaged, Interfaces::Rigid, Interfaces::LeftOnly})
  for (const auto& spec : specs_for(which)) {
    SCOPED_TRACE(std::string(name(spec)) + name(which));
    test::HexGrid grid = grid_with(12, 4, 3, which);
    const auto model = preproc::build_model(grid.mesh, grid.part);
    preproc::EarlyAnalysis early = preproc::EarlyAnalysis::start(model, spec);
    ASSERT_TRUE(early.started());
    const preproc::Assembled fe = preproc::assemble(model);
    std::vector<std::string> lines;
    preproc::ReductionLog log;
    log.message = [&](const std::string& s) { lines.push_back(s); };
    const auto with = preproc::reduce(model, fe, spec, log, &early);
    const auto without = preproc::reduce(model, fe, spec);
    // One analysis each: the early one was used as it was.
    EXPECT_EQ(with.factor.analyses, 1);
    EXPECT_EQ(without.factor.analyses, 1);
    EXPECT_EQ(with.factor.nnz_A, without.factor.nnz_A);
    EXPECT_EQ(with.factor.nnz_L, without.factor.nnz_L);
    EXPECT_EQ(with.factor.factor_entries, without.factor.factor_entries);
    EXPECT_EQ(with.factor.supernodes, without.factor.supernodes);
    EXPECT_EQ(with.factor.ordering_vertices, without.factor.ordering_vertices);
    bool said = false;
    for (const auto& l : lines) said = said || l.find("analysed during the assembly") != std::string::npos;
    EXPECT_TRUE(said);
    ASSERT_EQ(with.lambda.size(), spec.method == preproc::ReductionSpec::Method::CraigBampton ? 12 : 6);
    EXPECT_EQ(with.lambda, without.lambda);
    EXPECT_EQ(with.Phi, without.Phi);
  }
}

// The upper triangle written from the entity pattern has exactly the entries of the
// constrained matrix the reduction forms by the transform (for Craig-Bampton, of its interior
// block), and the node graph one group per node that keeps DOFs. Where the transform couples
// nodes (R averaged, or any spider left free) the direct construction must decline.
TEST(EarlyAnalysis, WritesThePrincipalSubmatrixFromTheNodeGraph) {
  for (const auto which : {Interfaces::Averaged, Interfaces::Rigid, Interfaces::LeftOnly})
  for (const auto& spec : specs_for(which)) {
    SCOPED_TRACE(std::string(name(spec)) + name(which));
    test::HexGrid grid = grid_with(5, 3, 2, which);
    const auto model = preproc::build_model(grid.mesh, grid.part);
    const bool cb = spec.method == preproc::ReductionSpec::Method::CraigBampton;
    const preproc::DofTransform t = preproc::build_transform(model, preproc::detail::states_for(model, spec));
    std::vector<preproc::Index> columns;
    if (cb) {
      columns = preproc::detail::interior_of(t.num_ind(), preproc::detail::boundary_dofs(model, t, spec));
    } else {
      for (preproc::Index j = 0; j < t.num_ind(); ++j) columns.push_back(j);
    }
    const auto rows = preproc::detail::unit_column_rows(t, columns);
    const bool principal = (cb && which == Interfaces::Rigid) ||
                           (spec.method == preproc::ReductionSpec::Method::Clamped && which == Interfaces::LeftOnly);
    ASSERT_EQ(!rows.empty(), principal);
    if (!principal) continue;

    SparseMatrix C = preproc::detail::constrained(t, preproc::assembly_pattern(model), cb);
    if (cb) {
      SparseMatrix Cii = preproc::detail::congruence(preproc::detail::selection(C.rows(), columns), C);
      C.swap(Cii);
    }
    const SparseMatrix upper = C.triangularView<Eigen::Upper>();
    const preproc::detail::Pattern p = preproc::detail::build_pattern(model, preproc::all_elements(model));
    const auto st = preproc::detail::selected_structure(p, rows, true);
    ASSERT_TRUE(st.has_value());
    // The hash factorize checks, streamed without the matrix, is that of the matrix.
    std::int64_t upper_nnz = 0;
    EXPECT_EQ(st->hash, preproc::detail::upper_pattern_hash(upper, &upper_nnz));
    EXPECT_EQ(st->upper_nnz, upper_nnz);
    EXPECT_EQ(upper_nnz, upper.nonZeros());
    ASSERT_EQ(st->upper.rows(), upper.rows());
    ASSERT_EQ(st->upper.nonZeros(), upper.nonZeros());
    EXPECT_TRUE(std::equal(upper.outerIndexPtr(), upper.outerIndexPtr() + upper.cols() + 1, st->upper.outerIndexPtr()));
    EXPECT_TRUE(std::equal(upper.innerIndexPtr(), upper.innerIndexPtr() + upper.nonZeros(), st->upper.innerIndexPtr()));
    // Groups: the grid's nodes that keep DOFs (three each), no interface node.
    const auto& g = st->graph;
    ASSERT_GE(g.first.size(), 2u);
    EXPECT_EQ(g.first.back(), upper.rows());
    EXPECT_EQ(3 * (static_cast<preproc::Index>(g.first.size()) - 1), upper.rows());
    for (std::size_t G = 0; G + 1 < g.first.size(); ++G) {
      EXPECT_EQ(g.first[G + 1] - g.first[G], 3);
      // Neighbours: the groups whose columns meet G's first column in C, G itself excluded.
      std::vector<std::int64_t> expect;
      const auto j = g.first[G];
      for (SparseMatrix::InnerIterator it(C, j); it; ++it) {
        const auto H = static_cast<std::int64_t>(std::upper_bound(g.first.begin(), g.first.end(), it.row()) - g.first.begin()) - 1;
        if (H != static_cast<std::int64_t>(G) && (expect.empty() || expect.back() != H)) expect.push_back(H);
      }
      if (!cb) {
        // C holds its upper triangle only: the later neighbours come from their own columns.
        for (std::size_t H = G + 1; H + 1 < g.first.size(); ++H)
          for (SparseMatrix::InnerIterator it(C, g.first[H]); it; ++it)
            if (it.row() == j) expect.push_back(static_cast<std::int64_t>(H));
      }
      const std::vector<std::int64_t> got(g.adjncy.begin() + g.xadj[G], g.adjncy.begin() + g.xadj[G + 1]);
      ASSERT_EQ(got, expect) << "group " << G;
    }
  }
}

// The symbolic factor from the node graph (CholmodFactor::analyze_groups, grouped_symbolic.hpp)
// against CHOLMOD's analysis of the DOF matrix in the same order: the same nnz(L) and flops
// (CHOLMOD's own counts), no second analysis at the factorization, and the same solutions.
TEST(GroupedSymbolic, FactorsAsTheAnalysisOfTheDofMatrix) {
  const test::HexGrid grid = grid_with(12, 6, 5, Interfaces::LeftOnly);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  const auto spec = clamped();
  const preproc::DofTransform t = preproc::build_transform(model, preproc::detail::states_for(model, spec));
  const preproc::Assembled fe = preproc::assemble(model);
  const SparseMatrix K = preproc::detail::constrained(t, fe.K, false);  // upper triangle
  const auto rows = preproc::detail::factorized_rows(model, t, spec);
  ASSERT_FALSE(rows.empty());
  const preproc::detail::Pattern p = preproc::detail::build_pattern(model, preproc::all_elements(model));
  const auto st = preproc::detail::selected_structure(p, rows, false);
  ASSERT_TRUE(st.has_value());
  const auto order = preproc::detail::metis_ordering(st->graph);
  ASSERT_EQ(static_cast<Eigen::Index>(order.perm.size()), K.rows());

  preproc::CholmodFactor dof, grouped;
  const auto ref = dof.analyze(K, order.perm, order.groups, "METIS");
  const auto got = grouped.analyze_groups(st->graph, order.perm, order.groups, st->hash, st->upper_nnz);
  EXPECT_EQ(got.n, ref.n);
  EXPECT_EQ(got.nnz_A, ref.nnz_A);
  EXPECT_EQ(got.nnz_L, ref.nnz_L);
  EXPECT_NEAR(got.flops, ref.flops, 1e-12 * ref.flops);
  EXPECT_GT(got.factor_entries, 0);
  dof.factorize(K);
  grouped.factorize(K);
  EXPECT_EQ(grouped.info().stats.analyses, 1) << "factorize analysed again: the hash did not match";
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(K.rows(), 5);
  const Eigen::MatrixXd X_ref = dof.solve(B), X = grouped.solve(B);
  EXPECT_LT((X - X_ref).norm(), 1e-10 * X_ref.norm());
  // Splitting a group is refused.
  std::vector<std::int64_t> split = order.perm;
  std::swap(split[0], split.back());
  EXPECT_THROW(grouped.analyze_groups(st->graph, split, order.groups, st->hash, st->upper_nnz), std::invalid_argument);
}

// A given order must be a permutation of the columns; the factor analysed with one reports it.
TEST(EarlyAnalysis, GivenOrderIsCheckedAndReported) {
  test::HexGrid grid(3, 2, 2);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  const SparseMatrix A = preproc::assembly_pattern(model);
  const auto n = static_cast<std::int64_t>(A.cols());
  std::vector<std::int64_t> perm(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k) perm[static_cast<std::size_t>(k)] = n - 1 - k;
  preproc::CholmodFactor f;
  const auto& stats = f.analyze(A, perm, n / 3, "reversed");
  EXPECT_EQ(stats.ordering, "reversed");
  EXPECT_EQ(stats.ordering_vertices, n / 3);
  EXPECT_GT(stats.nnz_L, 0.0);
  for (auto bad : {std::vector<std::int64_t>(perm.begin(), perm.end() - 1), perm}) {
    if (bad.size() == perm.size()) bad[1] = bad[0];  // a column twice
    try {
      f.analyze(A, bad, n, "bad");
      FAIL() << "a non-permutation of " << bad.size() << " entries was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("not a permutation of its " + std::to_string(n) + " columns"), std::string::npos)
          << e.what();
    }
  }
}

TEST(EarlyAnalysis, NeedsTwoThreadsAndLeavesBadInputToTheReduction) {
  test::HexGrid grid(3, 2, 2);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  {
    const unsigned before = preproc::max_threads();
    preproc::set_max_threads(1);
    EXPECT_FALSE(preproc::EarlyAnalysis::start(model, clamped()).started());
    preproc::set_max_threads(before);
  }
  TwoThreads two;
  {
    // Left without take() (an error upstream): the destructor waits for the thread, which
    // skips the analysis if it has not begun it.
    preproc::EarlyAnalysis left = preproc::EarlyAnalysis::start(model, clamped());
    EXPECT_TRUE(left.started());
  }
  // Overlapping interface groups (refused by the constraints): no factor from the early
  // analysis, and the reduction's own error, as without it.
  test::HexGrid overlap(3, 2, 2);
  overlap.part.interfaces.push_back({"L2", "left", "rigid", {}});
  const auto bad = preproc::build_model(overlap.mesh, overlap.part);
  preproc::EarlyAnalysis early = preproc::EarlyAnalysis::start(bad, free_free());
  ASSERT_TRUE(early.started());
  EXPECT_EQ(early.take(), nullptr);
  preproc::EarlyAnalysis again = preproc::EarlyAnalysis::start(bad, free_free());
  const preproc::Assembled fe = preproc::assemble(bad);
  try {
    preproc::reduce(bad, fe, free_free(), {}, &again);
    FAIL() << "overlapping interface groups were accepted";
  } catch (const formats::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("must not overlap"), std::string::npos) << e.what();
  }
}

// With two threads a factor large enough is computed subtree by subtree on both threads
// (tree_cholesky.cpp) instead of by CHOLMOD: the three reductions must give the one-thread
// modes to rounding (the modes' sign convention included).
TEST(TwoThreadFactorization, GivesTheOneThreadModesForEveryReduction) {
  test::HexGrid grid(16, 8, 8);  // 4 131 DOF: a factor just above the threaded path's threshold
  const auto model = preproc::build_model(grid.mesh, grid.part);
  const unsigned before = preproc::max_threads();
  for (const auto& spec : {clamped(), free_free(), craig_bampton()}) {
    SCOPED_TRACE(name(spec));
    preproc::set_max_threads(1);
    const auto one = preproc::reduce(model, preproc::assemble(model), spec);
    preproc::set_max_threads(2);
    const auto two = preproc::reduce(model, preproc::assemble(model), spec);
    preproc::set_max_threads(before);
    EXPECT_EQ(one.factor.factor_parallel_fraction, 0.0);
    EXPECT_GT(two.factor.factor_parallel_fraction, 0.0) << "factor entries " << two.factor.factor_entries;
    ASSERT_EQ(one.lambda.size(), two.lambda.size());
    for (Eigen::Index j = 0; j < one.lambda.size(); ++j) {
      EXPECT_NEAR(two.lambda[j], one.lambda[j], 1e-10 * std::abs(one.lambda[j])) << "mode " << j;
      EXPECT_LT((two.Phi.col(j) - one.Phi.col(j)).norm(), 1e-8 * one.Phi.col(j).norm()) << "mode " << j;
    }
  }
}
