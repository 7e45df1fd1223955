// The pivot scan behind CholmodFactor's singularity test. A supernode s spans columns
// super[s] .. super[s+1]-1 and stores a dense column-major block of pi[s+1]-pi[s] rows
// starting at x[px[s]], so column j's diagonal sits at px[s] + (j - super[s]) * (nrows + 1)
// (CHOLMOD user guide, "cholmod_factor" supernodal fields).

#include "cholmod_bridge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ffr::preproc::detail {

PivotRatio min_pivot_ratio(const cholmod_factor& L, const double* x, const SparseMatrix& A) {
  const Eigen::VectorXd diag = A.diagonal();
  const auto* super = static_cast<const SuiteSparse_long*>(L.super);
  const auto* pi = static_cast<const SuiteSparse_long*>(L.pi);
  const auto* px = static_cast<const SuiteSparse_long*>(L.px);
  const auto* perm = static_cast<const SuiteSparse_long*>(L.Perm);
  PivotRatio r{std::numeric_limits<double>::infinity(), 0, 0};
  for (size_t sn = 0; sn < L.nsuper; ++sn) {
    const SuiteSparse_long nsrow = pi[sn + 1] - pi[sn];
    for (SuiteSparse_long j = super[sn]; j < super[sn + 1]; ++j) {
      const double l = x[px[sn] + (j - super[sn]) * (nsrow + 1)];
      const double ratio = l * l / diag[perm ? perm[j] : j];
      if (ratio < r.ratio) r = {ratio, j, perm ? perm[j] : j};
    }
  }
  return r;
}

}  // namespace ffr::preproc::detail

namespace ffr::preproc::detail {

double reciprocal_condition(const cholmod_factor& L, const double* x) {
  const auto* super = static_cast<const SuiteSparse_long*>(L.super);
  const auto* pi = static_cast<const SuiteSparse_long*>(L.pi);
  const auto* px = static_cast<const SuiteSparse_long*>(L.px);
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (size_t sn = 0; sn < L.nsuper; ++sn) {
    const SuiteSparse_long nsrow = pi[sn + 1] - pi[sn];
    for (SuiteSparse_long j = super[sn]; j < super[sn + 1]; ++j) {
      const double l = std::abs(x[px[sn] + (j - super[sn]) * (nsrow + 1)]);
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
  }
  return hi > 0 ? (lo / hi) * (lo / hi) : 0.0;
}

}  // namespace ffr::preproc::detail
