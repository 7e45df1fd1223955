#pragma once
// Generalized symmetric eigen-solver K x = lambda M x: the eigenvalues nearest above a shift
// sigma, by shift-invert Lanczos on (K - sigma M)^{-1} M (the factor comes from CHOLMOD).
//
//   EigenOptions o;  o.nev = 20;  o.sigma = -1.0;  o.deflation = R;   // free body
//   EigenSolver s(o);
//   s.set_progress([](const EigenProgress& p) { ... });               // optional
//   const EigenResult& r = s.compute(K, M);   // lambda ascending, X M-orthonormal
//
// Conventions:
//   * sigma must lie below every wanted eigenvalue so that K - sigma M is positive definite
//     (a free body: sigma < 0 and the rigid-body modes passed as deflation, so no singular
//     matrix is ever factorized). If it is not, factorization fails with
//     NotPositiveDefiniteError.
//   * eigenvalues are lambda = omega^2 in the units of K/M; a frequency limit f_max [Hz]
//     is lambda_max = (2 pi f_max)^2 (the caller converts).
//   * vectors are M-normalized (X^T M X = I), eigenvalues ascending, and each vector's sign
//     is fixed: the first component (in DOF order) whose magnitude reaches
//     kSignThreshold * max|x_i| is positive. (Not "the largest component": symmetric
//     structures have mirrored components of equal magnitude and opposite sign, and
//     rounding would then pick the sign.)
//   * every returned pair is checked and EigenSolverError is thrown if a check fails (the
//     result stays readable in result()/info()). A pair passes if relative_residual <=
//     residual_tol, or if its residual is at the rounding level of the products K x and
//     M x themselves: backward_error <= kRoundoffBackwardError (~450 eps). The second case
//     covers what the relative residual cannot judge: ill-conditioned parts, whose lowest
//     modes have a rounding floor eps * lambda_max / lambda in the relative residual, and
//     zero eigenvalues (an undeflated rigid-body mode: noise over noise). Also checked:
//     orthonormality_error, deflation_error <= orthonormality_tol.
//   * M must be symmetric positive (semi-)definite. Full or upper-only storage (see
//     sparse_types.hpp).
//   * the library never prints; progress goes to the callback, status to info().

#include "ffr/preproc/solver/cholmod_factor.hpp"
#include "ffr/preproc/solver/mumps_options.hpp"
#include "ffr/preproc/solver/sparse_types.hpp"

#include <cstdint>
#include <functional>
#include <limits>
#include <string>

