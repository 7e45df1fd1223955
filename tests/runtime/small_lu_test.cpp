// SmallLU (the runtime's tangent factorisation) against Eigen's full-pivoting LU as the
// independent oracle, on dense, block-sparse and pivot-forcing matrices.
#include "ffr/runtime/small_lu.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd random_matrix(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixXd A(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) A(i, j) = u(rng);
  return A;
}

// Relative difference of SmallLU's solution from FullPivLU's for a few right-hand sides.
double solve_difference(const MatrixXd& A, std::mt19937& rng) {
  ffr::runtime::SmallLU lu(A.rows());
  EXPECT_TRUE(lu.compute(A));
  EXPECT_TRUE(lu.ok());
  const Eigen::FullPivLU<MatrixXd> ref(A);
  double worst = 0;
  for (int k = 0; k < 3; ++k) {
    const VectorXd b = random_matrix(static_cast<int>(A.rows()), rng).col(0);
    VectorXd x = b;
    lu.solve_in_place(x);
    const VectorXd y = ref.solve(b);
    worst = std::max(worst, (x - y).norm() / y.norm());
  }
  return worst;
}

TEST(SmallLU, DenseMatchesFullPivoting) {
  std::mt19937 rng(7);
  // Random dense matrices are well conditioned enough for 1e-10 (cond ~ n^2 at worst). The
  // sizes cover the substitutions' blocks of four columns with every remainder.
  for (int n : {1, 2, 3, 4, 5, 6, 7, 8, 9, 46}) EXPECT_LT(solve_difference(random_matrix(n, rng), rng), 1e-10) << "n = " << n;
}

TEST(SmallLU, BlockSparseTangentPatternMatchesFullPivoting) {
  // Three "bodies" of 12, 22 and 12 coordinates coupled in a chain, as the slider-crank's
  // tangent: the zero blocks are what the elimination skips.
  std::mt19937 rng(11);
  MatrixXd A = random_matrix(46, rng);
  A.block(0, 34, 12, 12).setZero();
  A.block(34, 0, 12, 12).setZero();
  A.diagonal().array() += 4.0;
  EXPECT_LT(solve_difference(A, rng), 1e-12);
}

TEST(SmallLU, ChainOfBodiesMatchesFullPivoting) {
  // Seventeen "bodies" of 12 coordinates, each coupled to the next (a geometrically exact
  // beam's node bodies, a chain of links): a block band, most of the matrix outside the
  // envelope the elimination follows. Weak diagonals force row swaps inside the band and fill
  // beyond the blocks; a second matrix also couples the first body with the last (a closed loop:
  // one long row and column of blocks, the envelope spanning the matrix).
  std::mt19937 rng(17);
  const int nb = 17, b = 12, n = nb * b;
  MatrixXd A = MatrixXd::Zero(n, n);
  for (int k = 0; k < nb; ++k) {
    A.block(k * b, k * b, b, b) = random_matrix(b, rng);
    if (k + 1 < nb) {
      A.block(k * b, (k + 1) * b, b, b) = random_matrix(b, rng);
      A.block((k + 1) * b, k * b, b, b) = random_matrix(b, rng);
    }
  }
  for (int i = 0; i < n; i += 5) A(i, i) = 0.0;  // pivots from further down
  EXPECT_LT(solve_difference(A, rng), 1e-9);
  A.block(0, (nb - 1) * b, b, b) = random_matrix(b, rng);
  A.block((nb - 1) * b, 0, b, b) = random_matrix(b, rng);
  EXPECT_LT(solve_difference(A, rng), 1e-9);
}

TEST(SmallLU, ZeroDiagonalNeedsPivotingFromBelowTheZeros) {
  // Column 0 is zero except in its last row: the pivot comes from the bottom, and the row swap
  // moves nonzeros below other columns' last nonzeros.
  std::mt19937 rng(3);
  const int n = 8;
  MatrixXd A = MatrixXd::Zero(n, n);
  A(n - 1, 0) = 2.0;
  for (int i = 1; i < n; ++i) A(i - 1, i) = 1.0 + i;  // superdiagonal
  A(0, 0) = 0.0;
  A(2, 5) = -3.0;
  A(6, 3) = 0.5;
  EXPECT_LT(solve_difference(A, rng), 1e-14);
}

