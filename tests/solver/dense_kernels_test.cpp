// The dense kernels of the supernodal factorization and the block Gram-Schmidt
// (solver/dense_kernels.hpp): the BLAS's and every Eigen variant this CPU runs, against plain
// loops written here (the BLAS's definitions of dgemm, dsyrk, dtrsm and dpotrf: C = alpha op(A)
// op(B) + beta C; the lower triangle of alpha A A^T + beta C; X L^T = B; the Cholesky
// recurrence L_jj = sqrt(A_jj - sum_k L_jk^2), L_ij = (A_ij - sum_k L_ik L_jk) / L_jj).
#include "solver/dense_kernels.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using ffr::preproc::DenseKernelChoice;
using ffr::preproc::detail::DenseKernels;

namespace {

// A column-major m x n matrix inside a larger leading dimension, the rows beyond m filled with a
// sentinel that no kernel may change.
struct Block {
  int m, n, ld;
  std::vector<double> v;
  Block(int rows, int cols, int extra, unsigned seed) : m(rows), n(cols), ld(rows + extra), v(std::size_t(ld) * cols) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (double& x : v) x = u(rng);
    for (int j = 0; j < n; ++j)
      for (int i = m; i < ld; ++i) at(i, j) = 1234.5;
  }
  double& at(int i, int j) { return v[std::size_t(j) * ld + i]; }
  double at(int i, int j) const { return v[std::size_t(j) * ld + i]; }
  bool padding_intact() const {
    for (int j = 0; j < n; ++j)
      for (int i = m; i < ld; ++i)
        if (at(i, j) != 1234.5) return false;
    return true;
  }
};

std::vector<const DenseKernels*> all_kernels() {
  std::vector<const DenseKernels*> k{&ffr::preproc::detail::blas_dense_kernels()};
  for (const DenseKernels* v : ffr::preproc::detail::eigen_dense_kernel_variants()) k.push_back(v);
  return k;
}

}  // namespace

// Every shape class the factorization and the Gram-Schmidt call: tiny (Eigen's coefficient-based
// path), panel-sized and above a 128-column block, every transposition, beta 0 over NaN (C must
// not be read), alpha -1 and beta 1 (the updates).
TEST(DenseKernels, GemmOfEveryKernelMatchesTheDefinition) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const DenseKernels* k : all_kernels()) {
    for (const auto& [m, n, depth] : {std::tuple{3, 2, 4}, {37, 29, 17}, {150, 131, 140}}) {
      for (const char ta : {'N', 'T'})
        for (const char tb : {'N', 'T'})
          for (const double beta : {0.0, 1.0}) {
            const Block A(ta == 'N' ? m : depth, ta == 'N' ? depth : m, 3, 1), B(tb == 'N' ? depth : n, tb == 'N' ? n : depth, 5, 2);
            Block C(m, n, 2, 3);
            if (beta == 0.0)
              for (int j = 0; j < n; ++j)
                for (int i = 0; i < m; ++i) C.at(i, j) = nan;
            const Block C0 = C;
            k->gemm(ta, tb, m, n, depth, -1.0, A.v.data(), A.ld, B.v.data(), B.ld, beta, C.v.data(), C.ld);
            double err = 0, scale = 0;
            for (int j = 0; j < n; ++j)
              for (int i = 0; i < m; ++i) {
                double s = beta == 0.0 ? 0.0 : C0.at(i, j);
                for (int l = 0; l < depth; ++l) s -= (ta == 'N' ? A.at(i, l) : A.at(l, i)) * (tb == 'N' ? B.at(l, j) : B.at(j, l));
                err = std::max(err, std::abs(C.at(i, j) - s));
                scale = std::max(scale, std::abs(s));
              }
            EXPECT_LE(err, 1e-13 * depth * scale) << k->name << ' ' << ta << tb << ' ' << m << 'x' << n << 'x' << depth;
            EXPECT_TRUE(C.padding_intact()) << k->name;
          }
    }
  }
}

TEST(DenseKernels, SyrkWritesTheLowerTriangleOnly) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const DenseKernels* k : all_kernels()) {
    for (const auto& [n, depth] : {std::pair{5, 3}, {64, 31}, {170, 133}}) {
      for (const double beta : {0.0, 1.0}) {
        const Block A(n, depth, 4, 7);
        Block C(n, n, 1, 8);
        for (int j = 0; j < n; ++j)
          for (int i = j; i < n && beta == 0.0; ++i) C.at(i, j) = nan;
        const Block C0 = C;
        k->syrk_lower(n, depth, 1.0, A.v.data(), A.ld, beta, C.v.data(), C.ld);
        double err = 0, scale = 0;
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            if (i < j) {
              EXPECT_EQ(C.at(i, j), C0.at(i, j)) << k->name << " wrote above the diagonal";
              continue;
            }
            double s = beta == 0.0 ? 0.0 : C0.at(i, j);
            for (int l = 0; l < depth; ++l) s += A.at(i, l) * A.at(j, l);
            err = std::max(err, std::abs(C.at(i, j) - s));
            scale = std::max(scale, std::abs(s));
          }
        EXPECT_LE(err, 1e-13 * depth * scale) << k->name << " n " << n << " k " << depth << " beta " << beta;
        EXPECT_TRUE(C.padding_intact()) << k->name;
      }
    }
  }
}

