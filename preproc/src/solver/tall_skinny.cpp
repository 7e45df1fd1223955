// Tall-skinny products for the block Gram-Schmidt (see tall_skinny.hpp for why).
#include "tall_skinny.hpp"

#include "../run_parts.hpp"
#include "kernel_clones.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <type_traits>
#include <vector>

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

// Calls kernel(R, G, j, l, a, m) (R and G as std::integral_constant) for the tiles of R columns
// of Q from j and G columns of the thin block from l, over the rows [a, a + m) of each chunk:
// tiles of 4 x 4 where they fit, then the rest by 1.
template <class Kernel>
inline void for_each_tile(Index k, Index p, Index r0, Index r1, Kernel&& kernel) {
  using One = std::integral_constant<int, 1>;
  using Four = std::integral_constant<int, 4>;
  for (Index a = r0; a < r1; a += kChunk) {
    const Index m = std::min(kChunk, r1 - a);
    const auto columns_of_q = [&](auto R, Index j) {
      Index l = 0;
      for (; l + 4 <= p; l += 4) kernel(R, Four{}, j, l, a, m);
      for (; l < p; ++l) kernel(R, One{}, j, l, a, m);
    };
    Index j = 0;
    for (; j + 4 <= k; j += 4) columns_of_q(Four{}, j);
    for (; j < k; ++j) columns_of_q(One{}, j);
  }
}

}  // namespace

FFR_KERNEL_CLONES
void add_transposed_product(const double* Q, Index ldq, Index k, const double* V, Index ldv, Index p, Index r0,
                            Index r1, double* C) {
  for_each_tile(k, p, r0, r1, [&](auto R, auto G, Index j, Index l, Index a, Index m) {
    dots<R(), G()>(Q + j * ldq + a, ldq, V + l * ldv + a, ldv, m, C + j + l * k, k);
  });
}

FFR_KERNEL_CLONES
void subtract_product(const double* Q, Index ldq, Index k, const double* C, Index p, Index r0, Index r1, double* V,
                      Index ldv) {
  for_each_tile(k, p, r0, r1, [&](auto R, auto G, Index j, Index l, Index a, Index m) {
    axpys<R(), G()>(Q + j * ldq + a, ldq, C + j + l * k, k, m, V + l * ldv + a, ldv);
  });
}

namespace {

// How many parts for work of about n * width values: the eigen-solver's threshold for vector
// work.
unsigned row_parts(Index n, Index width) { return parts_for(n * width, Index{1} << 18); }

// body(part, r0, r1) over `parts` parts of n rows, split at multiples of `align` rows.
template <class Body>
void over_row_parts(Index n, unsigned parts, Index align, Body&& body) {
  const auto split = [&](unsigned part) {
    if (part >= parts) return n;
    return n * static_cast<Index>(part) / static_cast<Index>(parts) / align * align;
  };
  run_parts(parts, split, body);
}

}  // namespace

void rotate_columns_in_place(Eigen::MatrixXd& Q, Eigen::Index k, const Eigen::Ref<const Eigen::MatrixXd>& S) {
  const Eigen::Index n = Q.rows(), m = S.cols();
  constexpr Eigen::Index kBand = 256;
  over_row_parts(n, row_parts(n, k), kBand, [&](unsigned, Index b, Index e) {
    Eigen::MatrixXd band(kBand, m);
    for (Eigen::Index r0 = b; r0 < e; r0 += kBand) {
      const Eigen::Index rows = std::min(kBand, e - r0);
      band.topRows(rows).noalias() = Q.block(r0, 0, rows, k) * S;
      Q.block(r0, 0, rows, m) = band.topRows(rows);
    }
  });
}

Eigen::MatrixXd transposed_product(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B) {
  const Index n = A.rows(), k = A.cols(), p = B.cols();
  const unsigned parts = row_parts(n, k);
  std::vector<Eigen::MatrixXd> partial(parts, Eigen::MatrixXd::Zero(k, p));
  over_row_parts(n, parts, 1, [&](unsigned part, Index r0, Index r1) {
    add_transposed_product(A.data(), A.outerStride(), k, B.data(), B.outerStride(), p, r0, r1, partial[part].data());
  });
  for (std::size_t part = 1; part < partial.size(); ++part) partial[0] += partial[part];
  return std::move(partial[0]);
}

void solve_upper_on_right(const Eigen::Ref<const Eigen::MatrixXd>& U, Eigen::MatrixXd& X) {
  const auto upper = U.triangularView<Eigen::Upper>();
  over_row_parts(X.rows(), row_parts(X.rows(), X.cols()), 1, [&](unsigned, Index r0, Index r1) {
    auto rows = X.middleRows(r0, r1 - r0);
    upper.solveInPlace<Eigen::OnTheRight>(rows);
  });
}

}  // namespace ffr::preproc::detail
