// The small dense kernels of a time step against Eigen's products: the penalty tangent's
// T += Ja^T diag(w) Jb (runtime/src/joints/weighted_gram.hpp) for every row count it branches
// on (1 to 6, and more in blocks of six), blocks with a leading dimension larger than their
// rows, and zero entries; and the matrix-vector products (integrator/dense_products.hpp).
#include "integrator/dense_products.hpp"
#include "joints/weighted_gram.hpp"

#include <gtest/gtest.h>

#include <random>

TEST(WeightedGram, MatchesTheDenseProductForEveryRowCount) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Index ld = 39, ldt = 46;
  for (int rows = 1; rows <= 13; ++rows) {
    for (const auto& [na, nb] : {std::pair<int, int>{12, 22}, {22, 12}, {9, 9}, {1, 3}}) {
      Eigen::MatrixXd P(ld, 60), T0(ldt, ldt);
      for (Eigen::Index j = 0; j < P.cols(); ++j)
        for (Eigen::Index i = 0; i < ld; ++i) P(i, j) = (i + j) % 5 == 0 ? 0.0 : u(rng);  // some zeros
      for (Eigen::Index j = 0; j < T0.cols(); ++j)
        for (Eigen::Index i = 0; i < ldt; ++i) T0(i, j) = u(rng);
      Eigen::VectorXd w(rows);
      for (int r = 0; r < rows; ++r) w(r) = 1.0 + u(rng);
      const int r0 = 3, ca = 2, cb = 30, ta = 5, tb = 7;  // block offsets in P and T
      const auto Ja = P.block(r0, ca, rows, na), Jb = P.block(r0, cb, rows, nb);
      Eigen::MatrixXd T = T0;
      std::vector<double> buf(static_cast<std::size_t>(na * rows));
      ffr::runtime::detail::add_weighted_gram(&P(r0, ca), &P(r0, cb), ld, rows, na, nb, w.data(), buf.data(),
                                              &T(ta, tb), ldt);
      Eigen::MatrixXd ref = T0;
      ref.block(ta, tb, na, nb) += Ja.transpose() * w.asDiagonal() * Jb;
      EXPECT_LT((T - ref).cwiseAbs().maxCoeff(), 1e-13) << rows << " rows, " << na << " x " << nb;
    }
  }
}

// The step's matrix-vector products (runtime/src/integrator/dense_products.hpp) against
// Eigen's, for sizes with every remainder of their blocks of four and vectors with zero runs
// (whose columns the product skips).
TEST(DenseProducts, MatchEigenForEveryShape) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int m : {1, 3, 4, 5, 39, 46})
    for (int n : {1, 2, 4, 6, 7, 46}) {
      Eigen::MatrixXd A(m, n);
      for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index i = 0; i < m; ++i) A(i, j) = u(rng);
      Eigen::VectorXd x(n), lam(m), y0(m), z0(n);
      for (Eigen::Index j = 0; j < n; ++j) x(j) = j % 5 < 2 ? 0.0 : u(rng);
      for (Eigen::Index i = 0; i < m; ++i) lam(i) = u(rng), y0(i) = u(rng);
      for (Eigen::Index j = 0; j < n; ++j) z0(j) = u(rng);
      Eigen::VectorXd y = y0, z = z0;
      ffr::runtime::detail::times(A, x, y, false);
      EXPECT_LT((y - A * x).cwiseAbs().maxCoeff(), 1e-14) << m << " x " << n;
      y = y0;
      ffr::runtime::detail::times(A, x, y, true);
      EXPECT_LT((y - (y0 + A * x)).cwiseAbs().maxCoeff(), 1e-14) << m << " x " << n;
      ffr::runtime::detail::add_transpose_times(A, lam, z);
      EXPECT_LT((z - (z0 + A.transpose() * lam)).cwiseAbs().maxCoeff(), 1e-13) << m << " x " << n;
    }
}

// The leading block's products (the unknowns of a step with driven bodies eliminated): only the
// first rows and columns are read, only the first entries of the result are written.
TEST(DenseProducts, LeadingBlockOnly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int m = 39, n = 46, rows = 27, cols = 34;
  Eigen::MatrixXd A(m, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < m; ++i) A(i, j) = u(rng);
  Eigen::VectorXd x(n), lam(m);
  for (auto& v : x) v = u(rng);
  for (auto& v : lam) v = u(rng);
  Eigen::VectorXd y = Eigen::VectorXd::Constant(m, 7.0), z = Eigen::VectorXd::Constant(n, 5.0);
  ffr::runtime::detail::times(A, rows, cols, x, y, false);
  EXPECT_LT((y.head(rows) - A.topLeftCorner(rows, cols) * x.head(cols)).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_TRUE((y.tail(m - rows).array() == 7.0).all());
  ffr::runtime::detail::add_transpose_times(A, rows, cols, lam, z);
  EXPECT_LT((z.head(cols) - (Eigen::VectorXd::Constant(cols, 5.0) + A.topLeftCorner(rows, cols).transpose() * lam.head(rows)))
                .cwiseAbs()
                .maxCoeff(),
            1e-13);
  EXPECT_TRUE((z.tail(n - cols).array() == 5.0).all());
}
