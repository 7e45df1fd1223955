// The distributed pencil (slepc_distributed.hpp): K and M summed by PETSc from each rank's
// element contributions into row-distributed matrices, and the serial EigenSolver's
// post-processing (eigen_postprocess.cpp) on them: every n-long quantity is kept as this rank's
// block of rows, and what the serial code computes as a product over all rows (X^T K X, the
// column norms, the projection on the deflation basis) is the sum over the ranks of the
// products over each block.
#include "slepc_distributed.hpp"

#include "eigen_backends.hpp"
#include "ffr/preproc/solver/parallel_session.hpp"
#include "ffr/preproc/solver/solver_errors.hpp"

#include <Eigen/Eigenvalues>

#include <chrono>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#if FFR_HAVE_SLEPC
#include "petsc_mumps.hpp"
#include "petsc_support.hpp"
#include "../stopwatch.hpp"
#endif

namespace ffr::preproc::detail {

std::int64_t first_row(std::int64_t n, int rank, int size) {
  const std::int64_t q = n / size, r = n % size;
  return rank * q + std::min<std::int64_t>(rank, r);
}
std::int64_t rows_of(std::int64_t n, int rank, int size) { return n / size + (rank < n % size ? 1 : 0); }

#if FFR_HAVE_SLEPC

namespace {

bool several() { return parallel_session_active(); }

// The sum over the ranks of a small dense matrix, in place.
void sum_matrix(Eigen::MatrixXd& A) { sum_over_ranks(A.data(), static_cast<std::size_t>(A.size())); }

struct VecPair {
  Vec x = nullptr, y = nullptr;
  ~VecPair() {
    if (x) VecDestroy(&x);
    if (y) VecDestroy(&y);
  }
};

// This rank's rows of A X (X: this rank's rows, one column at a time).
Eigen::MatrixXd apply(Mat A, const Eigen::MatrixXd& X) {
  VecPair v;
  check(MatCreateVecs(A, &v.x, &v.y), "MatCreateVecs");
  Eigen::MatrixXd Y(X.rows(), X.cols());
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    PetscScalar* a = nullptr;
    check(VecGetArray(v.x, &a), "VecGetArray");
    std::copy(X.col(j).data(), X.col(j).data() + X.rows(), a);
    check(VecRestoreArray(v.x, &a), "VecRestoreArray");
    check(MatMult(A, v.x, v.y), "MatMult");
    const PetscScalar* b = nullptr;
    check(VecGetArrayRead(v.y, &b), "VecGetArrayRead");
    std::copy(b, b + X.rows(), Y.col(j).data());
    check(VecRestoreArrayRead(v.y, &b), "VecRestoreArrayRead");
  }
  return Y;
}

// The whole of X (n x m) on every rank from each rank's block of rows.
Eigen::MatrixXd gather_rows(const Eigen::MatrixXd& X_local, std::int64_t n) {
  const int size = session_size();
  std::vector<int> counts(static_cast<std::size_t>(size)), displs(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) {
    counts[static_cast<std::size_t>(r)] = static_cast<int>(rows_of(n, r, size));
    displs[static_cast<std::size_t>(r)] = static_cast<int>(first_row(n, r, size));
  }
  Eigen::MatrixXd X(n, X_local.cols());
  for (Eigen::Index j = 0; j < X_local.cols(); ++j)
    MPI_Allgatherv(X_local.col(j).data(), static_cast<int>(X_local.rows()), MPI_DOUBLE, X.col(j).data(), counts.data(),
                   displs.data(), MPI_DOUBLE, PETSC_COMM_WORLD);
  return X;
}

// A matrix of this rank's rows, summed over what every rank passes (its upper triangle
// mirrored): PETSc's COO assembly sends each entry to the rank that owns its row.
Mat summed_matrix(const SparseMatrix& A, bool upper, PetscInt n_local) {
  const auto* outer = A.outerIndexPtr();
  const auto* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  PetscCount count = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (auto k = outer[j]; k < outer[j + 1]; ++k) count += (upper && inner[k] != j) ? 2 : 1;
  Mat B = nullptr;
  check(MatCreate(PETSC_COMM_WORLD, &B), "MatCreate");
  check(MatSetSizes(B, n_local, n_local, static_cast<PetscInt>(A.rows()), static_cast<PetscInt>(A.cols())), "MatSetSizes");
  check(MatSetType(B, MATAIJ), "MatSetType");
  {
    std::vector<PetscScalar> v(static_cast<std::size_t>(count));
    {
      std::vector<PetscInt> ci(static_cast<std::size_t>(count)), cj(static_cast<std::size_t>(count));
      std::size_t p = 0;
      for (Eigen::Index j = 0; j < A.outerSize(); ++j)
        for (auto k = outer[j]; k < outer[j + 1]; ++k) {
          const auto i = static_cast<PetscInt>(inner[k]);
          ci[p] = i, cj[p] = static_cast<PetscInt>(j), v[p++] = val[k];
          if (upper && i != j) ci[p] = static_cast<PetscInt>(j), cj[p] = i, v[p++] = val[k];
        }
      check(MatSetPreallocationCOO(B, count, ci.data(), cj.data()), "MatSetPreallocationCOO");
    }
    check(MatSetValuesCOO(B, v.data(), ADD_VALUES), "MatSetValuesCOO");
  }
  check(MatSetOption(B, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  // The COO maps PETSc keeps for further MatSetValuesCOO are as large as the matrix; a copy
  // without them is what the solve keeps.
  Mat C = nullptr;
  check(MatDuplicate(B, MAT_COPY_VALUES, &C), "MatDuplicate");
  MatDestroy(&B);
  check(MatSetOption(C, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  return C;
}

}  // namespace

int session_rank() {
  int r = 0;
  if (several()) MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
int session_size() {
  int s = 1;
  if (several()) MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}
void sum_over_ranks(double* data, std::size_t n) {
  if (several() && n > 0) MPI_Allreduce(MPI_IN_PLACE, data, static_cast<int>(n), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
}
void sum_over_ranks(std::int64_t* data, std::size_t n) {
  if (several() && n > 0) MPI_Allreduce(MPI_IN_PLACE, data, static_cast<int>(n), MPI_INT64_T, MPI_SUM, PETSC_COMM_WORLD);
}
double max_over_ranks(double v) {
  if (several()) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return v;
}
std::pair<double, int> min_over_ranks(double v) {
  struct {
    double v;
    int r;
  } in{v, session_rank()}, out{v, in.r};
  if (several()) MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MINLOC, PETSC_COMM_WORLD);
  return {out.v, out.r};
}
std::string broadcast(std::string text, int root) {
  if (!several()) return text;
  int len = static_cast<int>(text.size());
  MPI_Bcast(&len, 1, MPI_INT, root, PETSC_COMM_WORLD);
  text.resize(static_cast<std::size_t>(len));
  MPI_Bcast(text.data(), len, MPI_CHAR, root, PETSC_COMM_WORLD);
  return text;
}

struct DistributedPencil::Impl {
  Mat K = nullptr, M = nullptr;
  PetscInt n = 0, n_local = 0, r0 = 0;
  ~Impl() {
    if (K) MatDestroy(&K);
    if (M) MatDestroy(&M);
  }
};

DistributedPencil::DistributedPencil(const SparseMatrix& K_part, const SparseMatrix& M_part, bool upper)
    : impl_(std::make_unique<Impl>()) {
  if (!parallel_session_active())
    throw std::invalid_argument("distributed pencil: needs the program's MPI/SLEPc session (ffr::preproc::ParallelSession)");
  if (K_part.rows() != M_part.rows() || K_part.rows() != K_part.cols() || M_part.rows() != M_part.cols())
    throw std::invalid_argument("distributed pencil: K and M must be square and of one size");
  impl_->n = static_cast<PetscInt>(K_part.rows());
  impl_->n_local = static_cast<PetscInt>(rows_of(impl_->n, session_rank(), session_size()));
  impl_->r0 = static_cast<PetscInt>(first_row(impl_->n, session_rank(), session_size()));
  impl_->K = summed_matrix(K_part, upper, impl_->n_local);
  impl_->M = summed_matrix(M_part, upper, impl_->n_local);
}

DistributedPencil::~DistributedPencil() = default;

std::int64_t DistributedPencil::rows() const { return impl_->n; }

std::int64_t DistributedPencil::local_nonzeros() const {
  MatInfo a, b;
  check(MatGetInfo(impl_->K, MAT_LOCAL, &a), "MatGetInfo");
  check(MatGetInfo(impl_->M, MAT_LOCAL, &b), "MatGetInfo");
  return static_cast<std::int64_t>(a.nz_used + b.nz_used);
}

std::int64_t DistributedPencil::massless_dofs() const {
  Vec d = nullptr;
  check(MatCreateVecs(impl_->M, &d, nullptr), "MatCreateVecs");
  std::int64_t zero = 0;
  check(MatGetDiagonal(impl_->M, d), "MatGetDiagonal");
  const PetscScalar* a = nullptr;
  VecGetArrayRead(d, &a);
  for (PetscInt i = 0; i < impl_->n_local; ++i) zero += a[i] != 0.0 ? 0 : 1;
  VecRestoreArrayRead(d, &a);
  VecDestroy(&d);
  sum_over_ranks(&zero, 1);
  return zero;
}

DistributedModes DistributedPencil::eigenmodes(const Eigen::MatrixXd& R, const EigenOptions& o,
                                                const std::function<void(const std::string&)>& progress) const {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const Impl& P = *impl_;
  const Eigen::Index nl = P.n_local;
  if (R.cols() > 0 && R.rows() != P.n) throw std::invalid_argument("distributed eigen-solve: the deflation basis has the wrong size");
  // The deflation basis, this rank's rows, made M-orthonormal: R <- R L^{-T} with L L^T = R^T M R.
  Eigen::MatrixXd Rl = R.cols() > 0 ? Eigen::MatrixXd(R.middleRows(P.r0, nl)) : Eigen::MatrixXd(nl, 0), MRl;
  if (Rl.cols() > 0) {
    MRl = apply(P.M, Rl);
    Eigen::MatrixXd G = Rl.transpose() * MRl;
    sum_matrix(G);
    G = 0.5 * (G + G.transpose());
    Eigen::LLT<Eigen::MatrixXd> llt(G);
    if (llt.info() != Eigen::Success)
      throw std::invalid_argument("distributed eigen-solve: the deflation basis is linearly dependent in the M norm");
    const Eigen::MatrixXd Linv_t = llt.matrixL().solve(Eigen::MatrixXd::Identity(G.rows(), G.cols())).transpose();
    Rl = Rl * Linv_t;
    MRl = MRl * Linv_t;
  }
  auto project = [&](Eigen::MatrixXd& X) {
    if (Rl.cols() == 0) return;
    Eigen::MatrixXd C = MRl.transpose() * X;
    sum_matrix(C);
    X -= Rl * C;
  };
  const std::int64_t n_eff = P.n - Rl.cols();
  const bool by_limit = std::isfinite(o.lambda_max);
  if (!by_limit && o.nev > n_eff) {
    std::ostringstream os;
    os << "eigen-solver: " << o.nev << " eigenpairs requested but only " << n_eff << " degrees of freedom remain";
    throw std::invalid_argument(os.str());
  }

  // The start vector of every backend (the same pseudo-random numbers as EigenSolver's), this
  // rank's rows, projected.
  Eigen::MatrixXd v0(nl, 1);
  {
    std::mt19937_64 rng(20240611);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (PetscInt i = 0; i < P.n; ++i) {
      const double x = u(rng);
      if (i >= P.r0 && i < P.r0 + nl) v0(i - P.r0, 0) = x;
    }
    project(v0);
  }
  std::vector<Vec> defl(static_cast<std::size_t>(Rl.cols()));
  struct Vecs {
    std::vector<Vec>* v;
    ~Vecs() {
      for (Vec& x : *v)
        if (x) VecDestroy(&x);
    }
  } defl_guard{&defl};
  auto make_vec = [&](const double* x, Vec& v) {
    check(VecCreateMPI(PETSC_COMM_WORLD, nl, P.n, &v), "VecCreateMPI");
    PetscScalar* a = nullptr;
    check(VecGetArray(v, &a), "VecGetArray");
    std::copy(x, x + nl, a);
    check(VecRestoreArray(v, &a), "VecRestoreArray");
  };
  for (Eigen::Index c = 0; c < Rl.cols(); ++c) make_vec(Rl.col(c).data(), defl[static_cast<std::size_t>(c)]);

  DistributedModes out;
  Eigen::VectorXd lambda;
  Eigen::MatrixXd X;  // this rank's rows
  int nev = static_cast<int>(std::min<std::int64_t>(o.nev, n_eff));
  for (;;) {
    if (nev >= n_eff)
      throw EigenSolverError("eigen-solver (slepc, distributed): " + std::to_string(nev) + " eigenpairs of a problem with " +
                             std::to_string(n_eff) + " DOF: the whole spectrum; reduce it with the serial path");
    ++out.rounds;
    if (progress) progress("slepc: round " + std::to_string(out.rounds) + ", nev " + std::to_string(nev));
    struct EpsGuard {
      EPS e = nullptr;
      Vec start = nullptr, x = nullptr;
      ~EpsGuard() {
        if (e) EPSDestroy(&e);
        if (start) VecDestroy(&start);
        if (x) VecDestroy(&x);
      }
    } g;
    check(EPSCreate(PETSC_COMM_WORLD, &g.e), "EPSCreate");
    check(EPSSetOperators(g.e, P.K, P.M), "EPSSetOperators");
    check(EPSSetProblemType(g.e, EPS_GHEP), "EPSSetProblemType");
    check(EPSSetType(g.e, EPSKRYLOVSCHUR), "EPSSetType");
    check(EPSSetWhichEigenpairs(g.e, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
    check(EPSSetTarget(g.e, o.sigma), "EPSSetTarget");
    const PetscInt ncv = o.ncv > 0 ? static_cast<PetscInt>(std::min<std::int64_t>(std::max(o.ncv, nev + 1), n_eff)) : PETSC_DEFAULT;
    check(EPSSetDimensions(g.e, nev, ncv, PETSC_DEFAULT), "EPSSetDimensions");
    check(EPSSetTolerances(g.e, o.lanczos_tol, o.max_restarts), "EPSSetTolerances");
    ST st = nullptr;
    KSP ksp = nullptr;
    PC pc = nullptr;
    check(EPSGetST(g.e, &st), "EPSGetST");
    check(STSetType(st, STSINVERT), "STSetType");
    check(STGetKSP(st, &ksp), "STGetKSP");
    check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
    check(KSPGetPC(ksp, &pc), "KSPGetPC");
    check(PCSetType(pc, PCCHOLESKY), "PCSetType");
    check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    if (!defl.empty()) check(EPSSetDeflationSpace(g.e, static_cast<PetscInt>(defl.size()), defl.data()), "EPSSetDeflationSpace");
    make_vec(v0.data(), g.start);
    check(EPSSetInitialSpace(g.e, 1, &g.start), "EPSSetInitialSpace");
    const MumpsChoices mumps(o.mumps, kEigenSolvePrefix);
    check(EPSSetFromOptions(g.e), "EPSSetFromOptions");
    // The set-up factorizes K - sigma M: its failure or its size is known before the iterations.
    out.factor = mumps_outcome(EPSSetUp(g.e), "EPSSetUp", pc, mumps);
    if (progress && !out.factor.empty()) progress("slepc: " + out.factor);
    mumps_outcome(EPSSolve(g.e), "EPSSolve", pc, mumps);
    PetscInt nconv = 0, its = 0;
    check(EPSGetConverged(g.e, &nconv), "EPSGetConverged");
    check(EPSGetIterationNumber(g.e, &its), "EPSGetIterationNumber");
    out.iterations = static_cast<int>(its);
    if (nconv < nev) {
      EPSConvergedReason reason;
      EPSGetConvergedReason(g.e, &reason);
      std::ostringstream os;
      os << "eigen-solver (slepc): Krylov-Schur converged " << nconv << " of " << nev << " eigenpairs in " << its
         << " restarts (" << EPSConvergedReasons[reason] << "); try a larger ncv or more restarts";
      throw EigenSolverError(os.str());
    }
    lambda.resize(nconv);
    X.resize(nl, nconv);
    check(MatCreateVecs(P.K, &g.x, nullptr), "MatCreateVecs");
    for (PetscInt i = 0; i < nconv; ++i) {
      PetscScalar kr = 0, ki = 0;
      check(EPSGetEigenpair(g.e, i, &kr, &ki, g.x, nullptr), "EPSGetEigenpair");
      lambda(i) = kr;
      const PetscScalar* a = nullptr;
      check(VecGetArrayRead(g.x, &a), "VecGetArrayRead");
      std::copy(a, a + nl, X.col(i).data());
      check(VecRestoreArrayRead(g.x, &a), "VecRestoreArrayRead");
    }
    if (!by_limit || lambda.size() == 0) break;
    const double top = lambda.maxCoeff();
    if (top > o.lambda_max) break;
    if (nev >= o.max_modes) {
      std::ostringstream os;
      os << "eigen-solver: more than max_modes = " << o.max_modes << " eigenvalues lie below lambda_max = " << o.lambda_max;
      throw EigenSolverError(os.str());
    }
    nev = static_cast<int>(std::min<std::int64_t>({static_cast<std::int64_t>(grow_nev(nev, top, o.lambda_max, o.sigma)),
                                                   static_cast<std::int64_t>(o.max_modes) + 1, n_eff}));
  }
  out.solve_seconds = seconds_since(t0);
  const auto t1 = Clock::now();
  if (progress) progress("slepc: Rayleigh-Ritz and checks");

  // Rayleigh-Ritz on span(P X), as finish_eigenpairs, with the products over the ranks' rows summed.
  project(X);
  {
    Eigen::RowVectorXd nrm2 = X.colwise().squaredNorm();
    sum_over_ranks(nrm2.data(), static_cast<std::size_t>(nrm2.size()));
    for (Eigen::Index j = 0; j < X.cols(); ++j)
      if (nrm2(j) > 0) X.col(j) /= std::sqrt(nrm2(j));
  }
  Eigen::MatrixXd KX = apply(P.K, X), MX = apply(P.M, X);
  {
    Eigen::MatrixXd Ks = X.transpose() * KX, Ms = X.transpose() * MX;
    sum_matrix(Ks);
    sum_matrix(Ms);
    Ks = 0.5 * (Ks + Ks.transpose());
    Ms = 0.5 * (Ms + Ms.transpose());
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rr(Ks, Ms);
    lambda = rr.eigenvalues();
    X = X * rr.eigenvectors();
    KX = KX * rr.eigenvectors();
    MX = MX * rr.eigenvectors();
  }
  Eigen::Index m = lambda.size();
  if (!by_limit) m = std::min<Eigen::Index>(m, o.nev);
  else
    while (m > 0 && lambda[m - 1] > o.lambda_max) --m;
  if (by_limit && m > o.max_modes) {
    std::ostringstream os;
    os << "eigen-solver: " << m << " eigenvalues lie below lambda_max = " << o.lambda_max << ", more than max_modes = "
       << o.max_modes;
    throw EigenSolverError(os.str());
  }
  lambda.conservativeResize(m);
  X.conservativeResize(Eigen::NoChange, m);
  KX.conservativeResize(Eigen::NoChange, m);
  MX.conservativeResize(Eigen::NoChange, m);
  // The sign convention on the whole vectors (the first large component, in global order).
  out.X = gather_rows(X, P.n);
  const Eigen::VectorXd signs = normalize_signs(out.X);
  for (Eigen::Index j = 0; j < m; ++j) {
    X.col(j) *= signs[j];
    KX.col(j) *= signs[j];
    MX.col(j) *= signs[j];
  }

  // The checks of check_eigenpairs: residuals, backward errors, orthonormality, deflation.
  EigenResult res;
  res.lambda = lambda;
  PetscReal nK = 0, nM = 0;
  check(MatNorm(P.K, NORM_1, &nK), "MatNorm");
  check(MatNorm(P.M, NORM_1, &nM), "MatNorm");
  Eigen::MatrixXd sq(3, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    sq(0, j) = (KX.col(j) - lambda[j] * MX.col(j)).squaredNorm();
    sq(1, j) = KX.col(j).squaredNorm();
    sq(2, j) = MX.col(j).squaredNorm();
  }
  sum_matrix(sq);
  res.relative_residual.resize(m);
  res.backward_error.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double l = lambda[j], r = std::sqrt(sq(0, j));
    const double denom = std::sqrt(sq(1, j)) + std::abs(l) * std::sqrt(sq(2, j));
    res.relative_residual[j] = denom > 0 ? r / denom : r;
    const double bden = (nK + std::abs(l) * nM) * out.X.col(j).norm();
    res.backward_error[j] = bden > 0 ? r / bden : r;
  }
  res.XtKX = X.transpose() * KX;
  res.XtMX = X.transpose() * MX;
  sum_matrix(res.XtKX);
  sum_matrix(res.XtMX);
  res.max_relative_residual = m > 0 ? res.relative_residual.maxCoeff() : 0.0;
  res.orthonormality_error = m > 0 ? (res.XtMX - Eigen::MatrixXd::Identity(m, m)).cwiseAbs().maxCoeff() : 0.0;
  if (m > 0 && Rl.cols() > 0) {
    Eigen::MatrixXd D = MRl.transpose() * X;
    sum_matrix(D);
    res.deflation_error = D.cwiseAbs().maxCoeff();
  }
  const std::string why = check_eigenpairs(res, o);
  if (!why.empty()) throw EigenSolverError("eigen-solver check failed: " + why);
  out.lambda = std::move(res.lambda);
  out.XtKX = std::move(res.XtKX);
  out.XtMX = std::move(res.XtMX);
  out.max_relative_residual = res.max_relative_residual;
  out.orthonormality_error = res.orthonormality_error;
  out.verify_seconds = seconds_since(t1);
  return out;
}

#else

int session_rank() { return 0; }
int session_size() { return 1; }
void sum_over_ranks(double*, std::size_t) {}
void sum_over_ranks(std::int64_t*, std::size_t) {}
double max_over_ranks(double v) { return v; }
std::pair<double, int> min_over_ranks(double v) { return {v, 0}; }
std::string broadcast(std::string text, int) { return text; }

struct DistributedPencil::Impl {};
DistributedPencil::DistributedPencil(const SparseMatrix&, const SparseMatrix&, bool) {
  throw std::invalid_argument("distributed pencil: the slepc backend is not built into this program");
}
DistributedPencil::~DistributedPencil() = default;
std::int64_t DistributedPencil::rows() const { return 0; }
std::int64_t DistributedPencil::local_nonzeros() const { return 0; }
std::int64_t DistributedPencil::massless_dofs() const { return 0; }
DistributedModes DistributedPencil::eigenmodes(const Eigen::MatrixXd&, const EigenOptions&,
                                               const std::function<void(const std::string&)>&) const {
  return {};
}

#endif

}  // namespace ffr::preproc::detail
