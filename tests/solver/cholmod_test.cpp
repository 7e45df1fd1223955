// CholmodFactor: statistics, many-RHS solves against an independent factorization (Eigen's
// SimplicialLDLT), refusals (not positive definite with the column, singular, memory), and
// input validation.
#include "ffr/preproc/solver/cholmod_factor.hpp"
#include "ffr/preproc/solver/memory.hpp"
#include "ffr/preproc/threads.hpp"
#include "pencils.hpp"

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

using namespace ffr::preproc;
using ffr::test::Ends;

namespace {

Eigen::MatrixXd random_block(Eigen::Index n, Eigen::Index k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd B(n, k);
  for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = u(rng);
  return B;
}

// A 3D Q1 Laplacian with Dirichlet ends: SPD, 3375 DOF, fill large enough for supernodes.
SparseMatrix spd3d() { return ffr::test::box(16, 1.0, 16, 1.3, 16, 0.7, Ends::FixedFixed).K; }

// Three DOFs a node, numbered together: the vector Laplacian spd3d() (x) B3, 10 125 DOF, with a
// factor large enough for the threaded substitutions.
SparseMatrix vector_laplacian() {
  Eigen::MatrixXd b3(3, 3);
  b3 << 2.0, 0.5, 0.1, 0.5, 3.0, 0.2, 0.1, 0.2, 4.0;
  return ffr::test::kron(spd3d(), b3.sparseView());
}

// Back to the default thread count when a test that sets it ends, also on a failed ASSERT.
struct RestoreThreads {
  ~RestoreThreads() { set_max_threads(0); }
};

// A factorization of A made with `threads` threads (left as the thread count).
CholmodFactor factorized_on(unsigned threads, const SparseMatrix& A) {
  set_max_threads(threads);
  CholmodFactor f;
  f.factorize(A);
  return f;
}

}  // namespace

TEST(CholmodFactor, AnalyzeReportsStatisticsAndMetis) {
  const SparseMatrix A = spd3d();
  CholmodFactor f;
  const FactorStatistics& s = f.analyze(A);
  EXPECT_EQ(s.n, A.rows());
  // Upper triangle incl. diagonal of a symmetric matrix: (nnz + n) / 2.
  EXPECT_EQ(s.nnz_A, (A.nonZeros() + A.rows()) / 2);
  EXPECT_EQ(s.ordering, "METIS");
  EXPECT_EQ(s.ordering_vertices, s.n);  // one DOF a node: CHOLMOD's own METIS call on the matrix graph
  // nnz(L) at least the lower triangle of A, and supernodal storage holds at least nnz(L).
  EXPECT_GE(s.nnz_L, static_cast<double>(s.nnz_A));
  EXPECT_GE(static_cast<double>(s.factor_entries), s.nnz_L);
  EXPECT_GT(s.flops, s.nnz_L);
  EXPECT_GE(s.factor_bytes, 8u * static_cast<std::uint64_t>(s.factor_entries));
  EXPECT_GT(s.peak_bytes, s.factor_bytes);
  EXPECT_EQ(f.info().status, FactorStatus::Analyzed);
  EXPECT_FALSE(f.factorized());
}

TEST(CholmodFactor, ManyRightHandSidesMatchSimplicialLDLT) {
  const SparseMatrix A = spd3d();
  CholmodFactor f;
  f.factorize(A);
  ASSERT_TRUE(f.factorized());
  EXPECT_GT(f.info().stats.rcond, 0.0);
  const Eigen::MatrixXd B = random_block(A.rows(), 70, 1);  // several 16-column blocks
  const Eigen::MatrixXd X = f.solve(B);
  // Independent oracle: Eigen's own sparse LDL^T (AMD ordering, simplicial).
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::MatrixXd Xref = ldlt.solve(B);
  EXPECT_LT((X - Xref).norm() / Xref.norm(), 1e-12);
  // And the residual itself.
  EXPECT_LT((A * X - B).norm() / B.norm(), 1e-12);
  // Single-vector path, in place.
  Eigen::VectorXd x = B.col(5);
  f.solve(x.data(), x.data());
  EXPECT_LT((x - Xref.col(5)).norm() / Xref.col(5).norm(), 1e-12);
}

