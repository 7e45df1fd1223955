// The private kernels under the eigen-solver and the mesh import, against independent
// references: Eigen's dense products for the tall-skinny products of the block Gram-Schmidt,
// and the Z-order by hand for the node numbering.
#include "mesh/node_order.hpp"
#include "solver/eigen_backends.hpp"
#include "solver/tall_skinny.hpp"
#include "ffr/preproc/threads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using ffr::preproc::Index;

namespace {

Eigen::MatrixXd random_matrix(Index rows, Index cols, unsigned seed) {
  std::srand(seed);
  return Eigen::MatrixXd::Random(rows, cols);
}

}  // namespace

// Basis widths k and block widths p of 1 to 11, row ranges that start and end anywhere, Q and
// V with leading dimensions larger than their row count (blocks of a bigger matrix): the
// products of a row range (dgemm on offset operands) against Eigen's.
TEST(TallSkinny, MatchesEigenProductsForEveryShape) {
  const Index n = 2600, ld = 2611;
  for (const Index k : {1, 3, 4, 5, 8, 11}) {
    for (const Index p : {1, 3, 4, 5, 9}) {
      for (const auto& [r0, r1] : {std::pair<Index, Index>{0, n}, {7, 2301}, {1030, 1033}}) {
        const Eigen::MatrixXd Qs = random_matrix(ld, k, 11), Vs = random_matrix(ld, p, 12);
        const auto Q = Qs.topRows(n);
        Eigen::MatrixXd C0 = random_matrix(k, p, 13);

        Eigen::MatrixXd C = C0;
        ffr::preproc::detail::add_transposed_product(Qs.data(), ld, k, Vs.data(), ld, p, r0, r1, C.data());
        const Eigen::MatrixXd C_ref = C0 + Q.middleRows(r0, r1 - r0).transpose() * Vs.middleRows(r0, r1 - r0);
        EXPECT_LT((C - C_ref).norm(), 1e-13 * C_ref.norm()) << "k " << k << " p " << p << " rows " << r0 << ".." << r1;

        Eigen::MatrixXd V = Vs;
        ffr::preproc::detail::subtract_product(Qs.data(), ld, k, C0.data(), p, r0, r1, V.data(), ld);
        Eigen::MatrixXd V_ref = Vs;
        V_ref.middleRows(r0, r1 - r0) -= Q.middleRows(r0, r1 - r0) * C0;
        EXPECT_LT((V - V_ref).norm(), 1e-13 * V_ref.norm()) << "k " << k << " p " << p << " rows " << r0 << ".." << r1;
      }
    }
  }
}

// The row-parallel helpers (the Gram matrices, the triangular normalization and the in-place
// rotation) against Eigen's serial products, on one thread and on two: the shapes are large
// enough (n k above 2^18) for the rows to be split, at a point that is not a multiple of 4 or of
// the rotation's bands.
TEST(TallSkinny, RowParallelHelpersMatchEigenOnOneAndTwoThreads) {
  const unsigned before = ffr::preproc::max_threads();
  for (const unsigned threads : {1u, 2u}) {
    ffr::preproc::set_max_threads(threads);
    const Index n = 70001, k = 23, p = 4;
    const Eigen::MatrixXd A = random_matrix(n, k, 21), B = random_matrix(n, p, 22);
    const Eigen::MatrixXd G = ffr::preproc::detail::transposed_product(A, B);
    const Eigen::MatrixXd G_ref = A.transpose() * B;
    EXPECT_LT((G - G_ref).norm(), 1e-13 * G_ref.norm()) << threads << " threads";

    Eigen::MatrixXd U = random_matrix(p, p, 23).triangularView<Eigen::Upper>();
    U.diagonal().array() += 3.0;  // well conditioned
    Eigen::MatrixXd X = B;
    ffr::preproc::detail::solve_upper_on_right(U, X);
    EXPECT_LT((X * U.triangularView<Eigen::Upper>() - B).norm(), 1e-13 * B.norm()) << threads << " threads";

    const Eigen::MatrixXd S = random_matrix(k, 7, 24);
    Eigen::MatrixXd Q = A;
    ffr::preproc::detail::rotate_columns_in_place(Q, k, S);
    const Eigen::MatrixXd R_ref = A * S;
    EXPECT_LT((Q.leftCols(7) - R_ref).norm(), 1e-13 * R_ref.norm()) << threads << " threads";
  }
  ffr::preproc::set_max_threads(before);
}

// The 2 x 2 x 2 corners of a cube in Z-order (x the lowest bit of each cell's code, then y,
// then z), whatever order they are given in; equal points keep their input order; NaN
// coordinates do not crash, and every index comes back exactly once.
TEST(NodeOrder, ZOrderOfACubeTiesByIndexAndAPermutationAlways) {
  // Corner c at (c & 1, c >> 1 & 1, c >> 2 & 1), given in a scrambled order.
  const int given[8] = {5, 2, 7, 0, 3, 6, 1, 4};
  std::vector<double> x;
  for (int c : given) x.insert(x.end(), {double(c & 1), double(c >> 1 & 1), double(c >> 2 & 1)});
  const auto order = ffr::preproc::detail::spatial_order(x.data(), 8);
  ASSERT_EQ(order.size(), 8u);
  for (int c = 0; c < 8; ++c) EXPECT_EQ(given[order[static_cast<std::size_t>(c)]], c) << c;

  // Duplicates keep their order; a NaN point sorts somewhere, but once.
  std::vector<double> y = {1, 1, 1, 0, 0, 0, 1, 1, 1, std::nan(""), 0, 0, 0, 0, 0};
  const auto o2 = ffr::preproc::detail::spatial_order(y.data(), 5);
  std::vector<Index> sorted = o2;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<Index>{0, 1, 2, 3, 4}));
  const auto pos = [&](Index i) { return std::find(o2.begin(), o2.end(), i) - o2.begin(); };
  EXPECT_LT(pos(1), pos(4));  // both at the origin
  EXPECT_LT(pos(0), pos(2));  // both at (1, 1, 1)
  EXPECT_TRUE(ffr::preproc::detail::spatial_order(nullptr, 0).empty());
}

// The block Lanczos convergence count looks only at the Ritz pairs the basis holds: with 2
// Ritz values and 5 modes wanted it counts at most 2 (it once read theta past its end).
TEST(BlockLanczos, ConvergenceCountStaysInsideTheRitzValues) {
  Eigen::VectorXd theta(2);
  theta << 3.0, 2.0;
  Eigen::MatrixXd coupling = Eigen::MatrixXd::Zero(4, 2);
  EXPECT_EQ(ffr::preproc::detail::count_converged_ritz_pairs(theta, coupling, 5, 1e-12), 2);
  coupling(0, 1) = 1.0;  // pair 2's residual 1 > 1e-12 * 2
  EXPECT_EQ(ffr::preproc::detail::count_converged_ritz_pairs(theta, coupling, 5, 1e-12), 1);
  EXPECT_EQ(ffr::preproc::detail::count_converged_ritz_pairs(theta, coupling, 1, 1e-12), 1);
}
