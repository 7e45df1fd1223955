#include "ffr/preproc/solver/eigen_solver.hpp"

#include "eigen_backends.hpp"
#include "../stopwatch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

namespace ffr::preproc {

const char* to_string(EigenBackend b) {
  switch (b) {
    case EigenBackend::Spectra: return "Spectra";
    case EigenBackend::Arpack: return "ARPACK";
    case EigenBackend::Dense: return "dense";
    case EigenBackend::Block: return "block Lanczos";
    case EigenBackend::Slepc: return "SLEPc Krylov-Schur";
  }
  return "?";
}

const char* to_string(EigenStatus s) {
  switch (s) {
    case EigenStatus::NotRun: return "not run";
    case EigenStatus::Success: return "success";
    case EigenStatus::FactorizationFailed: return "factorization failed";
    case EigenStatus::NotConverged: return "not converged";
    case EigenStatus::CheckFailed: return "check failed";
    case EigenStatus::BadInput: return "bad input";
  }
  return "?";
}

namespace {

using Clock = std::chrono::steady_clock;

void validate_options(const EigenOptions& o) {
  auto bad = [](const std::string& m) { throw std::invalid_argument("eigen-solver options: " + m); };
  if (o.nev < 1) bad("nev must be >= 1, got " + std::to_string(o.nev));
  if (!std::isfinite(o.sigma)) bad("sigma must be finite");
  if (std::isnan(o.lambda_max) || o.lambda_max <= o.sigma) {
    std::ostringstream os;
    os << "lambda_max (" << o.lambda_max << ") must be above sigma (" << o.sigma << ")";
    bad(os.str());
  }
  if (o.max_modes < 1) bad("max_modes must be >= 1");
  if (o.ncv < 0) bad("ncv must be >= 0 (0 = automatic)");
  if (o.max_restarts < 1) bad("max_restarts must be >= 1");
  if (!(o.lanczos_tol > 0) || !(o.residual_tol > 0) || !(o.orthonormality_tol > 0))
    bad("tolerances must be positive");
}

// Deterministic start vector in the complement of the deflation basis (same for every
// backend and run, so results are reproducible).
Eigen::VectorXd start_vector(Eigen::Index n, const Deflation& d) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
  d.project(v.data());
  return v;
}

}  // namespace

EigenSolver::EigenSolver(EigenOptions options) : options_(std::move(options)) {}

const EigenResult& EigenSolver::compute(const SparseRef& K, const SparseRef& M) {
  return run_recorded(K, M, nullptr);
}

const EigenResult& EigenSolver::compute(const SparseRef& K, const SparseRef& M,
                                        const CholmodFactor& factor) {
  return run_recorded(K, M, &factor);
}

// Whatever escapes run() (including exceptions of Spectra or of a CHOLMOD solve in the
// middle of the Lanczos loop) leaves a status and message in info().
const EigenResult& EigenSolver::run_recorded(const SparseRef& K, const SparseRef& M,
                                             const CholmodFactor* given) {
  try {
    return run(K, M, given);
  } catch (const std::exception& e) {
    if (info_.status == EigenStatus::NotRun || info_.status == EigenStatus::Success) {
      info_.status = EigenStatus::NotConverged;
      info_.message = e.what();
    }
    throw;
  }
}

// The steps of EigenSolver::run, each a function of what it computes; `Run` carries what one
// step hands to the next and reports progress and failures into the solver's info.
struct EigenSolver::Run {
  Run(EigenSolver& s, const SparseRef& K_in, const SparseRef& M_in) : solver(s), K(K_in), M(M_in) {}
  EigenSolver& solver;
  const SparseRef& K;
  const SparseRef& M;
  SymmetricStorage sK = SymmetricStorage::Full, sM = SymmetricStorage::Full;
  Deflation deflation;
  Eigen::Index n = 0, n_eff = 0;  // n_eff: the DOFs left after deflation
  bool by_limit = false;          // a lambda_max query rather than a count
  EigenProgress progress;

  const EigenOptions& options() const { return solver.options_; }
  EigenInfo& info() { return solver.info_; }
  void report(const char* stage) {
    progress.stage = stage;
    if (solver.progress_) solver.progress_(progress);
  }
  void fail(EigenStatus s, const std::string& msg) {
    info().status = s;
    info().message = msg;
  }
  [[noreturn]] void refuse(const std::string& msg) {
    fail(EigenStatus::BadInput, msg);
    throw std::invalid_argument(msg);
  }

