// The penalty tangent's kernel T += Ja^T diag(w) Jb (runtime/src/joints/weighted_gram.hpp)
// against Eigen's dense product, for every row count it branches on (1 to 6, and more in
// blocks of six), blocks with a leading dimension larger than their rows, and zero entries.
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
