#pragma once
// The distributed pencil of the slepc backend's distributed path (slepc_distributed.cpp):
// every rank hands over the sum of its own elements' contributions to K and M (on the
// independent DOFs), PETSc adds them up into matrices of which each rank stores only its
// block of rows, and the eigen-solve, its Rayleigh-Ritz step and its checks run on those
// blocks, with the small reduced matrices and norms summed over the ranks. No rank ever holds
// K or M whole. Collective: every rank of the active ParallelSession calls each function in
// the same order with matrices of the same size. No PETSc type appears here.

#include "ffr/preproc/solver/eigen_solver.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ffr::preproc::detail {

/// This process's rank and the job's size (0 and 1 without an active ParallelSession).
int session_rank();
int session_size();
/// In-place sum over the ranks (nothing to do on one).
void sum_over_ranks(double* data, std::size_t n);
void sum_over_ranks(std::int64_t* data, std::size_t n);
/// The lowest value over the ranks and the rank that holds it (the lowest such rank on a tie).
std::pair<double, int> min_over_ranks(double v);
/// `text` of rank `root` on every rank.
std::string broadcast(std::string text, int root);
/// The largest of v over the ranks.
double max_over_ranks(double v);

/// The first row of this rank's block when n rows are split as PETSc splits them (the first
/// n mod size ranks one more), and its length.
std::int64_t first_row(std::int64_t n, int rank, int size);
std::int64_t rows_of(std::int64_t n, int rank, int size);

/// What the distributed eigen-solve returns: everything the serial EigenSolver's result
/// carries that the reduction uses; X gathered to every rank (its rows are the modes' shapes
/// every rank's elements need for the invariants, and rank 0's SID).
struct DistributedModes {
  Eigen::VectorXd lambda;
  Eigen::MatrixXd X, XtKX, XtMX;
  double max_relative_residual = 0, orthonormality_error = 0;
  int iterations = 0, rounds = 0;
  double solve_seconds = 0, verify_seconds = 0;
  std::string factor;  ///< MUMPS's report on the (last) factor: ordering, entries, memory
};

class DistributedPencil {
 public:
  /// K_part and M_part: n x n, this rank's contributions (`upper`: their upper triangles, the
  /// lower implied); summed over the ranks into PETSc's row-distributed matrices.
  DistributedPencil(const SparseMatrix& K_part, const SparseMatrix& M_part, bool upper);
  ~DistributedPencil();
  DistributedPencil(const DistributedPencil&) = delete;
  DistributedPencil& operator=(const DistributedPencil&) = delete;

  std::int64_t rows() const;
  /// Stored entries of K and M in this rank's rows (PETSc's, after the sums).
  std::int64_t local_nonzeros() const;
  /// DOFs whose diagonal mass is 0 (collective).
  std::int64_t massless_dofs() const;
  /// The lowest eigenpairs above options.sigma (options.nev of them, or every one up to
  /// options.lambda_max in as many rounds as it takes), M-orthogonal to the columns of R
  /// (n x r, whole on every rank; none: no deflation), after the Rayleigh-Ritz step, the
  /// selection, the sign convention and the checks of the serial EigenSolver (its options'
  /// tolerances). Throws EigenSolverError when they fail or the solver does not converge.
  DistributedModes eigenmodes(const Eigen::MatrixXd& R, const EigenOptions& options,
                              const std::function<void(const std::string&)>& progress) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffr::preproc::detail
