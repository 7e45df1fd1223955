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
  lu_.setZero(n, n);
  perm_.setZero(n);
  lower_.setZero(n);
  upper_.setZero(n);
  inv_diag_.setZero(n);
  ok_ = false;
}

// The kernels are plain loops over raw columns, compiled at -O3 and for AVX2 and AVX-512 as well
// (kernel_clones.hpp): Eigen's dynamic segments cost a call and an alignment prologue per AXPY,
// and a factorisation of the benchmark's tangent makes about a thousand AXPYs of 10 to 40
// entries.
FFR_RT_CLONES
bool SmallLU::factorize() {
  const Index n = lu_.rows();
  double* a = lu_.data();
  ok_ = false;
  for (Index k = 0; k < n; ++k) {
    double* ck = a + k * n;
    // Rows below the column's last nonzero take no part in this step.
    Index last = n - 1;
    while (last > k && ck[last] == 0.0) --last;
    Index p = k;
    double big = std::abs(ck[k]);
    for (Index i = k + 1; i <= last; ++i) {
      const double v = std::abs(ck[i]);
      if (v > big) {
        big = v;
        p = i;
      }
    }
    if (!(big > 0.0)) return false;  // exactly zero column (or NaN)
    perm_(k) = static_cast<int>(p);
    if (p != k)
      for (Index j = 0; j < n; ++j) std::swap(a[k + j * n], a[p + j * n]);
    const Index len = last - k;
    if (len == 0) continue;
    const double inv = 1.0 / ck[k];
    double* __restrict l = ck + k + 1;
    for (Index i = 0; i < len; ++i) l[i] *= inv;
    for (Index j = k + 1; j < n; ++j) {
      double* __restrict cj = a + j * n;
      const double f = cj[k];
      if (f == 0.0) continue;
      double* __restrict u = cj + k + 1;
      for (Index i = 0; i < len; ++i) u[i] -= f * l[i];
    }
  }
  // Nonzero spans of each column of L and U for the solves.
  for (Index k = 0; k < n; ++k) {
    const double* ck = a + k * n;
    Index lo = n - 1;
    while (lo > k && ck[lo] == 0.0) --lo;
    Index up = 0;
    while (up < k && ck[up] == 0.0) ++up;
    lower_(k) = static_cast<int>(lo);
    upper_(k) = static_cast<int>(up);
    inv_diag_(k) = 1.0 / ck[k];
  }
  ok_ = true;
  return true;
}

// The substitutions go four columns at a time: the triangle inside the four in registers,
// then one loop over the rows outside it with four multiply-adds a row; the diagonal is
// applied by its stored reciprocals. One AXPY a column and a division a row, as before, left
// the solve dominated by the loops' set-up and the chain of divisions (0.7 us a solve of the
// benchmark's 46 x 46 tangent, 13 solves a step).
FFR_RT_CLONES
void SmallLU::solve_in_place(Eigen::Ref<Eigen::VectorXd> xv) const {
  const Index n = lu_.rows();
  const double* a = lu_.data();
  const double* rd = inv_diag_.data();
  double* __restrict x = xv.data();
  const auto A = [&](Index i, Index j) { return a[i + j * n]; };
  for (Index k = 0; k < n; ++k)
    if (perm_(k) != k) std::swap(x[k], x[perm_(k)]);
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
    const double *__restrict c0 = a + k0 * n, *__restrict c1 = c0 + n, *__restrict c2 = c1 + n, *__restrict c3 = c2 + n;
    for (Index i = k0 + 4; i <= last; ++i) x[i] -= c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
  }
  for (Index c = k0; c < n; ++c)  // the last columns: nothing below them
    for (Index r = c + 1; r < n; ++r) x[r] -= A(r, c) * x[c];
  // Back: U on and above the diagonal; column k is zero above row upper_(k).
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
    const double *__restrict c0 = a + b * n, *__restrict c1 = c0 + n, *__restrict c2 = c1 + n, *__restrict c3 = c2 + n;
    for (Index i = first; i < b; ++i) x[i] -= c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
  }
  for (Index c = k1 - 1; c >= 0; --c) {  // the first columns: nothing above them
    x[c] *= rd[c];
    for (Index r = 0; r < c; ++r) x[r] -= A(r, c) * x[c];
  }
}

}  // namespace ffr::runtime
