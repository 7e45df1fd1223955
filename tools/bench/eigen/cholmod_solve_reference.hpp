#pragma once
// The peer of CholmodFactor::solve in eigen_bench: CHOLMOD's own supernodal analysis (METIS),
// factorization and cholmod_l_solve2 on the same matrix and right-hand sides.

#include "ffr/preproc/solver/sparse_types.hpp"

#include <Eigen/Core>

namespace ffr::bench {

struct ReferenceSolve {
  double seconds = 0;       ///< best of the repeats, one cholmod_l_solve2 call each
  Eigen::MatrixXd X;        ///< its solution, to compare with ours
};

/// Factorizes A (symmetric positive definite, full or upper storage) with CHOLMOD and times
/// cholmod_l_solve2 on B, best of `repeats`. Throws std::runtime_error if CHOLMOD fails.
ReferenceSolve cholmod_reference_solve(const ffr::preproc::SparseMatrix& A, const Eigen::MatrixXd& B,
                                       int repeats);

}  // namespace ffr::bench