TEST(SmallLU, TiedPivotCandidatesMatchFullPivoting) {
  // Entries of equal magnitude (+-1) tie in every pivot search, in each of the search's four
  // running maxima; sizes with every remainder of the four-column panels.
  std::mt19937 rng(5);
  std::bernoulli_distribution coin(0.5);
  for (int n : {5, 6, 7, 13, 46}) {
    MatrixXd A(n, n);
    do {  // small sign matrices are often singular: draw until this one is not
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) A(i, j) = coin(rng) ? 1.0 : -1.0;
    } while (Eigen::FullPivLU<MatrixXd>(A).rank() < n);
    EXPECT_LT(solve_difference(A, rng), 1e-9) << "n = " << n;
  }
}

TEST(SmallLU, SingularMatrixIsReportedNotSolved) {
  MatrixXd A = MatrixXd::Identity(4, 4);
  A(2, 2) = 0.0;  // column 2 zero on and below the diagonal after elimination
  ffr::runtime::SmallLU lu(4);
  EXPECT_FALSE(lu.compute(A));
  EXPECT_FALSE(lu.ok());
  A(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(lu.compute(A));
}

}  // namespace

// Buffers for 46 x 46 factorise smaller matrices too (the step's tangent once driven bodies are
// eliminated, after the initial conditions' whole one), and only the first entries of x change.
TEST(SmallLU, SmallerMatricesInTheSameBuffers) {
  std::mt19937 rng(21);
  ffr::runtime::SmallLU lu(46);
  for (const int n : {46, 34, 5, 46}) {
    const MatrixXd A = random_matrix(n, rng) + n * MatrixXd::Identity(n, n);
    ASSERT_TRUE(lu.compute(A));
    EXPECT_EQ(lu.size(), n);
    VectorXd x = VectorXd::Constant(46, 3.0);
    const VectorXd b = x.head(n);
    lu.solve_in_place(x);
    EXPECT_LT((A * x.head(n) - b).norm(), 1e-12 * b.norm()) << n;
    EXPECT_TRUE((x.tail(46 - n).array() == 3.0).all()) << n;
  }
}

// compute_within (a banded tangent's spans given, the buffer cleared only where the last factors
// reached outside them) against compute on the same matrices: the same factors bit for bit, so
// the same solutions. A sequence in one object: banded matrices with weak diagonals (row swaps
// widen the factors beyond the band, which the next factorisation must clear), spans that
// change between calls, a failed factorisation and one of another size in between (after
// which the buffer is cleared whole).
TEST(SmallLU, WithinSpansGivesTheSameFactorsAsWhole) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 60;
  ffr::runtime::SmallLU within(n), whole(n);
  const auto banded = [&](int half, std::vector<int>& first, std::vector<int>& last) {
    MatrixXd A = MatrixXd::Zero(n, n);
    first.assign(n, 0);
    last.assign(n, 0);
    for (int j = 0; j < n; ++j) {
      first[j] = std::max(0, j - half);
      last[j] = std::min(n - 1, j + half);
      for (int i = first[j]; i <= last[j]; ++i) A(i, j) = u(rng);
      if (j % 4 == 0) A(j, j) = 0.0;  // pivots from below
    }
    return A;
  };
  const auto check = [&](const MatrixXd& A, const std::vector<int>& first, const std::vector<int>& last) {
    ASSERT_TRUE(whole.compute(A));
    ASSERT_TRUE(within.compute_within(n, first.data(), last.data(), [&](ffr::runtime::SmallLU::MatrixMap& a) {
      for (int j = 0; j < n; ++j)
        for (int i = first[j]; i <= last[j]; ++i) a(i, j) = A(i, j);
    }));
    VectorXd b(n);
    for (int i = 0; i < n; ++i) b(i) = u(rng);
    VectorXd x = b, y = b;
    within.solve_in_place(x);
    whole.solve_in_place(y);
    EXPECT_TRUE((x.array() == y.array()).all());
    EXPECT_LT((A * x - b).norm(), 1e-8 * b.norm());
  };
  std::vector<int> first, last;
  for (const int half : {7, 7, 2, 11, 5}) {
    const MatrixXd A = banded(half, first, last);
    check(A, first, last);
  }
  // A failed factorisation, then one of another size, then the band again.
  MatrixXd S = banded(3, first, last);
  S.col(10).setZero();
  EXPECT_FALSE(within.compute_within(n, first.data(), last.data(), [&](ffr::runtime::SmallLU::MatrixMap& a) {
    for (int j = 0; j < n; ++j)
      for (int i = first[j]; i <= last[j]; ++i) a(i, j) = S(i, j);
  }));
  check(banded(6, first, last), first, last);
  ASSERT_TRUE(within.compute(random_matrix(20, rng) + 20 * MatrixXd::Identity(20, 20)));
  check(banded(4, first, last), first, last);
}
