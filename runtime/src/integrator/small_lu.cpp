// Right-looking LU with partial pivoting that skips the zeros of a multibody tangent
// (see small_lu.hpp for why it is not Eigen::PartialPivLU).
#include "ffr/runtime/small_lu.hpp"

#include <cmath>
#include <utility>

namespace ffr::runtime {

using Eigen::Index;

void SmallLU::resize(Index n) {
  lu_.setZero(n, n);
  perm_.setZero(n);
  lower_.setZero(n);
  upper_.setZero(n);
  ok_ = false;
}

bool SmallLU::factorize() {
  const Index n = lu_.rows();
  ok_ = false;
  for (Index k = 0; k < n; ++k) {
    auto ck = lu_.col(k);
    // Rows below the column's last nonzero take no part in this step.
    Index last = n - 1;
    while (last > k && ck(last) == 0.0) --last;
    Index p = k;
    double big = std::abs(ck(k));
    for (Index i = k + 1; i <= last; ++i) {
      const double v = std::abs(ck(i));
      if (v > big) {
        big = v;
        p = i;
      }
    }
    if (!(big > 0.0)) return false;  // exactly zero column (or NaN)
    perm_(k) = static_cast<int>(p);
    if (p != k) lu_.row(k).swap(lu_.row(p));
    const Index len = last - k;
    if (len == 0) continue;
    ck.segment(k + 1, len) /= ck(k);
    for (Index j = k + 1; j < n; ++j) {
      const double f = lu_(k, j);
      if (f != 0.0) lu_.col(j).segment(k + 1, len).noalias() -= f * ck.segment(k + 1, len);
    }
  }
  // Nonzero spans of each column of L and U for the solves.
  for (Index k = 0; k < n; ++k) {
    Index lo = n - 1;
    while (lo > k && lu_(lo, k) == 0.0) --lo;
    Index up = 0;
    while (up < k && lu_(up, k) == 0.0) ++up;
    lower_(k) = static_cast<int>(lo);
    upper_(k) = static_cast<int>(up);
  }
  ok_ = true;
  return true;
}

void SmallLU::solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const {
  const Index n = lu_.rows();
  for (Index k = 0; k < n; ++k)
    if (perm_(k) != k) std::swap(x(k), x(perm_(k)));
  for (Index k = 0; k < n; ++k) {
    const Index len = lower_(k) - k;
    const double xk = x(k);
    if (len > 0 && xk != 0.0) x.segment(k + 1, len).noalias() -= xk * lu_.col(k).segment(k + 1, len);
  }
  for (Index k = n - 1; k >= 0; --k) {
    x(k) /= lu_(k, k);
    const Index up = upper_(k), len = k - up;
    const double xk = x(k);
    if (len > 0 && xk != 0.0) x.segment(up, len).noalias() -= xk * lu_.col(k).segment(up, len);
  }
}

}  // namespace ffr::runtime
