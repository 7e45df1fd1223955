// Right-looking LU with partial pivoting that skips the zeros of a multibody tangent
// (see small_lu.hpp for why it is not Eigen::PartialPivLU).
#include "ffr/runtime/small_lu.hpp"

#include "kernel_clones.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ffr::runtime {

using Eigen::Index;

void SmallLU::resize(Index n) {
  buffer_.setZero((n + 2 * kPad) * n);
  work_.setZero(n + 2 * kPad);
  capacity_ = n;
  n_ = n;
  ld_ = n + 2 * kPad;
  row_of_.setZero(n);
  row_last_.setZero(n);
  lower_.setZero(n);
  upper_.setZero(n);
  inv_diag_.setZero(n);
  ok_ = false;
  spans_bound_buffer_ = false;
}

void SmallLU::clear_outside(Index k, const int* first, const int* last) {
  if (!spans_bound_buffer_ || k != n_) {
    buffer_.setZero();
    return;
  }
  // Column j of the last factors is zero outside rows upper_(j) .. lower_(j) (factorize).
  double* a = buffer_.data() + kPad;
  for (Index j = 0; j < k; ++j) {
    double* c = a + j * ld_;
    const Index lo = upper_(j), hi = lower_(j);
    if (lo < first[j]) std::fill(c + lo, c + std::min<Index>(first[j], hi + 1), 0.0);
    if (hi > last[j]) std::fill(c + std::max<Index>(last[j] + 1, lo), c + hi + 1, 0.0);
  }
}

namespace {

// Panel width of the blocked elimination: the trailing columns are updated once per four
// pivots (a rank-4 update: five loads, one store and four multiply-adds an entry) instead of
// once per pivot (two loads, one store and one multiply-add, four times over).
constexpr Index kPanel = 4;

// Blocks of four rows from `from` up to at least `to`: the blocks that cover from .. to (to < from:
// none). They reach at most three rows past `to`, into the zero rows below the columns
// (SmallLU::kPad).
inline Index blocks_of_four(Index from, Index to) { return to < from ? 0 : ((to - from) >> 2) + 1; }

// Rows k+1 .. last of column k scaled by 1 / pivot, then the panel's own columns k+1 .. p1-1
// updated by them (rank-1: the panel is at most four wide). Rows past `last` are zero in column
// k, so the blocks of four leave them zero.
inline void eliminate_in_panel(double* a, Index ld, Index k, Index last, Index p1) {
  double* ck = a + k * ld;
  const Index blocks = blocks_of_four(k + 1, last);
  const double inv = 1.0 / ck[k];
  double* __restrict l = ck + k + 1;
  for (Index b = 0; b < blocks; ++b)
    for (int q = 0; q < 4; ++q) l[4 * b + q] *= inv;
  for (Index j = k + 1; j < p1; ++j) {
    double* __restrict u = a + j * ld + k + 1;
    const double f = a[k + j * ld];
    if (f == 0.0) continue;
    for (Index b = 0; b < blocks; ++b)
      for (int q = 0; q < 4; ++q) u[4 * b + q] -= f * l[4 * b + q];
  }
}

// Largest |c[i]| for k <= i <= last, its row in p: the first such row, as a plain scan would
// find. Four independent running maxima: with one compare-and-select chain down the column, the
// search took about 45 % of the samples of a factorisation of the benchmark's tangent (perf
// annotate), for its latency, not its work. A NaN in c[k] is returned as the maximum (nothing
// compares greater), so the caller's singularity check sees it.
inline double pivot_search(const double* c, Index k, Index last, Index& p) {
  double big[4] = {std::abs(c[k]), -1.0, -1.0, -1.0};
  Index at[4] = {k, k, k, k};
  Index i = k + 1;
  for (; i + 3 <= last; i += 4)
    for (int q = 0; q < 4; ++q) {
      const double v = std::abs(c[i + q]);
      if (v > big[q]) {
        big[q] = v;
        at[q] = i + q;
      }
    }
  for (; i <= last; ++i) {
    const double v = std::abs(c[i]);
    if (v > big[0]) {
      big[0] = v;
      at[0] = i;
    }
  }
  double best = big[0];
  p = at[0];
  for (int q = 1; q < 4; ++q)
    if (big[q] > best || (big[q] == best && at[q] < p)) {
      best = big[q];
      p = at[q];
    }
  return best;
}

// Trailing column j after the panel k0 .. k0+B-1: its rows in the panel become U12 (the unit
// lower triangle L11 solved), then its rows from k0+B on lose L21 U12, in `blocks` blocks of
// four (blocks_of_four up to the panel's last nonzero row). Columns whose panel rows are all
// zero are left as they are.
template <int B>
inline void update_trailing_column(double* a, Index ld, Index k0, Index blocks, Index j) {
  double* __restrict c = a + j * ld;
  double u[B];
  bool any = false;
  for (int q = 0; q < B; ++q) {
    double x = c[k0 + q];
    for (int r = 0; r < q; ++r) x -= a[(k0 + q) + (k0 + r) * ld] * u[r];
    u[q] = x;
    c[k0 + q] = x;
    any = any || x != 0.0;
  }
  if (!any) return;
  const double* __restrict l = a + k0 * ld;
  for (Index b = 0; b < blocks; ++b) {
    const Index i0 = k0 + B + 4 * b;
    for (int r = 0; r < 4; ++r) {
      double x = c[i0 + r];
      for (int q = 0; q < B; ++q) x -= l[i0 + r + q * ld] * u[q];
      c[i0 + r] = x;
    }
  }
}

// The first i in [lo, hi] with c[i] != 0 (hi + 1 when none), and the last i in [lo, hi] with
// c[i] != 0 (lo - 1 when none), four entries at a time: the scans over a column's zeros were
// most of a factorisation of a banded tangent once the elimination followed its envelope. (A NaN
// counts as nonzero, as in the scalar tests.)
inline Index first_nonzero(const double* c, Index lo, Index hi) {
  Index i = lo;
  for (; i + 3 <= hi; i += 4) {
    const detail::simd::m4 nz = detail::simd::load(c + i) != detail::simd::v4{};
    if (nz[0] | nz[1] | nz[2] | nz[3]) break;
  }
  for (; i <= hi; ++i)
    if (c[i] != 0.0) return i;
  return hi + 1;
}

inline Index last_nonzero(const double* c, Index lo, Index hi) {
  Index i = hi;
  for (; i - 3 >= lo; i -= 4) {
    const detail::simd::m4 nz = detail::simd::load(c + i - 3) != detail::simd::v4{};
    if (nz[0] | nz[1] | nz[2] | nz[3]) break;
  }
  for (; i >= lo; --i)
    if (c[i] != 0.0) return i;
  return lo - 1;
}

}  // namespace

