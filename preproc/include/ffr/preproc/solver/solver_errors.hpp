#pragma once
// Exceptions of the sparse linear-algebra layer. Every one carries the numbers it talks
// about as fields (for callers that react programmatically) and in what() (for humans).
// Bad arguments (wrong sizes, non-finite entries, asymmetric input) are
// std::invalid_argument; these classes are for conditions found while computing.

#include <cstdint>
#include <stdexcept>
#include <string>

namespace ffr::preproc {

class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The Cholesky factorization met a non-positive pivot (CHOLMOD_NOT_POSDEF), or a pivot so
/// small relative to the largest that the matrix is singular to working precision. With a
/// stiffness matrix this means a mechanism or an unconstrained rigid-body motion; with
/// K - sigma*M it means the shift lies above an eigenvalue.
class NotPositiveDefiniteError : public SolverError {
 public:
  NotPositiveDefiniteError(const std::string& msg, std::int64_t column,
                           std::int64_t permuted_column, bool numerically_singular)
      : SolverError(msg), column(column), permuted_column(permuted_column),
        numerically_singular(numerically_singular) {}
  std::int64_t column;           ///< 0-based row/column of the matrix as given (the DOF)
  std::int64_t permuted_column;  ///< the same column in CHOLMOD's fill-reducing order
  bool numerically_singular;     ///< true: tiny positive pivot; false: pivot <= 0
};

/// The factor would not fit: the analysis' estimate exceeds the memory available
/// (/proc/meminfo MemAvailable, cgroup headroom) or the caller's limit.
class InsufficientMemoryError : public SolverError {
 public:
  InsufficientMemoryError(const std::string& msg, std::uint64_t needed, std::uint64_t available)
      : SolverError(msg), needed_bytes(needed), available_bytes(available) {}
  std::uint64_t needed_bytes;
  std::uint64_t available_bytes;
};

/// The eigen-solver did not converge, or a returned eigenpair failed its residual or
/// orthonormality check.
class EigenSolverError : public SolverError {
 public:
  using SolverError::SolverError;
};

}  // namespace ffr::preproc