// The substitutions run in interleaved blocks of 16, 8, 4 (the last two or three columns padded)
// and 1 column: every count up to 37 against Eigen's SimplicialLDLT, with the right-hand sides
// read through a leading dimension larger than n, and with the natural ordering (no fill-reducing
// permutation) as well as METIS.
TEST(CholmodFactor, EveryBlockWidthMatchesSimplicialLDLT) {
  const SparseMatrix A = spd3d();
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::Index n = A.rows();
  const Eigen::MatrixXd Bbig = random_block(n + 7, 40, 3);
  for (const Ordering ordering : {Ordering::Metis, Ordering::Natural}) {
    FactorOptions o;
    o.ordering = ordering;
    CholmodFactor f(o);
    f.factorize(A);
    ASSERT_TRUE(f.factorized());
    for (Eigen::Index k = 1; k <= 37; ++k) {
      const auto B = Bbig.block(2, 1, n, k);  // outer stride n + 7
      const Eigen::MatrixXd X = f.solve(B);
      const Eigen::MatrixXd Xref = ldlt.solve(Eigen::MatrixXd(B));
      EXPECT_LT((X - Xref).norm() / Xref.norm(), 1e-12) << k << " columns, " << to_string(ordering);
    }
  }
}

// With two threads the substitutions split the elimination tree (solve_schedule.hpp): subtrees
// on each thread, the separators near the root on one. The vector Laplacian's factor is large
// enough for it; the solution must be the serial one up to the summation order.
TEST(CholmodFactor, ThreadedSubstitutionsMatchTheSerialOnes) {
  const SparseMatrix A = vector_laplacian();
  const Eigen::MatrixXd B = random_block(A.rows(), 21, 5);  // widths 16, 4 and 1
  const RestoreThreads restore;
  const CholmodFactor serial = factorized_on(1, A);
  ASSERT_EQ(serial.info().stats.solve_threads, 1);
  const CholmodFactor threaded = factorized_on(2, A);
  ASSERT_EQ(threaded.info().stats.solve_threads, 2) << "factor entries " << threaded.info().stats.factor_entries;
  const Eigen::MatrixXd X = serial.solve(B), Xt = threaded.solve(B);
  EXPECT_LT((Xt - X).norm() / X.norm(), 1e-13);
  EXPECT_LT((A * Xt - B).norm() / B.norm(), 1e-12);
  Eigen::VectorXd x = B.col(20);
  threaded.solve(x.data(), x.data());
  EXPECT_LT((x - X.col(20)).norm() / X.col(20).norm(), 1e-13);
}