// An SPD matrix S = G G^T + n I: its factor by each kernel against the recurrence, then the
// triangular solve X L^T = B checked by multiplying back; a negative pivot at a known column
// reported as dpotrf's info (1-based), also beyond Eigen's first 128-column block.
TEST(DenseKernels, CholeskyAndTriangularSolveMatchTheDefinition) {
  for (const DenseKernels* k : all_kernels()) {
    for (const int n : {1, 7, 90, 300}) {
      const Block G(n, n, 0, 11);
      Block S(n, n, 3, 12);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          double s = i == j ? n : 0.0;
          for (int l = 0; l < n; ++l) s += G.at(i, l) * G.at(j, l);
          S.at(i, j) = s;
        }
      Block L = S;
      ASSERT_EQ(k->cholesky_lower(n, L.v.data(), L.ld), 0) << k->name << " n " << n;
      Block R = S;  // the recurrence, in place on the lower triangle
      for (int j = 0; j < n; ++j) {
        for (int l = 0; l < j; ++l) R.at(j, j) -= R.at(j, l) * R.at(j, l);
        R.at(j, j) = std::sqrt(R.at(j, j));
        for (int i = j + 1; i < n; ++i) {
          for (int l = 0; l < j; ++l) R.at(i, j) -= R.at(i, l) * R.at(j, l);
          R.at(i, j) /= R.at(j, j);
        }
      }
      double err = 0;
      for (int j = 0; j < n; ++j)
        for (int i = j; i < n; ++i) err = std::max(err, std::abs(L.at(i, j) - R.at(i, j)) / std::abs(R.at(j, j)));
      EXPECT_LT(err, 1e-12) << k->name << " n " << n;
      EXPECT_TRUE(L.padding_intact()) << k->name;

      const int m = 23;
      const Block B(m, n, 2, 13);
      Block X = B;
      k->solve_lower_transposed_on_right(m, n, L.v.data(), L.ld, X.v.data(), X.ld);
      double res = 0, scale = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < m; ++i) {
          double s = 0;  // (X L^T)(i, j) = sum_l X(i, l) L(j, l), l <= j
          for (int l = 0; l <= j; ++l) s += X.at(i, l) * L.at(j, l);
          res = std::max(res, std::abs(s - B.at(i, j)));
          scale = std::max(scale, std::abs(B.at(i, j)));
        }
      EXPECT_LT(res, 1e-12 * scale) << k->name << " n " << n;
      EXPECT_TRUE(X.padding_intact()) << k->name;

      for (const int bad : {0, n / 2, n - 1}) {
        Block A = S;
        A.at(bad, bad) = -1.0 - n * n;
        EXPECT_EQ(k->cholesky_lower(n, A.v.data(), A.ld), bad + 1) << k->name << " n " << n;
      }
    }
  }
}

// "auto" keeps the BLAS unless its kernels fall short of this CPU; the other two are what they say.
TEST(DenseKernels, ChoiceNamesTheKernelsInUse) {
  using ffr::preproc::detail::select_dense_kernels;
  EXPECT_STREQ(select_dense_kernels(DenseKernelChoice::Blas).name, "BLAS");
  EXPECT_EQ(std::string(select_dense_kernels(DenseKernelChoice::Eigen).name).rfind("Eigen (", 0), 0u);
  EXPECT_EQ(&select_dense_kernels(DenseKernelChoice::Auto), ffr::preproc::detail::blas_kernels_fall_short()
                                                                ? &select_dense_kernels(DenseKernelChoice::Eigen)
                                                                : &select_dense_kernels(DenseKernelChoice::Blas));
  // The widest variant the CPU runs is the one chosen.
  const auto variants = ffr::preproc::detail::eigen_dense_kernel_variants();
  ASSERT_GE(variants.size(), 1u);
  EXPECT_STREQ(variants.front()->name, "Eigen (baseline)");
  EXPECT_EQ(&select_dense_kernels(DenseKernelChoice::Eigen), variants.back());
  for (const char* name : {"auto", "blas", "eigen"})
    EXPECT_STREQ(ffr::preproc::to_string(*ffr::preproc::dense_kernel_choice_from_string(name)), name);
  EXPECT_FALSE(ffr::preproc::dense_kernel_choice_from_string("mkl"));
}
