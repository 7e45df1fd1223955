// Tall-skinny products for the block Gram-Schmidt (see tall_skinny.hpp for why).
#include "tall_skinny.hpp"

#include "kernel_clones.hpp"

#include <algorithm>

namespace ffr::preproc::detail {
namespace {

using Index = std::int64_t;

// Rows per chunk: a chunk of 4 columns of V is 32 KB, the size of L1, and each column of Q is
// read in runs of 8 KB, long enough for the hardware prefetcher.
constexpr Index kChunk = 1024;

using simd::load;
using simd::store;
using simd::v4;

inline double sum(v4 v) { return (v[0] + v[1]) + (v[2] + v[3]); }

// c[r + g * ldc] += q_r(0:m)^T v_g(0:m) for R columns q_r = q + r * ldq and G columns
// v_g = V + g * ldv.
template <int R, int G>
inline void dots(const double* q, Index ldq, const double* V, Index ldv, Index m, double* c, Index ldc) {
  v4 acc[R][G] = {};
  Index i = 0;
  for (; i + 4 <= m; i += 4) {
    v4 vv[G];
    for (int g = 0; g < G; ++g) vv[g] = load(V + g * ldv + i);
    for (int r = 0; r < R; ++r) {
      const v4 qv = load(q + r * ldq + i);
      for (int g = 0; g < G; ++g) acc[r][g] += qv * vv[g];
    }
  }
  for (int r = 0; r < R; ++r)
    for (int g = 0; g < G; ++g) {
      double s = sum(acc[r][g]);
      for (Index t = i; t < m; ++t) s += q[r * ldq + t] * V[g * ldv + t];
      c[r + g * ldc] += s;
    }
}

// v_g(0:m) -= sum_r q_r(0:m) c[r + g * ldc] for R columns q_r = q + r * ldq and G columns
// v_g = V + g * ldv.
template <int R, int G>
inline void axpys(const double* q, Index ldq, const double* c, Index ldc, Index m, double* V, Index ldv) {
  double a[R][G];
  for (int r = 0; r < R; ++r)
    for (int g = 0; g < G; ++g) a[r][g] = c[r + g * ldc];
  Index i = 0;
  for (; i + 4 <= m; i += 4) {
    v4 acc[G];
    for (int g = 0; g < G; ++g) acc[g] = load(V + g * ldv + i);
    for (int r = 0; r < R; ++r) {
      const v4 x = load(q + r * ldq + i);
      for (int g = 0; g < G; ++g) acc[g] -= a[r][g] * x;
    }
    for (int g = 0; g < G; ++g) store(V + g * ldv + i, acc[g]);
  }
  for (; i < m; ++i)
    for (int g = 0; g < G; ++g) {
      double v = V[g * ldv + i];
      for (int r = 0; r < R; ++r) v -= a[r][g] * q[r * ldq + i];
      V[g * ldv + i] = v;
    }
}

}  // namespace

FFR_KERNEL_CLONES
void add_transposed_product(const double* Q, Index ldq, Index k, const double* V, Index ldv, Index p, Index r0,
                            Index r1, double* C) {
  for (Index a = r0; a < r1; a += kChunk) {
    const Index m = std::min(kChunk, r1 - a);
    Index j = 0;
    for (; j + 4 <= k; j += 4) {
      const double* q = Q + j * ldq + a;
      Index l = 0;
      for (; l + 4 <= p; l += 4) dots<4, 4>(q, ldq, V + l * ldv + a, ldv, m, C + j + l * k, k);
      for (; l < p; ++l) dots<4, 1>(q, ldq, V + l * ldv + a, ldv, m, C + j + l * k, k);
    }
    for (; j < k; ++j) {
      const double* q = Q + j * ldq + a;
      Index l = 0;
      for (; l + 4 <= p; l += 4) dots<1, 4>(q, ldq, V + l * ldv + a, ldv, m, C + j + l * k, k);
      for (; l < p; ++l) dots<1, 1>(q, ldq, V + l * ldv + a, ldv, m, C + j + l * k, k);
    }
  }
}

FFR_KERNEL_CLONES
void subtract_product(const double* Q, Index ldq, Index k, const double* C, Index p, Index r0, Index r1, double* V,
                      Index ldv) {
  for (Index a = r0; a < r1; a += kChunk) {
    const Index m = std::min(kChunk, r1 - a);
    Index j = 0;
    for (; j + 4 <= k; j += 4) {
      const double* q = Q + j * ldq + a;
      Index l = 0;
      for (; l + 4 <= p; l += 4) axpys<4, 4>(q, ldq, C + j + l * k, k, m, V + l * ldv + a, ldv);
      for (; l < p; ++l) axpys<4, 1>(q, ldq, C + j + l * k, k, m, V + l * ldv + a, ldv);
    }
    for (; j < k; ++j) {
      const double* q = Q + j * ldq + a;
      Index l = 0;
      for (; l + 4 <= p; l += 4) axpys<1, 4>(q, ldq, C + j + l * k, k, m, V + l * ldv + a, ldv);
      for (; l < p; ++l) axpys<1, 1>(q, ldq, C + j + l * k, k, m, V + l * ldv + a, ldv);
    }
  }
}

}  // namespace ffr::preproc::detail
