#include "numeric_backends.hpp"

#include "tree_cholesky.hpp"
#include "ffr/preproc/solver/solver_errors.hpp"

#include <algorithm>
#include <string>

namespace ffr::preproc::detail {

NumericResult CholmodNumeric::factorize(const cholmod_sparse& A, const SparseMatrix& Aeigen, cholmod_factor& L,
                                        cholmod_common* c, unsigned) {
  clear();
  NumericResult r;
  cholmod_sparse view = A;
  r.ok = cholmod_l_factorize(&view, &L, c) && c->status >= CHOLMOD_OK;
  if (!r.ok) return r;
  r.minor = static_cast<std::int64_t>(L.minor);
  if (r.minor < static_cast<std::int64_t>(L.n)) return r;
  L_ = &L;
  c_ = c;
  r.rcond = cholmod_l_rcond(&L, c);
  r.pivots = min_pivot_ratio(L, static_cast<const double*>(L.x), Aeigen);
  return r;
}

void CholmodNumeric::solve(const double* B, std::int64_t ldb, std::int64_t ncols, double* X, std::int64_t ldx) const {
  const auto n = static_cast<std::int64_t>(L_->n);
  // Blocks of up to 16 columns: X_, Y_ and E_ stay at 16 n values, whatever ncols is.
  constexpr std::int64_t kChunk = 16;
  for (std::int64_t j0 = 0; j0 < ncols; j0 += kChunk) {
    const std::int64_t w = std::min(kChunk, ncols - j0);
    cholmod_dense b = view_dense(B + j0 * ldb, static_cast<size_t>(n), static_cast<size_t>(w), static_cast<size_t>(ldb));
    if (!cholmod_l_solve2(CHOLMOD_A, L_, &b, nullptr, &X_, nullptr, &Y_, &E_, c_))
      throw SolverError("CHOLMOD's solve (cholmod_l_solve2) failed (CHOLMOD status " + std::to_string(c_->status) + ")");
    const auto* x = static_cast<const double*>(X_->x);
    const auto ld = static_cast<std::int64_t>(X_->d);
    for (std::int64_t j = 0; j < w; ++j) std::copy(x + j * ld, x + j * ld + n, X + (j0 + j) * ldx);
  }
}

void CholmodNumeric::clear() {
  if (c_) {
    cholmod_l_free_dense(&X_, c_);
    cholmod_l_free_dense(&Y_, c_);
    cholmod_l_free_dense(&E_, c_);
  }
  L_ = nullptr;
  c_ = nullptr;
}

NumericResult SupernodalNumeric::factorize(const cholmod_sparse& A, const SparseMatrix& Aeigen, cholmod_factor& L,
                                           cholmod_common* c, unsigned threads) {
  clear();
  NumericResult r;
  if (!values_.allocate(static_cast<std::size_t>(tree_cholesky_values(L)))) {
    c->status = CHOLMOD_OUT_OF_MEMORY;
    return r;
  }
  r.ok = true;
  r.minor = tree_cholesky(A, L, values_.data(), threads, *kernels_);
  if (r.minor < static_cast<std::int64_t>(L.n)) return r;
  r.rcond = reciprocal_condition(L, values_.data());
  r.pivots = min_pivot_ratio(L, values_.data(), Aeigen);
  // Only the substitutions read the values from here on: packed, most of the diagonal blocks'
  // upper triangles are given back (factor_packing.hpp).
  std::vector<SuiteSparse_long> offsets = packed_offsets(L);
  pack_values(L, values_.data(), offsets);
  values_.shrink(static_cast<std::size_t>(offsets.back()));
  // At most 8 threads, as the other threaded vector work (run_parts.hpp): every sweep starts
  // and joins them.
  solver_ = std::make_unique<SupernodalSolver>(L, values_.data(), std::move(offsets), std::min(threads, 8u));
  return r;
}

void SupernodalNumeric::solve(const double* B, std::int64_t ldb, std::int64_t ncols, double* X,
                              std::int64_t ldx) const {
  solver_->solve(B, ldb, ncols, X, ldx);
}

void SupernodalNumeric::clear() {
  solver_.reset();
  values_.release();
}

}  // namespace ffr::preproc::detail