namespace ffr::preproc {

enum class EigenBackend {
  Spectra,  ///< Spectra 1.0 SymGEigsShiftSolver, shift-invert mode
  Arpack,   ///< ARPACK-ng dsaupd/dseupd, reverse communication, mode 3
  Dense,    ///< Eigen's dense GeneralizedSelfAdjointEigenSolver; small problems only
  Block,    ///< block shift-invert Lanczos (blocks of solves with the factor; the default); falls
            ///< back to Spectra if it does not converge or the problem is too small for its basis
  Slepc,    ///< SLEPc's Krylov-Schur over MPI, shift-invert factorized by MUMPS (needs a
            ///< ParallelSession, solver/parallel_session.hpp; no CHOLMOD factor is used)
};
const char* to_string(EigenBackend b);

inline constexpr double kSignThreshold = 0.6180339887498949;
inline constexpr double kRoundoffBackwardError = 1e-13;

struct EigenOptions {
  /// Number of eigenpairs wanted (ignored when lambda_max is set, except as first guess).
  int nev = 10;
  /// If finite: return all eigenvalues in (sigma, lambda_max]; nev grows until the largest
  /// converged eigenvalue exceeds lambda_max (or the whole spectrum is computed).
  double lambda_max = std::numeric_limits<double>::infinity();
  /// Upper bound on modes for a lambda_max query; exceeding it is an error, not truncation.
  int max_modes = 5000;
  double sigma = 0.0;
  /// Block (the default, as in the part file): fastest on the reducer's benchmark parts.
  EigenBackend backend = EigenBackend::Block;
  /// Basis to exclude exactly (ndof x r), e.g. rigid-body modes; need not be orthonormal.
  Eigen::MatrixXd deflation;
  /// Lanczos basis size; 0 = max(2 nev + 1, nev + 20), capped by the problem size.
  int ncv = 0;
  int max_restarts = 1000;
  /// Block backend: vectors per block (0 = 4); its basis size before a restart is ncv if
  /// set, else max(4 nev + 2 block, nev + 4 block).
  int block_size = 0;
  double lanczos_tol = 1e-12;  ///< Ritz convergence tolerance handed to Spectra/ARPACK
  double residual_tol = 1e-8;  ///< limit on the relative residual of every returned pair
  double orthonormality_tol = 1e-10;  ///< limit on max|X^T M X - I|
  /// Largest problem (DOF after deflation) the Dense backend or the automatic fallback may
  /// take. Lanczos needs nev < ncv <= n; smaller problems are handed to Dense if they fit.
  std::int64_t dense_max_n = 3000;
  /// Optional Y = M X for the block backend's products with M (X with a block's columns), where
  /// the caller has a cheaper form of the same M (the reductions: from the solids' node mass
  /// matrix). M itself is still what the checks and the other backends use.
  std::function<void(const Eigen::MatrixXd& X, Eigen::MatrixXd& Y)> mass_product;
  /// Ordering and memory limit of the factorization of K - sigma M. Its min_pivot_ratio
  /// (the mechanism test) applies for sigma >= 0 only: for sigma < 0 small pivots are the
  /// intended nearness of the rigid-body modes (set to 0 internally).
  FactorOptions factor;
  /// The slepc backend's MUMPS factorization (its ordering, out-of-core factors).
  MumpsOptions mumps;
};

/// What the progress callback sees. Counts are cumulative over the whole compute() call.
struct EigenProgress {
  const char* stage = "";         ///< "factorize", "lanczos", "verify", "done"
  int round = 0;                  ///< lambda_max queries: 1, 2, ... as nev grows
  int nev = 0;                    ///< eigenpairs requested in this round
  std::int64_t operator_applications = 0;  ///< solves with K - sigma M so far
  int iterations = -1;            ///< restarts of the finished round (-1 while running)
  int converged = -1;             ///< converged pairs of the finished round (-1 while running)
};
using EigenProgressCallback = std::function<void(const EigenProgress&)>;

struct EigenResult {
  Eigen::VectorXd lambda;               ///< ascending
  Eigen::MatrixXd X;                    ///< n x nev, M-orthonormal, sign-normalized
  Eigen::VectorXd relative_residual;    ///< ||K x - l M x|| / (||K x|| + |l| ||M x||)
  Eigen::VectorXd backward_error;       ///< ||K x - l M x|| / ((||K||_1 + |l| ||M||_1) ||x||)
  double orthonormality_error = 0;      ///< max |X^T M X - I|
  double deflation_error = 0;           ///< max |R^T M X| (R M-orthonormal); 0 without deflation
  double max_relative_residual = 0;
  Eigen::MatrixXd XtKX;                 ///< X^T K X, from the checks' product K X (modal stiffness)
  Eigen::MatrixXd XtMX;                 ///< X^T M X, from the checks' product M X (modal mass)
};

enum class EigenStatus { NotRun, Success, FactorizationFailed, NotConverged, CheckFailed, BadInput };
const char* to_string(EigenStatus s);

struct EigenInfo {
  EigenStatus status = EigenStatus::NotRun;
  std::string message;
  EigenBackend backend_used = EigenBackend::Spectra;
  int rounds = 0;
  int iterations = 0;                   ///< restarts of the last round
  std::int64_t operator_applications = 0;
  /// Block backend: subspace-iteration steps taken because the Ritz vectors missed a check (0 or 1)
  int refinements = 0;
  double factorize_seconds = 0;         ///< analysis + numeric factorization
  double lanczos_seconds = 0;
  double verify_seconds = 0;            ///< Rayleigh-Ritz clean-up and checks
  FactorStatistics factor;
};

class EigenSolver {
 public:
  explicit EigenSolver(EigenOptions options = {});

  void set_progress(EigenProgressCallback cb) { progress_ = std::move(cb); }

  /// Factorizes K - sigma M and solves. Throws std::invalid_argument (bad input),
  /// NotPositiveDefiniteError / InsufficientMemoryError (factorization), EigenSolverError.
  const EigenResult& compute(const SparseRef& K, const SparseRef& M);

  /// Same with a factor of K - sigma M the caller already holds (e.g. Craig-Bampton reuses
  /// the factor of K_ii from its static solves; sigma must match factor.info().shift).
  const EigenResult& compute(const SparseRef& K, const SparseRef& M,
                             const CholmodFactor& factor);

  const EigenResult& result() const { return result_; }
  const EigenInfo& info() const { return info_; }
  const EigenOptions& options() const { return options_; }

 private:
  const EigenResult& run_recorded(const SparseRef& K, const SparseRef& M,
                                  const CholmodFactor* given);
  const EigenResult& run(const SparseRef& K, const SparseRef& M,
                         const CholmodFactor* given);
  struct Run;  // the steps of run() (eigen_solver.cpp)
  EigenOptions options_;
  EigenProgressCallback progress_;
  EigenResult result_;
  EigenInfo info_;
};

}  // namespace ffr::preproc
