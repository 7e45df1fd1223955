// The eigen-solve's symbolic analysis started before the assembly (EarlyAnalysis) against the
// one made afterwards from the assembled K and M: the same factor structure, no second
// analysis at the factorization, and bit for bit the same modes, for a clamped (rigid spider
// held), a free-free and a Craig-Bampton reduction. It starts with two threads only; bad input
// reaches the reduction as before. Also on two threads: the factorization by subtrees gives
// the one-thread modes for the three reductions.
#include "ffr/formats/h5.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/reduce/reduction.hpp"
#include "ffr/preproc/threads.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace ffr;

namespace {

// Two threads for the test (EarlyAnalysis starts only with two or more), restored after it.
struct TwoThreads {
  unsigned before = preproc::max_threads();
  TwoThreads() { preproc::set_max_threads(2); }
  ~TwoThreads() { preproc::set_max_threads(before); }
};

preproc::ReductionSpec clamped() {
  preproc::ReductionSpec s;
  s.method = preproc::ReductionSpec::Method::Clamped;
  s.interface = "L";
  s.modes = 6;
  return s;
}

preproc::ReductionSpec free_free() {
  preproc::ReductionSpec s;
  s.method = preproc::ReductionSpec::Method::Free;
  s.modes = 6;
  return s;
}

preproc::ReductionSpec craig_bampton() {
  preproc::ReductionSpec s;
  s.method = preproc::ReductionSpec::Method::CraigBampton;
  s.interfaces = {"L", "R"};
  s.frame = "L";
  s.modes = 6;
  return s;
}

const char* name(const preproc::ReductionSpec& s) {
  switch (s.method) {
    case preproc::ReductionSpec::Method::Free: return "free";
    case preproc::ReductionSpec::Method::Clamped: return "clamped";
    case preproc::ReductionSpec::Method::CraigBampton: return "craig-bampton";
  }
  return "?";
}

}  // namespace

TEST(EarlyAnalysis, GivesTheSameFactorAndModesWithoutAnalysingAgain) {
  TwoThreads two;
  test::HexGrid grid(12, 4, 3);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  for (const auto& spec : {clamped(), free_free(), craig_bampton()}) {
    SCOPED_TRACE(name(spec));
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
