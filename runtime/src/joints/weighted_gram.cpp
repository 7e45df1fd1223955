#include "weighted_gram.hpp"

// Compiled at -O3 (runtime/CMakeLists.txt) and for AVX2/AVX-512 as well: the inner loop has a
// run-time length, which GCC vectorises at -O3 only.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FFR_GRAM_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define FFR_GRAM_CLONES
#endif

namespace ffr::runtime::detail {

FFR_GRAM_CLONES
void add_weighted_gram(const double* Ja, const double* Jb, Eigen::Index ld, int rows, int na, int nb,
                       const double* w, double* buf, double* T, Eigen::Index ldt) {
  // buf = (diag(w) Ja)^T, na x rows: each row of Ja becomes a contiguous column.
  for (int r = 0; r < rows; ++r)
    for (int i = 0; i < na; ++i) buf[i + r * na] = w[r] * Ja[r + i * ld];
  // Column c of T gets sum_r Jb(r, c) buf(:, r); most entries of a joint's rows are zero.
  for (int c = 0; c < nb; ++c) {
    double* __restrict t = T + c * ldt;
    for (int r = 0; r < rows; ++r) {
      const double s = Jb[r + c * ld];
      if (s == 0.0) continue;
      const double* __restrict b = buf + r * na;
      for (int i = 0; i < na; ++i) t[i] += s * b[i];
    }
  }
}

}  // namespace ffr::runtime::detail
