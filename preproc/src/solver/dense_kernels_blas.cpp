// The dense kernels as the Fortran BLAS and LAPACK calls (dense_kernels.hpp), linked from the
// libraries CHOLMOD itself calls.
#include "dense_kernels.hpp"

extern "C" {
void dsyrk_(const char*, const char*, const int*, const int*, const double*, const double*, const int*, const double*,
            double*, const int*);
void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*, const double*, const int*,
            const double*, const int*, const double*, double*, const int*);
void dtrsm_(const char*, const char*, const char*, const char*, const int*, const int*, const double*, const double*,
            const int*, double*, const int*);
void dpotrf_(const char*, const int*, double*, const int*, int*);
}

namespace ffr::preproc::detail {
namespace {

void gemm(char ta, char tb, int m, int n, int k, double alpha, const double* A, int lda, const double* B, int ldb,
          double beta, double* C, int ldc) {
  const char sa[2] = {ta, 0}, sb[2] = {tb, 0};
  dgemm_(sa, sb, &m, &n, &k, &alpha, A, &lda, B, &ldb, &beta, C, &ldc);
}

void syrk_lower(int n, int k, double alpha, const double* A, int lda, double beta, double* C, int ldc) {
  dsyrk_("L", "N", &n, &k, &alpha, A, &lda, &beta, C, &ldc);
}

void solve_lower_transposed_on_right(int m, int n, const double* L, int ldl, double* B, int ldb) {
  const double one = 1.0;
  dtrsm_("R", "L", "T", "N", &m, &n, &one, L, &ldl, B, &ldb);
}

int cholesky_lower(int n, double* A, int lda) {
  int info = 0;
  dpotrf_("L", &n, A, &lda, &info);
  return info;
}

}  // namespace

const DenseKernels& blas_dense_kernels() {
  static constexpr DenseKernels k{"BLAS", gemm, syrk_lower, solve_lower_transposed_on_right, cholesky_lower};
  return k;
}

}  // namespace ffr::preproc::detail
