// The distributed backend "slepc": SLEPc's Krylov-Schur on the pencil (K, M) in shift-invert
// mode, (K - sigma M)^{-1} factorized by MUMPS (Cholesky), over the ranks of the job's
// ParallelSession. Every rank holds K and M whole (the pipeline before the eigen-solve runs on
// each); each copies only its block of rows into PETSc's distributed matrices, so the
// factorization and the Krylov vectors are distributed, and the converged eigenvectors are
// gathered back to every rank for the Rayleigh-Ritz pass and the checks of EigenSolver. This is
// the replicated path (Craig-Bampton, stiffening, preload, a part's own matrices); the free and
// clamped reductions take the distributed one (slepc_distributed.hpp), where no rank holds K
// or M whole.
#include "eigen_backends.hpp"
#include "ffr/preproc/solver/parallel_session.hpp"
#include "ffr/preproc/solver/solver_errors.hpp"

#include <sstream>
#include <stdexcept>

#if FFR_HAVE_SLEPC
#include "petsc_mumps.hpp"
#include "petsc_support.hpp"

#include <algorithm>
#include <numeric>
#include <vector>
#endif

namespace ffr::preproc::detail {

#if FFR_HAVE_SLEPC
namespace {

// Rows [r0, r1) of the symmetric matrix A (either triangle implied by `storage`) in CSR with
// global, ascending column indices: what MatCreateMPIAIJWithArrays copies for this rank.
struct LocalRows {
  std::vector<PetscInt> ia, ja;
  std::vector<PetscScalar> va;
};

LocalRows local_rows(const SparseRef& A, SymmetricStorage storage, PetscInt r0, PetscInt r1) {
  const bool upper = storage == SymmetricStorage::UpperOnly || storage == SymmetricStorage::Diagonal;
  const auto* outer = A.outerIndexPtr();
  const auto* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  const PetscInt m = r1 - r0;
  LocalRows L;
  L.ia.assign(static_cast<std::size_t>(m) + 1, 0);
  // Column j holds (i, j); stored upper, it also stands for (j, i).
  auto visit = [&](auto&& add) {
    for (Eigen::Index j = 0; j < A.outerSize(); ++j)
      for (auto k = outer[j]; k < outer[j + 1]; ++k) {
        const Eigen::Index i = inner[k];
        if (i >= r0 && i < r1) add(i, j, val[k]);
        if (upper && i != j && j >= r0 && j < r1) add(j, i, val[k]);
      }
  };
  visit([&](Eigen::Index i, Eigen::Index, double) { ++L.ia[static_cast<std::size_t>(i - r0) + 1]; });
  for (PetscInt r = 0; r < m; ++r) L.ia[static_cast<std::size_t>(r) + 1] += L.ia[static_cast<std::size_t>(r)];
  L.ja.resize(static_cast<std::size_t>(L.ia.back()));
  L.va.resize(L.ja.size());
  std::vector<PetscInt> fill(L.ia.begin(), L.ia.end() - 1);
  visit([&](Eigen::Index i, Eigen::Index j, double v) {
    const auto p = static_cast<std::size_t>(fill[static_cast<std::size_t>(i - r0)]++);
    L.ja[p] = static_cast<PetscInt>(j);
    L.va[p] = v;
  });
  // In columns visited in ascending order the rows come out sorted (the lower part of a row,
  // from its own column, before its diagonal, and the upper part from the later columns); a
  // matrix with unsorted columns is sorted here.
  for (PetscInt r = 0; r < m; ++r) {
    const auto b = static_cast<std::size_t>(L.ia[static_cast<std::size_t>(r)]);
    const auto e = static_cast<std::size_t>(L.ia[static_cast<std::size_t>(r) + 1]);
    if (std::is_sorted(L.ja.begin() + static_cast<std::ptrdiff_t>(b), L.ja.begin() + static_cast<std::ptrdiff_t>(e))) continue;
    std::vector<std::size_t> perm(e - b);
    std::iota(perm.begin(), perm.end(), b);
    std::sort(perm.begin(), perm.end(), [&](std::size_t x, std::size_t y) { return L.ja[x] < L.ja[y]; });
    std::vector<PetscInt> cj(perm.size());
    std::vector<PetscScalar> cv(perm.size());
    for (std::size_t q = 0; q < perm.size(); ++q) {
      cj[q] = L.ja[perm[q]];
      cv[q] = L.va[perm[q]];
    }
    std::copy(cj.begin(), cj.end(), L.ja.begin() + static_cast<std::ptrdiff_t>(b));
    std::copy(cv.begin(), cv.end(), L.va.begin() + static_cast<std::ptrdiff_t>(b));
  }
  return L;
}

Mat distributed_matrix(const SparseRef& A, SymmetricStorage storage, PetscInt n_local, PetscInt r0) {
  const LocalRows L = local_rows(A, storage, r0, r0 + n_local);
  Mat M = nullptr;
  const auto n = static_cast<PetscInt>(A.rows());
  check(MatCreateMPIAIJWithArrays(PETSC_COMM_WORLD, n_local, n_local, n, n, L.ia.data(), L.ja.data(), L.va.data(), &M),
        "MatCreateMPIAIJWithArrays");
  check(MatSetOption(M, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  return M;
}

// A vector of the layout of the matrices with this rank's rows of x.
Vec distributed_vector(const double* x, PetscInt n_local, PetscInt r0, PetscInt n) {
  Vec v = nullptr;
  check(VecCreateMPI(PETSC_COMM_WORLD, n_local, n, &v), "VecCreateMPI");
  PetscScalar* a = nullptr;
  check(VecGetArray(v, &a), "VecGetArray");
  std::copy(x + r0, x + r0 + n_local, a);
  check(VecRestoreArray(v, &a), "VecRestoreArray");
  return v;
}

}  // namespace

BackendOutcome run_slepc(const SparseRef& K, SymmetricStorage sK, const SparseRef& M, SymmetricStorage sM,
                         const Deflation& deflation, const SlepcRequest& req) {
  if (!parallel_session_active())
    throw std::invalid_argument(
        "eigen-solver: the slepc backend needs the program's MPI/SLEPc session (ffr::preproc::ParallelSession; "
        "ffr-reduce starts it for reduction.backend \"slepc\")");
  BackendOutcome out;
  const auto n = static_cast<PetscInt>(K.rows());
  PetscInt n_local = PETSC_DECIDE, n_global = n;
  check(PetscSplitOwnership(PETSC_COMM_WORLD, &n_local, &n_global), "PetscSplitOwnership");
  PetscInt r0 = 0;
  MPI_Exscan(&n_local, &r0, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) r0 = 0;  // MPI_Exscan leaves rank 0's result undefined

  MatGuard A, B;
  A.m = distributed_matrix(K, sK, n_local, r0);
  B.m = distributed_matrix(M, sM, n_local, r0);

  EpsGuard eps;
  check(EPSCreate(PETSC_COMM_WORLD, &eps.e), "EPSCreate");
  check(EPSSetOperators(eps.e, A.m, B.m), "EPSSetOperators");
  check(EPSSetProblemType(eps.e, EPS_GHEP), "EPSSetProblemType");
  check(EPSSetType(eps.e, EPSKRYLOVSCHUR), "EPSSetType");
  // The eigenvalues nearest sigma, which lies below every wanted one: the lowest.
  check(EPSSetWhichEigenpairs(eps.e, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
  check(EPSSetTarget(eps.e, req.sigma), "EPSSetTarget");
  check(EPSSetDimensions(eps.e, req.nev, req.ncv > 0 ? req.ncv : PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
  check(EPSSetTolerances(eps.e, req.tol, req.max_restarts), "EPSSetTolerances");
  ST st = nullptr;
  KSP ksp = nullptr;
  PC pc = nullptr;
  check(EPSGetST(eps.e, &st), "EPSGetST");
  check(STSetType(st, STSINVERT), "STSetType");
  check(STGetKSP(st, &ksp), "STGetKSP");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");

  // The deflation basis (the rigid-body modes of a free body): SLEPc keeps the Krylov basis
  // M-orthogonal to it (the inner product of a generalized Hermitian problem is M's).
  std::vector<VecGuard> defl(static_cast<std::size_t>(deflation.rank()));
  std::vector<Vec> defl_vecs;
  for (Eigen::Index c = 0; c < deflation.rank(); ++c) {
    defl[static_cast<std::size_t>(c)].v = distributed_vector(deflation.R.col(c).data(), n_local, r0, n);
    defl_vecs.push_back(defl[static_cast<std::size_t>(c)].v);
  }
  if (!defl_vecs.empty())
    check(EPSSetDeflationSpace(eps.e, static_cast<PetscInt>(defl_vecs.size()), defl_vecs.data()), "EPSSetDeflationSpace");
  // The start vector every backend uses (already in the complement of the deflation basis).
  VecGuard start;
  if (req.v0) {
    start.v = distributed_vector(req.v0->data(), n_local, r0, n);
    check(EPSSetInitialSpace(eps.e, 1, &start.v), "EPSSetInitialSpace");
  }
  // PETSC_OPTIONS may adjust the solver (e.g. MUMPS's -st_mat_mumps_icntl_14 workspace on a
  // cluster); EigenSolver's checks of every returned pair still apply.
  const MumpsChoices mumps(req.mumps, kEigenSolvePrefix);
  check(EPSSetFromOptions(eps.e), "EPSSetFromOptions");
  mumps_outcome(EPSSetUp(eps.e), "EPSSetUp", pc, mumps);
  mumps_outcome(EPSSolve(eps.e), "EPSSolve", pc, mumps);

  PetscInt nconv = 0, its = 0;
  check(EPSGetConverged(eps.e, &nconv), "EPSGetConverged");
  check(EPSGetIterationNumber(eps.e, &its), "EPSGetIterationNumber");
  out.iterations = static_cast<int>(its);
  out.converged = static_cast<int>(nconv);
  if (nconv < req.nev) {
    EPSConvergedReason reason;
    EPSGetConvergedReason(eps.e, &reason);
    std::ostringstream o;
    o << "eigen-solver (slepc): Krylov-Schur converged " << nconv << " of " << req.nev << " eigenpairs in " << its
      << " restarts (" << EPSConvergedReasons[reason] << "); try a larger ncv or more restarts";
    out.message = o.str();
    return out;
  }

  // Every converged pair, gathered to every rank.
  VecGuard x, x_all;
  ScatterGuard to_all;
  check(MatCreateVecs(A.m, &x.v, nullptr), "MatCreateVecs");
  check(VecScatterCreateToAll(x.v, &to_all.s, &x_all.v), "VecScatterCreateToAll");
  out.lambda.resize(nconv);
  out.X.resize(n, nconv);
  for (PetscInt i = 0; i < nconv; ++i) {
    PetscScalar kr = 0, ki = 0;
    check(EPSGetEigenpair(eps.e, i, &kr, &ki, x.v, nullptr), "EPSGetEigenpair");
    out.lambda(i) = kr;
    check(VecScatterBegin(to_all.s, x.v, x_all.v, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(to_all.s, x.v, x_all.v, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* a = nullptr;
    check(VecGetArrayRead(x_all.v, &a), "VecGetArrayRead");
    std::copy(a, a + n, out.X.col(i).data());
    check(VecRestoreArrayRead(x_all.v, &a), "VecRestoreArrayRead");
  }
  out.success = true;
  return out;
}

Eigen::MatrixXd distributed_spd_solve(const SparseRef& A, SymmetricStorage sA, const Eigen::MatrixXd& B,
                                      const MumpsOptions& mumps_options) {
  if (!parallel_session_active())
    throw std::invalid_argument("distributed solve: needs the program's MPI/SLEPc session (ffr::preproc::ParallelSession)");
  const auto n = static_cast<PetscInt>(A.rows());
  PetscInt n_local = PETSC_DECIDE, n_global = n;
  check(PetscSplitOwnership(PETSC_COMM_WORLD, &n_local, &n_global), "PetscSplitOwnership");
  PetscInt r0 = 0;
  MPI_Exscan(&n_local, &r0, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) r0 = 0;
  MatGuard Ad;
  Ad.m = distributed_matrix(A, sA, n_local, r0);
  KspGuard ksp;
  PC pc = nullptr;
  check(KSPCreate(PETSC_COMM_WORLD, &ksp.k), "KSPCreate");
  check(KSPSetOperators(ksp.k, Ad.m, Ad.m), "KSPSetOperators");
  check(KSPSetType(ksp.k, KSPPREONLY), "KSPSetType");
  check(KSPGetPC(ksp.k, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  // Options of its own in PETSC_OPTIONS (-ffr_solve_...), apart from the eigen-solve's (-st_...).
  check(KSPSetOptionsPrefix(ksp.k, kSolvePrefix), "KSPSetOptionsPrefix");
  const MumpsChoices mumps(mumps_options, kSolvePrefix);
  check(KSPSetFromOptions(ksp.k), "KSPSetFromOptions");
  {
    const PetscErrorCode ierr = KSPSetUp(ksp.k);
    // A matrix that is not positive definite is the caller's to explain (a mechanism); every
    // other failure of MUMPS is named by mumps_outcome.
    PCFailedReason failed = PC_NOERROR;
    if (ierr == 0) check(PCGetFailedReason(pc, &failed), "PCGetFailedReason");
    if (failed == PC_FACTOR_NUMERIC_ZEROPIVOT)
      throw NotPositiveDefiniteError(std::string("MUMPS's Cholesky factorization failed (") + PCFailedReasons[failed] + ")",
                                     -1, -1, true);
    mumps_outcome(ierr, "KSPSetUp", pc, mumps);
  }
  VecGuard b, x, x_all;
  ScatterGuard to_all;
  check(MatCreateVecs(Ad.m, &x.v, &b.v), "MatCreateVecs");
  check(VecScatterCreateToAll(x.v, &to_all.s, &x_all.v), "VecScatterCreateToAll");
  Eigen::MatrixXd X(n, B.cols());
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    PetscScalar* a = nullptr;
    check(VecGetArray(b.v, &a), "VecGetArray");
    std::copy(B.col(c).data() + r0, B.col(c).data() + r0 + n_local, a);
    check(VecRestoreArray(b.v, &a), "VecRestoreArray");
    mumps_outcome(KSPSolve(ksp.k, b.v, x.v), "KSPSolve", pc, mumps);
    KSPConvergedReason reason;
    check(KSPGetConvergedReason(ksp.k, &reason), "KSPGetConvergedReason");
    if (reason < 0)
      throw std::runtime_error(std::string("distributed solve: MUMPS's solve failed (") + KSPConvergedReasons[reason] + ")");
    check(VecScatterBegin(to_all.s, x.v, x_all.v, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(to_all.s, x.v, x_all.v, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* xa = nullptr;
    check(VecGetArrayRead(x_all.v, &xa), "VecGetArrayRead");
    std::copy(xa, xa + n, X.col(c).data());
    check(VecRestoreArrayRead(x_all.v, &xa), "VecRestoreArrayRead");
  }
  return X;
}

#else

Eigen::MatrixXd distributed_spd_solve(const SparseRef&, SymmetricStorage, const Eigen::MatrixXd&, const MumpsOptions&) {
  throw std::invalid_argument("distributed solve: the slepc backend is not built into this program");
}

BackendOutcome run_slepc(const SparseRef&, SymmetricStorage, const SparseRef&, SymmetricStorage, const Deflation&,
                         const SlepcRequest&) {
  throw std::invalid_argument(
      "eigen-solver: the slepc backend is not built into this program (configure with -DFFR_SLEPC=ON and Debian's "
      "slepc-dev, petsc-dev and libopenmpi-dev)");
}

#endif

}  // namespace ffr::preproc::detail