// The kernels are plain loops over raw columns, compiled at -O3 and for AVX2 as well
// (kernel_clones.hpp): Eigen's dynamic segments cost a call and an alignment prologue per AXPY.
// The elimination is blocked (LAPACK's right-looking getrf with a panel of kPanel columns):
// partial pivoting inside the panel, each swap applied to the whole row at once, then the
// trailing columns updated once for the whole panel. Unblocked, a factorisation of the
// benchmark's tangent made about a thousand AXPYs of 10 to 40 entries.
//
// The envelope: each row's last nonzero column and each column's last nonzero row (bounds,
// found in one pass over the matrix and widened by every swap and update that can fill in).
// With them the row swaps, the pivot column's search for its last nonzero and the loop over
// the trailing columns stop where the rows and columns end, instead of running over all n: on
// a tangent whose bodies are coupled in a chain (a geometrically exact beam's node bodies, a
// chain of links) most of the matrix lies outside the envelope, and those loops were most of
// a factorisation. The arithmetic is the same as without the bounds (they skip only columns
// and rows of zeros, which the loops left as they were).
//
// With the columns' spans given (compute_within) they are the initial bounds, and nothing
// outside them is read: no pass over the whole matrix.
FFR_RT_CLONES
bool SmallLU::factorize(const int* span_first, const int* span_last) {
  const Index n = n_, ld = ld_;
  double* a = buffer_.data() + kPad;
  ok_ = false;
  // lower_ (the solves' spans, set at the end) holds the column bounds meanwhile.
  int* col_last = lower_.data();     // column j: zero below this row
  int* row_last = row_last_.data();  // row i: zero right of this column
  for (Index k = 0; k < n; ++k) {
    row_of_(k) = static_cast<int>(k);
    row_last[k] = static_cast<int>(k);
  }
  for (Index j = 0; j < n; ++j) {  // the zero rows around each column (kPad), and the bounds
    std::fill(a + j * ld - kPad, a + j * ld, 0.0);
    std::fill(a + j * ld + n, a + j * ld + n + kPad, 0.0);
    // The rows between the column's first and last nonzero may reach column j (the columns go
    // in ascending order, so the last such column stays).
    const double* c = a + j * ld;
    const Index first = span_first ? span_first[j] : first_nonzero(c, 0, n - 1);
    const Index last = span_last ? span_last[j] : last_nonzero(c, first, n - 1);
    for (Index i = first; i <= last; ++i) row_last[i] = std::max(row_last[i], static_cast<int>(j));
    col_last[j] = static_cast<int>(std::max(j, last));
  }
  // The columns before `left` are zero from the current pivot row down (their last nonzero
  // rows are above it, and rows there change no more): a row swap starts at it.
  Index left = 0;
  for (Index k0 = 0; k0 < n; k0 += kPanel) {
    const Index p1 = std::min(n, k0 + kPanel);
    // Last nonzero row of the panel's columns of L: the trailing update runs down to it.
    Index last_panel = k0;
    for (Index k = k0; k < p1; ++k) {
      double* ck = a + k * ld;
      // Rows below the column's last nonzero take no part in this step.
      const Index last = std::max(k, last_nonzero(ck, k + 1, col_last[k]));
      Index p = 0;
      const double big = pivot_search(ck, k, last, p);
      if (!(big > 0.0)) return false;  // exactly zero column (or NaN)
      if (p != k) {
        // Row k's nonzeros move down to row p: the columns they land in reach row p now.
        const Index end = std::max(row_last[k], row_last[p]);
        while (left < k && col_last[left] < k) ++left;
        for (Index j = left; j <= end; ++j) {
          std::swap(a[k + j * ld], a[p + j * ld]);
          if (a[p + j * ld] != 0.0) col_last[j] = std::max(col_last[j], static_cast<int>(p));
        }
        std::swap(row_of_(k), row_of_(p));
        std::swap(row_last[k], row_last[p]);
      }
      last_panel = std::max(last_panel, last);
      if (last > k) {
        eliminate_in_panel(a, ld, k, last, p1);
        // Rows k+1 .. last may fill in the panel's columns after k, down to row last.
        const int fill = std::min(row_last[k], static_cast<int>(p1 - 1));
        for (Index i = k + 1; i <= last; ++i) row_last[i] = std::max(row_last[i], fill);
        for (Index j = k + 1; j < p1; ++j) col_last[j] = std::max(col_last[j], static_cast<int>(last));
      }
    }
    // (Only the last panel can be narrower, and no columns follow it.)
    // The trailing columns with a nonzero in the panel's rows end at the panel rows' last column.
    Index end = p1 - 1;
    for (Index i = k0; i < p1; ++i) end = std::max(end, static_cast<Index>(row_last[i]));
    const Index blocks = blocks_of_four(k0 + kPanel, last_panel);
    for (Index j = p1; j <= end; ++j) update_trailing_column<kPanel>(a, ld, k0, blocks, j);
    // The update fills rows p1 .. last_panel of those columns.
    if (end >= p1) {
      for (Index i = p1; i <= last_panel; ++i) row_last[i] = std::max(row_last[i], static_cast<int>(end));
      for (Index j = p1; j <= end; ++j) col_last[j] = std::max(col_last[j], static_cast<int>(last_panel));
    }
  }
  // Nonzero spans of each column of L and U for the solves. Rows above `top` end left of
  // column k (their row_last, a bound, is below k): the search for U's first nonzero starts
  // there, not at row 0.
  Index top = 0;
  for (Index k = 0; k < n; ++k) {
    const double* ck = a + k * ld;
    while (top < k && row_last[top] < k) ++top;
    const Index lo = std::max(k, last_nonzero(ck, k + 1, col_last[k]));
    const Index up = first_nonzero(ck, top, k - 1);  // k when none
    lower_(k) = static_cast<int>(lo);
    upper_(k) = static_cast<int>(up);
    inv_diag_(k) = 1.0 / ck[k];
  }
  ok_ = true;
  spans_bound_buffer_ = true;
  return true;
}

