#pragma once
// The two matrix operators of shift-invert Lanczos for K x = lambda M x, written to the
// operator concepts of Spectra 1.0 (SymGEigsShiftSolver<OpType, BOpType,
// GEigsMode::ShiftInvert>: Scalar, rows(), cols(), set_shift(), perform_op()) and reused
// unchanged by the ARPACK driver (dsaupd mode 3 asks for exactly these two products).
//
//   ShiftInvertOp:  y = P (K - sigma M)^{-1} P^T x   through a CholmodFactor of K - sigma M
//   MassOp:         y = M x
//
// P = I - R R^T M is the M-orthogonal projector onto the complement of a deflation basis R
// (R^T M R = I), e.g. the rigid-body modes of a free body. The Lanczos vectors are
// M-orthogonal (Spectra and ARPACK both work in the M inner product) and the input of the
// inverse is M v, so P^T = I - M R R^T applied to the input and P to the output keep the
// whole Krylov space M-orthogonal to R: the excluded modes can never reappear, and
// P (K - sigma M)^{-1} M P stays M-self-adjoint, so the Lanczos theory is untouched.

#include "ffr/preproc/solver/cholmod_factor.hpp"
#include "ffr/preproc/solver/sparse_types.hpp"

#include <cstdint>
#include <functional>

namespace ffr::preproc {

/// An M-orthonormal basis to exclude from the eigen-solution, with M R precomputed.
struct Deflation {
  Eigen::MatrixXd R;   ///< n x r, R^T M R = I to round-off
  Eigen::MatrixXd MR;  ///< M R

  bool empty() const { return R.cols() == 0; }
  Eigen::Index rank() const { return R.cols(); }
  /// x <- P x = x - R (MR^T x): removes the M-projection on span(R).
  void project(double* x) const;
  /// f <- P^T f = f - MR (R^T f): the same for a vector already multiplied by M.
  void project_dual(double* f) const;
};

/// M-orthonormalizes the columns of R (two passes: eigen-decomposition of R^T M R, then a
/// Cholesky clean-up). Throws std::invalid_argument naming the problem when R has the wrong
/// number of rows, non-finite entries, or (nearly) linearly dependent columns in the M norm
/// (smallest/largest eigenvalue of R^T M R below rank_tol).
Deflation make_deflation(const SparseRef& M, SymmetricStorage storage,
                         const Eigen::Ref<const Eigen::MatrixXd>& R, double rank_tol = 1e-10);

class ShiftInvertOp {
 public:
  using Scalar = double;
  /// factor must hold K - sigma M (factorize_shifted); deflation may be null or empty.
  ShiftInvertOp(const CholmodFactor& factor, const Deflation* deflation);

  Eigen::Index rows() const { return factor_.rows(); }
  Eigen::Index cols() const { return factor_.rows(); }
  /// The solver announces its shift; it must be the one the factor was built with, since
  /// refactorizing here would hide the cost (and the memory check) from the caller.
  void set_shift(double sigma);
  /// y_out = P (K - sigma M)^{-1} P^T x_in.
  void perform_op(const double* x_in, double* y_out) const;
  /// The same for every column of X at once (one pass of the factor for the whole block).
  Eigen::MatrixXd apply_block(const Eigen::MatrixXd& X) const;
  /// The same into Y (resized to X's size; Y may be X itself): the block Lanczos's loop keeps
  /// its blocks instead of taking a new n x p result every step.
  void apply_block(const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) const;

  std::int64_t applications() const { return applications_; }
  /// Called after every application with the running count (progress reporting).
  void set_observer(std::function<void(std::int64_t)> f) { observer_ = std::move(f); }

 private:
  const CholmodFactor& factor_;
  const Deflation* deflation_;
  mutable Eigen::VectorXd work_;
  mutable std::int64_t applications_ = 0;
  std::function<void(std::int64_t)> observer_;
};

class MassOp {
 public:
  using Scalar = double;
  /// Keeps a reference to M: a SparseRef that outlives the operator (not a temporary one made
  /// from a SparseMatrix at the call, hence the deleted overload).
  MassOp(const SparseRef& M, SymmetricStorage storage) : M_(M), storage_(storage) {}
  MassOp(SparseRef&&, SymmetricStorage) = delete;
  Eigen::Index rows() const { return M_.rows(); }
  Eigen::Index cols() const { return M_.cols(); }
  /// y_out = M x_in.
  void perform_op(const double* x_in, double* y_out) const;
  /// Products computed, and products answered from the one-vector cache.
  std::int64_t products() const { return products_; }
  std::int64_t cache_hits() const { return hits_; }

 private:
  const SparseRef& M_;
  SymmetricStorage storage_;
  // Spectra's Lanczos asks for M f twice in a row for the same f (the M-norm of the residual,
  // then V^T M f for its reorthogonalization). Remembering the last input and product (and
  // comparing the input bit for bit, n doubles against the ~50 n bytes of M) saves those.
  mutable Eigen::VectorXd last_x_, last_y_;
  mutable std::int64_t products_ = 0, hits_ = 0;
};

}  // namespace ffr::preproc