  // Options, sizes, symmetry, the deflation basis made M-orthonormal. Bad input throws
  // std::invalid_argument with status BadInput.
  void validate_pencil() {
    const EigenOptions& o = options();
    try {
      validate_options(o);
      if (K.rows() != M.rows() || K.cols() != M.cols()) {
        std::ostringstream os;
        os << "K is " << K.rows() << " x " << K.cols() << " but M is " << M.rows() << " x " << M.cols();
        throw std::invalid_argument(os.str());
      }
      sK = validate_symmetric(K, "K");
      sM = validate_symmetric(M, "M");
      deflation = make_deflation(M, sM, o.deflation);
      if (K.rows() - deflation.rank() < 1) throw std::invalid_argument("deflation basis leaves no degrees of freedom");
    } catch (const std::exception& e) {
      fail(EigenStatus::BadInput, e.what());
      throw;
    }
    n = K.rows();
    n_eff = n - deflation.rank();
    by_limit = std::isfinite(o.lambda_max);
    if (!by_limit && o.nev > n_eff) {
      std::ostringstream os;
      os << "eigen-solver: " << o.nev << " eigenpairs requested but only " << n_eff
         << " degrees of freedom remain (n = " << n << ", deflation rank " << deflation.rank() << ")";
      refuse(os.str());
    }
  }

  // The factor of K - sigma M: the caller's (checked to be of this shift), else computed into
  // `own`; none for the dense backend, nor for slepc (MUMPS factorizes it, distributed).
  const CholmodFactor* factor_shifted_stiffness(const CholmodFactor* given, CholmodFactor& own) {
    const EigenOptions& o = options();
    const auto t0 = Clock::now();
    const CholmodFactor* factor = given;
    try {
      if (given) {
        if (!given->factorized() || given->rows() != n)
          throw std::invalid_argument("eigen-solver: the given factor is not a valid factorization of an n x n matrix");
        const double have = given->info().shift;
        if (std::abs(have - o.sigma) > 1e-12 * std::max(1.0, std::abs(o.sigma))) {
          std::ostringstream os;
          os << "eigen-solver: the given factor is of K - " << have << " M but sigma = " << o.sigma;
          throw std::invalid_argument(os.str());
        }
      } else if (o.backend != EigenBackend::Dense && o.backend != EigenBackend::Slepc) {
        report("factorize");
        own.factorize_shifted(K, M, o.sigma);
        factor = &own;
      }
    } catch (const NotPositiveDefiniteError& e) {
      std::ostringstream os;
      os << "eigen-solver: factorizing K - sigma*M with sigma = " << o.sigma << ": " << e.what();
      fail(EigenStatus::FactorizationFailed, os.str());
      throw NotPositiveDefiniteError(os.str(), e.column, e.permuted_column, e.numerically_singular);
    } catch (const std::invalid_argument& e) {
      fail(EigenStatus::BadInput, e.what());
      throw;
    } catch (const std::exception& e) {
      fail(EigenStatus::FactorizationFailed, e.what());
      throw;
    }
    info().factorize_seconds = seconds_since(t0);
    if (factor) info().factor = factor->info().stats;
    return factor;
  }

  // The backend for a request of nev pairs: Lanczos needs nev < ncv <= n_eff, otherwise the
  // whole spectrum is wanted anyway and the dense backend takes it if it may.
  EigenBackend backend_for(int nev, EigenBackend wanted) {
    const EigenOptions& o = options();
    if (wanted != EigenBackend::Dense && nev >= n_eff) {
      if (n_eff > o.dense_max_n) {
        std::ostringstream os;
        os << "eigen-solver: " << nev << " eigenpairs of a problem with " << n_eff
           << " DOF need the dense backend, which is limited to dense_max_n = " << o.dense_max_n;
        refuse(os.str());
      }
      return EigenBackend::Dense;
    }
    if (wanted == EigenBackend::Dense && n_eff > o.dense_max_n) {
      std::ostringstream os;
      os << "eigen-solver: dense backend asked for a problem with " << n_eff << " DOF, above dense_max_n = "
         << o.dense_max_n;
      refuse(os.str());
    }
    return wanted;
  }