// The substitutions go four columns at a time: the triangle inside the four in registers,
// then one loop over the rows outside it with four multiply-adds a row, in blocks of four rows
// (kPad); the diagonal is applied by its stored reciprocals. One AXPY a column and a division a
// row, as before, left the solve dominated by the loops' set-up and the chain of divisions
// (0.7 us a solve of the benchmark's 46 x 46 tangent, 13 solves a step).
FFR_RT_CLONES
void SmallLU::solve_in_place(Eigen::Ref<Eigen::VectorXd> xv) const {
  const Index n = n_, ld = ld_;
  eigen_assert(xv.size() >= n);
  const double* a = buffer_.data() + kPad;
  const double* rd = inv_diag_.data();
  double* __restrict x = work_.data() + kPad;
  const auto A = [&](Index i, Index j) { return a[i + j * ld]; };
  // The right-hand side in the factors' row order, between zeros.
  for (Index k = 0; k < n; ++k) x[k] = xv[row_of_(k)];
  std::fill(x - kPad, x, 0.0);
  std::fill(x + n, x + n + kPad, 0.0);
  // Forward: unit lower L; column k is zero below row lower_(k).
  Index k0 = 0;
  for (; k0 + 4 <= n; k0 += 4) {
    double x0 = x[k0], x1 = x[k0 + 1], x2 = x[k0 + 2], x3 = x[k0 + 3];
    x1 -= A(k0 + 1, k0) * x0;
    x2 -= A(k0 + 2, k0) * x0 + A(k0 + 2, k0 + 1) * x1;
    x3 -= A(k0 + 3, k0) * x0 + A(k0 + 3, k0 + 1) * x1 + A(k0 + 3, k0 + 2) * x2;
    x[k0 + 1] = x1;
    x[k0 + 2] = x2;
    x[k0 + 3] = x3;
    const Index last = std::max({lower_(k0), lower_(k0 + 1), lower_(k0 + 2), lower_(k0 + 3)});
    const double *__restrict c0 = a + k0 * ld, *__restrict c1 = c0 + ld, *__restrict c2 = c1 + ld, *__restrict c3 = c2 + ld;
    const Index blocks = blocks_of_four(k0 + 4, last);
    for (Index b = 0; b < blocks; ++b) {
      const Index i0 = k0 + 4 + 4 * b;
      for (int r = 0; r < 4; ++r) {
        const Index i = i0 + r;
        x[i] -= c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
      }
    }
  }
  for (Index c = k0; c < n; ++c)  // the last columns: nothing below them
    for (Index r = c + 1; r < n; ++r) x[r] -= A(r, c) * x[c];
  // Back: U on and above the diagonal; column k is zero above row upper_(k). The rows above a
  // block go in blocks of four that end right above it, the first starting at most three rows
  // above the first nonzero (zeros, or the zero rows above the columns).
  Index k1 = n;
  for (; k1 >= 4; k1 -= 4) {
    const Index b = k1 - 4;
    double x0 = x[b], x1 = x[b + 1], x2 = x[b + 2], x3 = x[b + 3];
    x3 *= rd[b + 3];
    x2 = (x2 - A(b + 2, b + 3) * x3) * rd[b + 2];
    x1 = (x1 - A(b + 1, b + 2) * x2 - A(b + 1, b + 3) * x3) * rd[b + 1];
    x0 = (x0 - A(b, b + 1) * x1 - A(b, b + 2) * x2 - A(b, b + 3) * x3) * rd[b];
    x[b] = x0;
    x[b + 1] = x1;
    x[b + 2] = x2;
    x[b + 3] = x3;
    const Index first = std::min({upper_(b), upper_(b + 1), upper_(b + 2), upper_(b + 3)});
    const double *__restrict c0 = a + b * ld, *__restrict c1 = c0 + ld, *__restrict c2 = c1 + ld, *__restrict c3 = c2 + ld;
    const Index blocks = blocks_of_four(first, b - 1), i_lo = b - 4 * blocks;
    for (Index k = 0; k < blocks; ++k) {
      const Index i0 = i_lo + 4 * k;
      for (int r = 0; r < 4; ++r) {
        const Index i = i0 + r;
        x[i] -= c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
      }
    }
  }
  for (Index c = k1 - 1; c >= 0; --c) {  // the first columns: nothing above them
    x[c] *= rd[c];
    for (Index r = 0; r < c; ++r) x[r] -= A(r, c) * x[c];
  }
  for (Index k = 0; k < n; ++k) xv[k] = x[k];
}

}  // namespace ffr::runtime