// The supernodal backend (tree_cholesky.cpp) on CHOLMOD's analysis: on two threads the
// elimination tree's subtrees run on separate threads, on one thread it goes in order.
// CHOLMOD's own factorization and solve (the cholmod backend) is the reference: the factors differ by
// rounding only, so the solutions agree to it. The top separators' updates of this matrix
// exceed tree_cholesky's 2^18-value buffer, so their blocked computation is covered too; and
// every factor is packed for the substitutions (factor_packing.hpp), keeping at least nnz(L)
// and fewer than CHOLMOD's stored values.
TEST(CholmodFactor, OwnFactorizationMatchesCholmodsOnOneAndTwoThreads) {
  const SparseMatrix A = vector_laplacian();
  const Eigen::MatrixXd B = random_block(A.rows(), 5, 9);
  const RestoreThreads restore;
  FactorOptions reference_options;
  reference_options.backend = FactorizationBackend::Cholmod;
  CholmodFactor reference(reference_options);
  set_max_threads(1);
  reference.factorize(A);
  ASSERT_EQ(reference.info().stats.backend, FactorizationBackend::Cholmod);
  ASSERT_EQ(reference.info().stats.factor_parallel_fraction, 0.0);
  CholmodFactor serial = factorized_on(1, A);
  ASSERT_EQ(serial.info().stats.backend, FactorizationBackend::Supernodal);
  ASSERT_EQ(serial.info().stats.factor_parallel_fraction, 0.0);
  // Its workspace estimate has no permuted copy of A: below CHOLMOD's, above the factor alone.
  EXPECT_GT(serial.info().stats.peak_bytes, serial.info().stats.factor_bytes);
  EXPECT_LT(serial.info().stats.peak_bytes, reference.info().stats.peak_bytes);
  CholmodFactor tree = factorized_on(2, A);
  ASSERT_EQ(tree.info().stats.backend, FactorizationBackend::Supernodal);
  ASSERT_GT(tree.info().stats.factor_parallel_fraction, 1.0 / 3) << "factor entries " << tree.info().stats.factor_entries;
  EXPECT_EQ(tree.info().stats.analyses, 1);
  const Eigen::MatrixXd X = reference.solve(B);
  for (const CholmodFactor* f : {&serial, &tree}) {
    const Eigen::MatrixXd Xo = f->solve(B);
    EXPECT_LT((Xo - X).norm() / X.norm(), 1e-13);
    EXPECT_LT((A * Xo - B).norm() / B.norm(), 1e-12);
    EXPECT_NEAR(f->info().stats.rcond, reference.info().stats.rcond, 1e-12 * reference.info().stats.rcond);
    const FactorStatistics& s = f->info().stats;
    EXPECT_GE(static_cast<double>(s.packed_entries), s.nnz_L);
    EXPECT_LT(s.packed_entries, s.factor_entries);
  }

  // A second factorization on the same analysis (the shifted matrix of an eigen-solve).
  SparseMatrix A2 = A;
  for (Eigen::Index i = 0; i < A2.rows(); ++i) A2.coeffRef(i, i) *= 1.5;
  tree.factorize(A2);  // still on two threads
  set_max_threads(1);
  serial.factorize(A2);
  reference.factorize(A2);
  EXPECT_EQ(serial.info().stats.factor_parallel_fraction, 0.0);
  EXPECT_GT(tree.info().stats.factor_parallel_fraction, 0.0);
  EXPECT_EQ(tree.info().stats.analyses, 1);
  const Eigen::MatrixXd X2 = reference.solve(B);
  EXPECT_LT((tree.solve(B) - X2).norm() / X2.norm(), 1e-13);
  EXPECT_LT((serial.solve(B) - X2).norm() / X2.norm(), 1e-13);
  EXPECT_GT((X2 - X).norm() / X.norm(), 1e-3);  // the second matrix is another one

  // The cholmod backend leaves the factorization to CHOLMOD, also on two threads.
  set_max_threads(2);
  CholmodFactor cholmod(reference_options);
  cholmod.factorize(A);
  EXPECT_EQ(cholmod.info().stats.backend, FactorizationBackend::Cholmod);
  EXPECT_LT((cholmod.solve(B) - X).norm() / X.norm(), 1e-13);
  EXPECT_EQ(cholmod.info().stats.factor_parallel_fraction, 0.0);
}

