#pragma once
#include <functional>
// Private interface between EigenSolver and its three backends, and the post-processing
// every backend's output goes through.

#include "ffr/preproc/solver/eigen_solver.hpp"
#include "ffr/preproc/solver/shift_invert_ops.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace ffr::preproc::detail {

/// Next request size when every converged eigenvalue is still below lambda_max (a
/// max_frequency_hz reduction): the eigenvalue count of a 3D body grows like lambda^{3/2}
/// (Weyl's law), so extrapolate with that exponent and at least double. Shared by the serial
/// EigenSolver and the distributed SLEPc path, so both ask for the same sizes.
inline int grow_nev(int nev, double top, double lambda_max, double sigma) {
  const double ratio = (lambda_max - sigma) / std::max(top - sigma, 1e-300);
  const double est = 1.2 * nev * std::pow(ratio, 1.5);
  return static_cast<int>(std::min(std::max(2.0 * nev, est), 1e9));
}

struct LanczosRequest {
  int nev = 0;
  int ncv = 0;
  int max_restarts = 0;
  double tol = 0;
  double sigma = 0;
  const Eigen::VectorXd* v0 = nullptr;  ///< starting vector, already projected by P
  MumpsOptions mumps;
};

struct BackendOutcome {
  Eigen::VectorXd lambda;  ///< converged eigenvalues (any order)
  Eigen::MatrixXd X;       ///< matching vectors (any normalization)
  int iterations = 0;      ///< restarts used
  int converged = 0;
  bool success = false;
  std::string message;     ///< why not, if !success
};

struct BlockRequest {
  int nev = 0;
  int block = 0;            ///< vectors per block
  Eigen::Index max_basis = 0;  ///< basis size before a thick restart (>= nev + 2 block)
  int max_restarts = 0;
  double tol = 0;
  double sigma = 0;
  unsigned long long seed = 0;  ///< of the pseudo-random start block
  /// Y = M X in place of the products with M (EigenOptions::mass_product), when set.
  std::function<void(const Eigen::MatrixXd& X, Eigen::MatrixXd& Y)> mass_product;
};

/// Block shift-invert Lanczos (block_lanczos_backend.cpp). On failure (breakdown, no
/// convergence, a problem too small for the basis) returns success = false with a message.
BackendOutcome run_block_lanczos(ShiftInvertOp& op, const SparseRef& M, SymmetricStorage sM,
                                 const Deflation& deflation, const BlockRequest& req);

/// How many of the leading min(nev, theta.size()) Ritz pairs (theta descending) have residual
/// ||coupling.col(i)|| <= tol * theta_i. Never looks beyond the pairs the basis holds.
int count_converged_ritz_pairs(const Eigen::VectorXd& theta, const Eigen::MatrixXd& coupling, int nev, double tol);

/// Spectra 1.0 SymGEigsShiftSolver<ShiftInvertOp, MassOp, GEigsMode::ShiftInvert>.
BackendOutcome run_spectra(ShiftInvertOp& op, MassOp& bop, const LanczosRequest& req);

/// ARPACK-ng dsaupd/dseupd, bmat = 'G', which = 'LM', mode 3 (shift-invert).
BackendOutcome run_arpack(ShiftInvertOp& op, MassOp& bop, const LanczosRequest& req);

struct SlepcRequest {
  int nev = 0;
  int ncv = 0;  ///< 0: SLEPc's default
  int max_restarts = 0;
  double tol = 0;
  double sigma = 0;
  const Eigen::VectorXd* v0 = nullptr;  ///< starting vector, already projected by P
  MumpsOptions mumps;                   ///< its factorization's ordering and out-of-core choice
};

/// SLEPc's Krylov-Schur, shift-invert with a MUMPS Cholesky factor of K - sigma M, distributed
/// over the ranks of the active ParallelSession (slepc_backend.cpp); collective: every rank
/// calls it with the same K, M and deflation and gets every converged pair. Throws
/// std::invalid_argument when the backend is not built in or no session is active, and
/// std::runtime_error with PETSc's message when a PETSc or SLEPc call fails.
BackendOutcome run_slepc(const SparseRef& K, SymmetricStorage sK, const SparseRef& M, SymmetricStorage sM,
                         const Deflation& deflation, const SlepcRequest& req);

/// X = A^{-1} B for a symmetric positive definite A and dense B (n x k), by a MUMPS Cholesky
/// factor distributed over the ranks of the active ParallelSession (slepc_backend.cpp), one
/// solve a column; collective: every rank passes the same A and B and gets all of X. A failed
/// factorization (A not definite) throws NotPositiveDefiniteError with column -1 (MUMPS does
/// not say where); other PETSc failures std::runtime_error.
Eigen::MatrixXd distributed_spd_solve(const SparseRef& A, SymmetricStorage sA, const Eigen::MatrixXd& B,
                                      const MumpsOptions& mumps);

/// All eigenpairs with lambda > sigma of the pencil restricted to the M-orthogonal
/// complement of the deflation basis, by Eigen's dense solver. n <= a few thousand.
BackendOutcome run_dense(const SparseRef& K, SymmetricStorage sK, const SparseRef& M,
                         SymmetricStorage sM, const Deflation& deflation, double sigma);

/// Rayleigh-Ritz on span(P X), selection (first `keep` pairs, or all with lambda <=
/// lambda_max), sign convention, and the residual / orthonormality / deflation checks.
/// Fills everything in `out`; does not throw on failed checks (the caller decides).
void finish_eigenpairs(const SparseRef& K, SymmetricStorage sK, const SparseRef& M,
                       SymmetricStorage sM, const Deflation& deflation, Eigen::MatrixXd X,
                       int keep, double lambda_max, EigenResult& out);

/// "" if every pair passes (see EigenSolver's header for the criteria), else the reason.
std::string check_eigenpairs(const EigenResult& r, const EigenOptions& o);

/// Flips each column so that its first component with |x_i| >= kSignThreshold max|x| is > 0.
Eigen::VectorXd normalize_signs(Eigen::MatrixXd& X);

}  // namespace ffr::preproc::detail
