#pragma once
// The two numeric backends of CholmodFactor (FactorizationBackend), on one CHOLMOD symbolic
// analysis L: each computes the numeric factor of an upper-stored A and solves with it.
//
//   CholmodNumeric:    cholmod_l_factorize into L itself and cholmod_l_solve2, untouched; the
//                      reference the other is tested against.
//   SupernodalNumeric: the own supernodal factorization (tree_cholesky.hpp) into arrays of its
//                      own, packed (factor_packing.hpp) for the block substitutions
//                      (supernodal_solve.hpp). It only reads L's structure (super, pi, px, s,
//                      Perm); L stays symbolic.

#include "cholmod_bridge.hpp"
#include "dense_kernels.hpp"
#include "factor_packing.hpp"
#include "supernodal_solve.hpp"

#include <concepts>
#include <cstdint>
#include <memory>

namespace ffr::preproc::detail {

/// The outcome of a numeric factorization.
struct NumericResult {
  bool ok = false;             ///< false: the computation itself failed (c->status says why)
  std::int64_t minor = 0;      ///< first permuted column with a non-positive pivot; n if none
  double rcond = 0;            ///< (min |L_jj| / max |L_jj|)^2
  PivotRatio pivots{};         ///< min_j L_jj^2 / A_jj (FactorOptions::min_pivot_ratio)
};

/// What CholmodFactor needs of a numeric backend: factorize A (upper-stored, analysed as L) on
/// up to `threads` threads, then solve blocks of right-hand sides B (n x ncols, leading
/// dimension ldb) into X (ldx); B and X may alias.
template <class B>
concept NumericBackend = requires(B& b, const B& cb, const cholmod_sparse& A, const SparseMatrix& Aeigen,
                                  cholmod_factor& L, cholmod_common* c, unsigned threads, const double* rhs,
                                  double* x, std::int64_t n) {
  { b.factorize(A, Aeigen, L, c, threads) } -> std::same_as<NumericResult>;
  cb.solve(rhs, n, n, x, n);
  b.clear();
};

class CholmodNumeric {
 public:
  CholmodNumeric() = default;
  CholmodNumeric(const CholmodNumeric&) = delete;
  CholmodNumeric& operator=(const CholmodNumeric&) = delete;
  NumericResult factorize(const cholmod_sparse& A, const SparseMatrix& Aeigen, cholmod_factor& L, cholmod_common* c,
                          unsigned threads);
  void solve(const double* B, std::int64_t ldb, std::int64_t ncols, double* X, std::int64_t ldx) const;
  void clear();
  ~CholmodNumeric() { clear(); }

 private:
  cholmod_factor* L_ = nullptr;
  cholmod_common* c_ = nullptr;
  // cholmod_l_solve2's result and workspace, kept across calls so the Lanczos loop reuses them.
  mutable cholmod_dense *X_ = nullptr, *Y_ = nullptr, *E_ = nullptr;
};

class SupernodalNumeric {
 public:
  /// The dense kernels of the factorization (dense_kernels.hpp).
  void use(const DenseKernels& kernels) { kernels_ = &kernels; }

  NumericResult factorize(const cholmod_sparse& A, const SparseMatrix& Aeigen, cholmod_factor& L, cholmod_common* c,
                          unsigned threads);
  void solve(const double* B, std::int64_t ldb, std::int64_t ncols, double* X, std::int64_t ldx) const;
  void clear();

  std::int64_t packed_entries() const { return static_cast<std::int64_t>(values_.size()); }
  unsigned solve_threads() const { return solver_ ? solver_->threads() : 0u; }
  double solve_parallel_fraction() const { return solver_ ? solver_->parallel_fraction() : 0.0; }

 private:
  const DenseKernels* kernels_ = &select_dense_kernels(DenseKernelChoice::Auto);
  FactorValues values_;
  // The substitutions keep their interleaved workspace across calls (no allocation in the
  // Lanczos loop); solve() is const for the caller, the workspace is not.
  std::unique_ptr<SupernodalSolver> solver_;
};

static_assert(NumericBackend<CholmodNumeric>);
static_assert(NumericBackend<SupernodalNumeric>);

}  // namespace ffr::preproc::detail