// A failing pivot inside the subtrees is reported with the column CHOLMOD reports: the
// first in the elimination order. Two large negative entries keep every leading minor positive
// until their DOFs are eliminated; far apart, they fall in different subtrees, and each thread
// stops at its own.
// The supernodal factorization with each of its dense kernels (dense_kernels.hpp: the BLAS's and
// Eigen's for this CPU), on one thread and on two (subtrees, the top's split supernodes):
// solutions within rounding of CHOLMOD's own factorization (the reference), and an indefinite
// matrix's failing column the one CHOLMOD names.
TEST(CholmodFactor, EachDenseKernelsFactorizeAsCholmod) {
  SparseMatrix A = vector_laplacian();
  const Eigen::MatrixXd B = random_block(A.rows(), 4, 17);
  const RestoreThreads restore;
  FactorOptions reference_options;
  reference_options.backend = FactorizationBackend::Cholmod;
  set_max_threads(1);
  CholmodFactor reference(reference_options);
  reference.factorize(A);
  EXPECT_EQ(reference.info().stats.dense_kernels, "BLAS");
  const Eigen::MatrixXd X = reference.solve(B);
  SparseMatrix indefinite = A;
  indefinite.coeffRef(A.rows() - 40, A.rows() - 40) = -1e6;
  std::int64_t reference_column = -1;
  try {
    CholmodFactor(reference_options).factorize(indefinite);
  } catch (const NotPositiveDefiniteError& e) {
    reference_column = e.column;
  }
  ASSERT_GE(reference_column, 0);
  for (const DenseKernelChoice choice : {DenseKernelChoice::Blas, DenseKernelChoice::Eigen}) {
    for (const unsigned threads : {1u, 2u}) {
      set_max_threads(threads);
      FactorOptions options;
      options.dense_kernels = choice;
      CholmodFactor f(options);
      f.factorize(A);
      const std::string name = f.info().stats.dense_kernels;
      EXPECT_EQ(name.rfind(choice == DenseKernelChoice::Blas ? "BLAS" : "Eigen (", 0), 0u) << name;
      if (threads == 2) {
        EXPECT_GT(f.info().stats.factor_parallel_fraction, 0.0);
      }
      const Eigen::MatrixXd Xo = f.solve(B);
      EXPECT_LT((Xo - X).norm() / X.norm(), 1e-13) << name << ", " << threads << " threads";
      EXPECT_LT((A * Xo - B).norm() / B.norm(), 1e-12) << name << ", " << threads << " threads";
      std::int64_t column = -1;
      try {
        CholmodFactor(options).factorize(indefinite);
      } catch (const NotPositiveDefiniteError& e) {
        column = e.column;
      }
      EXPECT_EQ(column, reference_column) << name << ", " << threads << " threads";
    }
  }
}

TEST(CholmodFactor, IndefiniteMatrixNamesTheColumnOnTwoThreads) {
  SparseMatrix A = vector_laplacian();
  const Eigen::Index far = A.rows() - 40;
  A.coeffRef(37, 37) = -1e6;
  A.coeffRef(far, far) = -1e6;
  const RestoreThreads restore;
  auto failing_column = [&](unsigned threads, double* share) -> std::int64_t {
    set_max_threads(threads);
    CholmodFactor f;
    try {
      f.factorize(A);
    } catch (const NotPositiveDefiniteError& e) {
      EXPECT_FALSE(e.numerically_singular);
      EXPECT_FALSE(f.factorized());
      *share = f.info().stats.factor_parallel_fraction;
      return e.column;
    }
    ADD_FAILURE() << "indefinite matrix accepted on " << threads << " thread(s)";
    return -1;
  };
  double share1 = 0, share2 = 0;
  const std::int64_t cholmod = failing_column(1, &share1), tree = failing_column(2, &share2);
  EXPECT_TRUE(cholmod == 37 || cholmod == far) << cholmod;
  EXPECT_EQ(tree, cholmod);
  EXPECT_EQ(share1, 0.0);
  EXPECT_GT(share2, 0.0);
}

