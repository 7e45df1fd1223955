// The dense kernels (dense_kernels.hpp) as Eigen's products, triangular solve and blocked
// Cholesky. This file is compiled once with the library's own flags (the baseline variant) and,
// on x86-64 with the GNU toolchain, again for x86-64-v3 and x86-64-v4 (preproc/CMakeLists.txt).
// Each extra variant is one relocatable object in which every symbol but its table
// (ffr_dense_kernels_eigen_<variant>) is made local: Eigen's templates, instantiated the same
// way in every variant and in the rest of the library, would otherwise be merged by the linker
// into one copy, compiled for whichever ISA the linker met first.
#include "dense_kernels.hpp"

#define EIGEN_DONT_PARALLELIZE  // every call runs on its caller's thread (dense_kernels.hpp)
#include <Eigen/Cholesky>
#include <Eigen/Core>

// FFR_DENSE_LEVEL: the x86-64 level a variant is compiled for (3 or 4); none for the baseline.
#ifdef FFR_DENSE_LEVEL
#define FFR_DENSE_VARIANT FFR_DENSE_CAT(x86_64_v, FFR_DENSE_LEVEL)
#define FFR_DENSE_NAME "Eigen (x86-64-v" FFR_DENSE_STR(FFR_DENSE_LEVEL) ")"
#else
#define FFR_DENSE_VARIANT baseline
#define FFR_DENSE_NAME "Eigen (baseline)"
#endif
#define FFR_DENSE_CAT2(a, b) a##b
#define FFR_DENSE_CAT(a, b) FFR_DENSE_CAT2(a, b)
#define FFR_DENSE_STR2(a) #a
#define FFR_DENSE_STR(a) FFR_DENSE_STR2(a)

namespace {

using Table = ffr::preproc::detail::DenseKernels;
using Stride = Eigen::OuterStride<>;
using Mat = Eigen::Map<Eigen::MatrixXd, 0, Stride>;
using ConstMat = Eigen::Map<const Eigen::MatrixXd, 0, Stride>;

bool transposed(char t) { return t == 'T' || t == 't' || t == 'C' || t == 'c'; }

void gemm(char ta, char tb, int m, int n, int k, double alpha, const double* A, int lda, const double* B, int ldb,
          double beta, double* C, int ldc) {
  if (m <= 0 || n <= 0) return;
  Mat c(C, m, n, Stride(ldc));
  // As the BLAS: with beta = 0, C is not read (it may hold anything, NaN included).
  if (beta == 0.0) c.setZero();
  else if (beta != 1.0) c *= beta;
  if (k <= 0 || alpha == 0.0) return;
  const bool at = transposed(ta), bt = transposed(tb);
  const ConstMat a(A, at ? k : m, at ? m : k, Stride(lda));
  const ConstMat b(B, bt ? n : k, bt ? k : n, Stride(ldb));
  if (!at && !bt) c.noalias() += alpha * a * b;
  else if (!at) c.noalias() += alpha * a * b.transpose();
  else if (!bt) c.noalias() += alpha * a.transpose() * b;
  else c.noalias() += alpha * a.transpose() * b.transpose();
}

void syrk_lower(int n, int k, double alpha, const double* A, int lda, double beta, double* C, int ldc) {
  if (n <= 0) return;
  Mat c(C, n, n, Stride(ldc));
  if (beta == 0.0) c.triangularView<Eigen::Lower>().setZero();
  else if (beta != 1.0) c.triangularView<Eigen::Lower>() *= beta;
  if (k <= 0 || alpha == 0.0) return;
  c.selfadjointView<Eigen::Lower>().rankUpdate(ConstMat(A, n, k, Stride(lda)), alpha);
}

void solve_lower_transposed_on_right(int m, int n, const double* L, int ldl, double* B, int ldb) {
  if (m <= 0 || n <= 0) return;
  Mat b(B, m, n, Stride(ldb));
  // X L^T = B: the upper-triangular L^T on the right.
  const ConstMat l(L, n, n, Stride(ldl));
  l.transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(b);
}

int cholesky_lower(int n, double* A, int lda) {
  if (n <= 0) return 0;
  Mat a(A, n, n, Stride(lda));
  // Eigen's blocked LL^T (what Eigen::LLT runs), for the column where it stops: -1 when every
  // pivot was positive, else that column (0-based).
  const Eigen::Index failed = Eigen::internal::llt_inplace<double, Eigen::Lower>::blocked(a);
  return failed < 0 ? 0 : static_cast<int>(failed) + 1;
}

constexpr Table kKernels{FFR_DENSE_NAME, gemm, syrk_lower, solve_lower_transposed_on_right,
                       cholesky_lower};

}  // namespace

extern "C" __attribute__((visibility("default"))) const Table* FFR_DENSE_CAT(ffr_dense_kernels_eigen_, FFR_DENSE_VARIANT)() {
  return &kKernels;
}
