#pragma once
// The dense kernels of the supernodal factorization and of the block Gram-Schmidt: the BLAS's,
// or Eigen's compiled for this CPU's vector units.
//
// Why two: OpenBLAS (built with DYNAMIC_ARCH, as Debian ships it) picks its kernels from the
// CPU's model number and runs its oldest x86-64 ones (Prescott, SSE3) on a model newer than its
// release (blas_kernels.hpp). The supernodal factorization is nearly all dsyrk/dgemm, and on such
// a CPU it ran about 2.5 times as long as with the kernels the CPU's features allow. Eigen's
// products are compiled here for x86-64-v4 (AVX-512) and x86-64-v3 (AVX2, FMA) beside the
// baseline and chosen by the CPU's features (dense_kernels_eigen.cpp, preproc/CMakeLists.txt),
// so the default path no longer depends on the BLAS knowing the CPU. Where the BLAS's kernels do
// suit the CPU (OpenBLAS on a CPU it knows, or another BLAS), "auto" keeps the BLAS. CHOLMOD's
// own factorization (the "cholmod" backend) always calls the BLAS.

#include "ffr/preproc/solver/dense_kernel_choice.hpp"

#include <vector>

namespace ffr::preproc::detail {

/// Column-major dense kernels; leading dimensions as in the BLAS. Every function runs on the
/// calling thread (the BLAS is held to one thread where these are called from threads of the
/// reducer, ffr/cli/process_threads.hpp).
struct DenseKernels {
  /// "BLAS", or "Eigen (x86-64-v4)", "Eigen (x86-64-v3)", "Eigen (baseline)".
  const char* name;
  /// C = alpha op(A) op(B) + beta C, C m x n; op(X) = X or X^T by 'N' / 'T' (dgemm).
  void (*gemm)(char transa, char transb, int m, int n, int k, double alpha, const double* A, int lda, const double* B,
               int ldb, double beta, double* C, int ldc);
  /// The lower triangle of C (n x n) = alpha A A^T + beta C, A n x k (dsyrk "L", "N"); beta 0
  /// or 1. The strict upper triangle of C is not touched.
  void (*syrk_lower)(int n, int k, double alpha, const double* A, int lda, double beta, double* C, int ldc);
  /// B (m x n) <- B L^-T, L n x n lower triangular with a non-unit diagonal (dtrsm "R", "L",
  /// "T", "N" with alpha 1).
  void (*solve_lower_transposed_on_right)(int m, int n, const double* L, int ldl, double* B, int ldb);
  /// The lower triangle of A (n x n) <- its Cholesky factor (dpotrf "L"). Returns 0, or the
  /// 1-based column whose pivot is not positive (dpotrf's info).
  int (*cholesky_lower)(int n, double* A, int lda);
};

const DenseKernels& blas_dense_kernels();
/// Eigen's kernels for the widest vector units this CPU has among the compiled variants.
const DenseKernels& eigen_dense_kernels();
/// Every compiled Eigen variant this CPU can run, baseline first (for the tests).
std::vector<const DenseKernels*> eigen_dense_kernel_variants();
/// The kernels for `choice` on this process's BLAS and this CPU.
const DenseKernels& select_dense_kernels(DenseKernelChoice choice);

/// Whether the BLAS in this process runs kernels older than this CPU's vector units: OpenBLAS
/// with kernels before AVX2 (blas_kernel_name) on a CPU that has AVX2 and FMA.
bool blas_kernels_fall_short();

}  // namespace ffr::preproc::detail