// A failing pivot in the top separator, whose supernodes the two threads share (tree_cholesky's
// top_node: the blocked Cholesky of the supernode split over the threads), is reported with
// the column of the one-thread factorization. The column is found by probing: a large
// negative diagonal entry makes the factorization fail exactly where its column is eliminated,
// so the reported permuted column tells where each probed column sits; the lines through the
// box's centre cross the separator planes.
TEST(CholmodFactor, IndefiniteTopSeparatorNamesTheColumnOnTwoThreads) {
  const SparseMatrix A0 = vector_laplacian();
  const Eigen::Index n = A0.rows(), m = 15;  // 15^3 nodes, three DOFs each
  const RestoreThreads restore;
  struct Failure {
    std::int64_t column = -1, permuted = -1;
  };
  auto fail_at = [&](Eigen::Index j, unsigned threads) {
    SparseMatrix A = A0;
    A.coeffRef(j, j) = -1e6;
    set_max_threads(threads);
    CholmodFactor f;
    Failure out;
    try {
      f.factorize(A);
    } catch (const NotPositiveDefiniteError& e) {
      out = {e.column, e.permuted_column};
    }
    return out;
  };
  Eigen::Index chosen = -1;
  Failure serial;
  for (Eigen::Index step = 0; step < m && chosen < 0; ++step)
    for (const Eigen::Index node : {step + m * (7 + m * 7), 7 + m * (step + m * 7), 7 + m * (7 + m * step)}) {
      const Failure f = fail_at(3 * node, 1);
      ASSERT_EQ(f.column, 3 * node);
      if (f.permuted >= n - 200) {  // in the last columns: the root separator
        chosen = 3 * node;
        serial = f;
        break;
      }
    }
  ASSERT_GE(chosen, 0) << "no probed column in the top separator";
  const Failure two = fail_at(chosen, 2);
  EXPECT_EQ(two.column, serial.column);
  EXPECT_EQ(two.permuted, serial.permuted);
}

// Three DOFs a node, numbered together (a vector Laplacian S (x) B3): METIS orders the node
// graph, a third of the columns; the factor must be as sparse as CHOLMOD's own nested
// dissection of the DOF graph makes it, and solve.
TEST(CholmodFactor, OrdersTheNodeGraphOfAVectorProblem) {
  const SparseMatrix A = vector_laplacian();
  CholmodFactor f;
  const FactorStatistics s = f.analyze(A);
  EXPECT_EQ(s.ordering, "METIS");
  EXPECT_EQ(s.ordering_vertices, A.rows() / 3);
  FactorOptions o;
  o.ordering = Ordering::Nesdis;
  CholmodFactor g(o);
  const FactorStatistics sg = g.analyze(A);
  EXPECT_EQ(sg.ordering_vertices, A.rows());
  EXPECT_LT(s.nnz_L, 1.15 * sg.nnz_L) << "nodal METIS " << s.nnz_L << ", NESDIS " << sg.nnz_L;
  f.factorize(A);
  const Eigen::MatrixXd B = random_block(A.rows(), 3, 4);
  EXPECT_LT((A * f.solve(B) - B).norm() / B.norm(), 1e-12);
  // Upper-only storage of the same matrix gives the same node graph.
  CholmodFactor u;
  EXPECT_EQ(u.analyze(ffr::test::upper(A)).ordering_vertices, A.rows() / 3);
}

// Products with an upper-only matrix split its columns over the threads (above 2^18 stored
// entries), each part after the first into its own buffer. Every chunk width (16, 8, 4 and the
// dynamic rest) against the product with the full matrix, on one and on two threads.
TEST(SymMultiply, UpperOnlyOnTwoThreadsMatchesTheFullProduct) {
  const SparseMatrix A = vector_laplacian();
  const SparseMatrix U = ffr::test::upper(A);
  ASSERT_GT(U.nonZeros(), 1 << 18);
  const Eigen::MatrixXd X = random_block(A.rows(), 31, 6);
  const Eigen::MatrixXd ref = A * X;
  const RestoreThreads restore;
  for (const unsigned threads : {1u, 2u}) {
    set_max_threads(threads);
    const Eigen::MatrixXd Y = sym_multiply(U, SymmetricStorage::UpperOnly, X);
    EXPECT_LT((Y - ref).norm() / ref.norm(), 1e-14) << threads << " threads";
  }
}

TEST(CholmodFactor, UpperOnlyStorageGivesTheSameSolution) {
  const SparseMatrix A = spd3d();
  CholmodFactor full, up;
  full.factorize(A);
  up.factorize(ffr::test::upper(A));
  const Eigen::MatrixXd B = random_block(A.rows(), 3, 2);
  EXPECT_LT((full.solve(B) - up.solve(B)).norm() / full.solve(B).norm(), 1e-14);
}