  // nev Ritz pairs of the shift-invert operator (K - sigma M)^{-1} M by the block Lanczos,
  // which hands over to Spectra when its basis does not fit or it does not converge; or by
  // Spectra or ARPACK directly.
  detail::BackendOutcome shift_invert_lanczos(const CholmodFactor& factor, int nev, EigenBackend& backend,
                                              const Eigen::VectorXd& v0) {
    const EigenOptions& o = options();
    int ncv = o.ncv > 0 ? o.ncv : std::max(2 * nev + 1, nev + 20);
    ncv = static_cast<int>(std::min<Eigen::Index>(std::max(ncv, nev + 1), n_eff));
    ShiftInvertOp op(factor, &deflation);
    MassOp bop(M, sM);
    const std::int64_t before = info().operator_applications;
    op.set_observer([&](std::int64_t k) {
      progress.operator_applications = before + k;
      report("lanczos");
    });
    detail::BackendOutcome run;
    bool done = false;
    if (backend == EigenBackend::Block) {
      // Block 4 and a basis of ~4 nev (about what 20..30 modes need without a restart) were
      // the fastest on the 100k-DOF plate and the 250k-DOF shell tube of tools/bench/reduce.
      const int p = o.block_size > 0 ? o.block_size : 4;
      const Eigen::Index m_max = o.ncv > 0 ? std::max(o.ncv, nev + 2 * p) : std::max(4 * nev + 2 * p, nev + 4 * p);
      if (2 * m_max <= n_eff) {
        const detail::BlockRequest breq{nev, p, m_max, std::min(o.max_restarts, 100), o.lanczos_tol, o.sigma,
                                        20240611ULL, o.mass_product};
        run = detail::run_block_lanczos(op, M, sM, deflation, breq);
        done = run.success;
      }
      if (!done) backend = EigenBackend::Spectra;  // too small for the block basis, or no convergence
    }
    if (!done) {
      const detail::LanczosRequest req{nev, ncv, o.max_restarts, o.lanczos_tol, o.sigma, &v0};
      run = backend == EigenBackend::Arpack ? detail::run_arpack(op, bop, req) : detail::run_spectra(op, bop, req);
    }
    info().operator_applications = before + op.applications();
    return run;
  }

  // nev pairs by SLEPc's Krylov-Schur, distributed over the session's ranks.
  detail::BackendOutcome slepc_krylov_schur(int nev, const Eigen::VectorXd& v0) {
    const EigenOptions& o = options();
    const int ncv = o.ncv > 0 ? static_cast<int>(std::min<Eigen::Index>(std::max(o.ncv, nev + 1), n_eff)) : 0;
    const detail::SlepcRequest req{nev, ncv, o.max_restarts, o.lanczos_tol, o.sigma, &v0, o.mumps};
    return detail::run_slepc(K, sK, M, sM, deflation, req);
  }

  // The converged pairs, in as many rounds as a lambda_max query needs: nev grows (Weyl's law)
  // until a converged eigenvalue lies above lambda_max.
  detail::BackendOutcome ritz_pairs(const CholmodFactor* factor, EigenBackend& backend) {
    const EigenOptions& o = options();
    const auto t0 = Clock::now();
    detail::BackendOutcome run;
    int nev = static_cast<int>(std::min<Eigen::Index>(o.nev, n_eff));
    backend = o.backend;
    const Eigen::VectorXd v0 = start_vector(n, deflation);
    for (;;) {
      ++info().rounds;
      progress.round = info().rounds;
      progress.nev = nev;
      progress.iterations = progress.converged = -1;
      backend = backend_for(nev, backend);
      info().backend_used = backend;
      report("lanczos");
      if (backend == EigenBackend::Dense) run = detail::run_dense(K, sK, M, sM, deflation, o.sigma);
      else if (backend == EigenBackend::Slepc) run = slepc_krylov_schur(nev, v0);
      else run = shift_invert_lanczos(*factor, nev, backend, v0);
      info().backend_used = backend;
      info().iterations = run.iterations;
      progress.iterations = run.iterations;
      progress.converged = run.converged;
      progress.operator_applications = info().operator_applications;
      report("lanczos");
      if (!run.success) {
        fail(EigenStatus::NotConverged, run.message);
        throw EigenSolverError(run.message);
      }
      if (!by_limit || backend == EigenBackend::Dense || run.lambda.size() == 0) break;
      const double top = run.lambda.maxCoeff();
      if (top > o.lambda_max || nev >= n_eff) break;
      if (nev >= o.max_modes) {
        std::ostringstream os;
        os << "eigen-solver: more than max_modes = " << o.max_modes << " eigenvalues lie below lambda_max = "
           << o.lambda_max << " (the " << nev << "th is " << top << ")";
        fail(EigenStatus::BadInput, os.str());
        throw EigenSolverError(os.str());
      }
      nev = static_cast<int>(std::min<std::int64_t>({static_cast<std::int64_t>(detail::grow_nev(nev, top, o.lambda_max, o.sigma)),
                                                     static_cast<std::int64_t>(o.max_modes) + 1,
                                                     static_cast<std::int64_t>(n_eff)}));
    }
    info().lanczos_seconds = seconds_since(t0);
    if (backend == EigenBackend::Dense) {
      // Keep only what is needed before the Rayleigh-Ritz pass (cubic in the column count).
      Eigen::Index m = run.lambda.size();
      if (!by_limit) m = std::min<Eigen::Index>(m, o.nev);
      else
        m = std::count_if(run.lambda.data(), run.lambda.data() + m, [&](double l) { return l <= o.lambda_max; });
      run.X.conservativeResize(Eigen::NoChange, m);
    }
    return run;
  }