TEST(CholmodFactor, RefactorizationReusesAnalysisAndShiftedMatchesExplicit) {
  const auto p = ffr::test::box(12, 1.0, 10, 1.0, 8, 1.0, Ends::FixedFixed);
  CholmodFactor f;
  f.factorize_shifted(p.K, p.M, -3.0);
  const double t_analyze = f.info().stats.analyze_seconds;
  EXPECT_DOUBLE_EQ(f.info().shift, -3.0);
  const Eigen::MatrixXd B = random_block(p.K.rows(), 4, 3);
  const SparseMatrix C = p.K + 3.0 * p.M;  // the explicit sum, by Eigen
  EXPECT_LT((C * f.solve(B) - B).norm() / B.norm(), 1e-12);
  // The merged upper triangle equals Eigen's upper triangle of K + 3 M entry by entry.
  EXPECT_LT((SparseMatrix(shifted_upper(p.K, p.M, -3.0)) - ffr::test::upper(C)).norm(),
            1e-14 * C.norm());
  // Same pattern, new shift: no new analysis (the recorded analysis time is unchanged).
  EXPECT_EQ(f.info().stats.analyses, 1);
  f.factorize_shifted(p.K, p.M, -5.0);
  EXPECT_EQ(f.info().stats.analyze_seconds, t_analyze);
  EXPECT_EQ(f.info().stats.analyses, 1);
  const SparseMatrix C5 = p.K + 5.0 * p.M;
  EXPECT_LT((C5 * f.solve(B) - B).norm() / B.norm(), 1e-12);
  // Another structure (the diagonal alone) is analysed anew: what a factor analysed before
  // the assembly (EarlyAnalysis) relies on when its matrix is not the one it expected.
  SparseMatrix D(p.K.rows(), p.K.cols());
  D.setIdentity();
  f.factorize(D);
  EXPECT_EQ(f.info().stats.analyses, 2);
  EXPECT_LT((f.solve(B) - B).norm() / B.norm(), 1e-15);
}

TEST(CholmodFactor, IndefiniteMatrixNamesTheColumn) {
  // SPD rod stiffness plus a large negative diagonal entry at DOF 37: the leading minors
  // stay positive in any elimination order until DOF 37 is eliminated, so the failing pivot
  // is DOF 37 whatever the ordering.
  auto p = ffr::test::rod(100, 1.0, Ends::FixedFixed);
  SparseMatrix A = p.K;
  A.coeffRef(37, 37) = -1e6;
  CholmodFactor f;
  try {
    f.factorize(A);
    FAIL() << "indefinite matrix accepted";
  } catch (const NotPositiveDefiniteError& e) {
    EXPECT_EQ(e.column, 37);
    EXPECT_FALSE(e.numerically_singular);
    EXPECT_NE(std::string(e.what()).find("column 37"), std::string::npos) << e.what();
  }
  EXPECT_EQ(f.info().status, FactorStatus::Failed);
  EXPECT_FALSE(f.factorized());
  EXPECT_THROW(f.solve(Eigen::MatrixXd::Ones(A.rows(), 1)), std::logic_error);
}

TEST(CholmodFactor, SingularStiffnessOfAFreeBodyIsRefused) {
  // Free-free rod: K has the rigid translation in its null space.
  const auto p = ffr::test::rod(200, 1.0, Ends::FreeFree, 2.1e11, 7850.0);
  CholmodFactor f;
  try {
    f.factorize(p.K);
    FAIL() << "singular matrix accepted, rcond = " << f.info().stats.rcond;
  } catch (const NotPositiveDefiniteError& e) {
    EXPECT_GE(e.column, 0);
    EXPECT_LT(e.column, p.K.rows());
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos);
  }
  // A free 3D Q1 Laplacian (Neumann box): every pivot comes out positive by rounding
  // (pivot ratio ~1e-12), so only the MAXRATIO-style test catches it.
  const auto b = ffr::test::box(20, 1.0, 20, 1.0, 20, 1.0, Ends::FreeFree);
  try {
    f.factorize(b.K);
    FAIL() << "singular box accepted, pivot ratio " << f.info().stats.min_pivot_ratio;
  } catch (const NotPositiveDefiniteError& e) {
    EXPECT_TRUE(e.numerically_singular) << e.what();
    EXPECT_NE(std::string(e.what()).find("numerically singular"), std::string::npos);
  }
  FactorOptions lax;
  lax.min_pivot_ratio = 0;  // check disabled: the same matrix goes through
  CholmodFactor g(lax);
  EXPECT_NO_THROW(g.factorize(b.K));
  EXPECT_LT(g.info().stats.min_pivot_ratio, 1e-10);
  // A clamped rod of the same material is accepted.
  const auto q = ffr::test::rod(200, 1.0, Ends::FixedFree, 2.1e11, 7850.0);
  EXPECT_NO_THROW(f.factorize(q.K));
}

TEST(CholmodFactor, RefusesWhenTheFactorWouldNotFitWithTheNumbers) {
  const SparseMatrix A = spd3d();
  FactorOptions o;
  o.memory_limit_bytes = 4096;
  CholmodFactor f(o);
  const auto& s = f.analyze(A);
  try {
    f.factorize(A);
    FAIL() << "factorization above the memory limit was not refused";
  } catch (const InsufficientMemoryError& e) {
    EXPECT_EQ(e.available_bytes, 4096u);
    EXPECT_EQ(e.needed_bytes, s.peak_bytes);
    const std::string w = e.what();
    EXPECT_NE(w.find(std::to_string(s.peak_bytes)), std::string::npos) << w;
    EXPECT_NE(w.find("4096"), std::string::npos) << w;
  }
  EXPECT_FALSE(f.factorized());
}

TEST(CholmodFactor, BadInputIsRejectedWithAMessage) {
  CholmodFactor f;
  SparseMatrix rect(3, 4);
  EXPECT_THROW(f.factorize(rect), std::invalid_argument);
  auto p = ffr::test::rod(10, 1.0, Ends::FixedFixed);
  SparseMatrix asym = p.K;
  asym.coeffRef(2, 3) += 1e-3;
  try {
    f.factorize(asym);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not symmetric"), std::string::npos) << e.what();
  }
  SparseMatrix nan = p.K;
  nan.coeffRef(4, 4) = std::nan("");
  EXPECT_THROW(f.factorize(nan), std::invalid_argument);
  SparseMatrix lower = SparseMatrix(p.K.triangularView<Eigen::Lower>());
  EXPECT_THROW(f.factorize(lower), std::invalid_argument);
}

TEST(Memory, ReadsMeminfoAndRss) {
  const auto a = available_memory_bytes();
  ASSERT_TRUE(a.has_value());
  EXPECT_GT(*a, 0u);
  EXPECT_GT(peak_rss_bytes(), 0u);
  EXPECT_GE(peak_rss_bytes(), current_rss_bytes() / 2);
  EXPECT_EQ(format_bytes(512), "512 B");
  EXPECT_EQ(format_bytes(3u << 20), "3.00 MiB");
}

namespace {
long threads_of_this_process() {
  long n = 0;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/self/task", ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec))
    ++n;
  return n;
}
}  // namespace

// The default (supernodal) backend leaves no threads behind: its subtrees run on threads that are
// joined before factorize returns, and it never enters CHOLMOD's numeric factorization, whose
// OpenMP regions (a compiled-in 4 threads in Debian's CHOLMOD) would start a pool that stays. The
// cholmod backend's OpenMP is the host program's to limit (ffr-reduce's main() keeps it
// inactive); the library does not touch it.
TEST(CholmodFactor, FactorizationStartsNoThreadsOfItsOwn) {
  const SparseMatrix A = ffr::test::box(30, 1.0, 30, 1.3, 30, 0.7, Ends::FixedFixed).K;
  const long before = threads_of_this_process();
  ASSERT_GE(before, 1);
  CholmodFactor f;
  f.factorize(A);
  ASSERT_TRUE(f.factorized());
  EXPECT_EQ(threads_of_this_process(), before);
}