  // Rayleigh-Ritz on the Ritz vectors (selection, signs) and the checks of every pair; a block
  // Lanczos result that misses them gets one step of subspace iteration first.
  void rayleigh_ritz_and_checks(Eigen::MatrixXd X, const CholmodFactor* factor, EigenBackend backend) {
    const EigenOptions& o = options();
    EigenResult& result = solver.result_;
    const auto t0 = Clock::now();
    report("verify");
    detail::finish_eigenpairs(K, sK, M, sM, deflation, std::move(X), by_limit ? 0 : o.nev, o.lambda_max, result);
    info().verify_seconds = seconds_since(t0);
    if (by_limit && static_cast<Eigen::Index>(result.lambda.size()) > o.max_modes) {
      std::ostringstream os;
      os << "eigen-solver: " << result.lambda.size() << " eigenvalues lie below lambda_max = " << o.lambda_max
         << ", more than max_modes = " << o.max_modes;
      fail(EigenStatus::BadInput, os.str());
      throw EigenSolverError(os.str());
    }
    std::string why = detail::check_eigenpairs(result, o);
    if (!why.empty() && backend == EigenBackend::Block) {
      // One step of subspace iteration on the returned vectors, then the checks again. The
      // block method's Ritz vectors carry the error of its Cholesky-QR normalizations
      // (condition squared) and what is left of the start block; one more block solve with
      // the factor damps both by the gaps theta_j / theta_i, at the cost of one solve a vector.
      // A loose Lanczos tolerance needs it (EigenBlock tests).
      ShiftInvertOp op(*factor, &deflation);
      Eigen::MatrixXd Y = op.apply_block(sym_multiply(M, sM, result.X));
      info().operator_applications += op.applications();
      ++info().refinements;
      detail::finish_eigenpairs(K, sK, M, sM, deflation, std::move(Y), static_cast<int>(result.lambda.size()),
                                o.lambda_max, result);
      info().verify_seconds = seconds_since(t0);
      why = detail::check_eigenpairs(result, o);
    }
    if (!why.empty()) {
      const std::string msg = "eigen-solver check failed: " + why;
      fail(EigenStatus::CheckFailed, msg);
      throw EigenSolverError(msg);
    }
  }
};

const EigenResult& EigenSolver::run(const SparseRef& K, const SparseRef& M, const CholmodFactor* given) {
  info_ = EigenInfo{};
  result_ = EigenResult{};
  Run step(*this, K, M);
  step.validate_pencil();
  FactorOptions fo = options_.factor;
  fo.check_symmetry = false;  // K and M were validated above
  // With sigma < 0, K - sigma M is definite by construction (K semi-definite, M definite) and
  // its small pivots only measure how close the rigid-body modes (lambda = 0) are to sigma:
  // a free body's intended geometry, harmless since the deflation removes exactly those
  // directions from every solve. Non-positive pivots (an indefinite K) are still refused.
  if (options_.sigma < 0) fo.min_pivot_ratio = 0;
  CholmodFactor own(fo);
  const CholmodFactor* factor = step.factor_shifted_stiffness(given, own);
  EigenBackend backend = options_.backend;
  detail::BackendOutcome ritz = step.ritz_pairs(factor, backend);
  step.rayleigh_ritz_and_checks(std::move(ritz.X), factor, backend);
  info_.status = EigenStatus::Success;
  step.report("done");
  return result_;
}

}  // namespace ffr::preproc
