#pragma once
// Private glue between Eigen and CHOLMOD's 64-bit API: an owning cholmod_common that never
// prints, and zero-copy views of Eigen storage as cholmod_sparse / cholmod_dense.

#include "ffr/preproc/solver/sparse_types.hpp"

#include <cholmod.h>

#include <string>
#include <type_traits>

namespace ffr::preproc::detail {

static_assert(sizeof(SuiteSparse_long) == sizeof(SparseMatrix::StorageIndex),
              "CHOLMOD's SuiteSparse_long must match the 64-bit index of SparseMatrix");

/// Owns a cholmod_common configured for this project: silent (print = 0, errors captured
/// by last_error() instead of written to stdout), supernodal LL^T.
class CholmodCommon {
 public:
  CholmodCommon();
  ~CholmodCommon();
  CholmodCommon(const CholmodCommon&) = delete;
  CholmodCommon& operator=(const CholmodCommon&) = delete;
  cholmod_common* get() { return &c_; }
  const cholmod_common* get() const { return &c_; }
  /// Message of the most recent CHOLMOD error on this thread ("" if none); cleared on read.
  static std::string take_last_error();

 private:
  cholmod_common c_;
};

/// View of the upper triangle of a symmetric SparseMatrix (stype = +1): CHOLMOD ignores the
/// lower entries, so full and upper-only storage both work without a copy.
inline cholmod_sparse view_upper(const SparseMatrix& A) {
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(A.rows());
  s.ncol = static_cast<size_t>(A.cols());
  s.nzmax = static_cast<size_t>(A.nonZeros());
  s.p = const_cast<SparseMatrix::StorageIndex*>(A.outerIndexPtr());
  s.i = const_cast<SparseMatrix::StorageIndex*>(A.innerIndexPtr());
  s.nz = A.isCompressed() ? nullptr : const_cast<SparseMatrix::StorageIndex*>(A.innerNonZeroPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.z = nullptr;
  s.stype = 1;
  s.itype = CHOLMOD_LONG;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;  // Eigen keeps inner indices sorted within each column
  s.packed = A.isCompressed() ? 1 : 0;
  return s;
}

/// View of nrow x ncol column-major doubles with leading dimension ld.
inline cholmod_dense view_dense(const double* x, size_t nrow, size_t ncol, size_t ld) {
  cholmod_dense d{};
  d.nrow = nrow;
  d.ncol = ncol;
  d.nzmax = ld * ncol;
  d.d = ld;
  d.x = const_cast<double*>(x);
  d.z = nullptr;
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

/// Smallest pivot of a numeric supernodal LL^T factor relative to the matrix's own
/// diagonal entry, min_j L_jj^2 / A_pp with p = Perm[j] (the MAXRATIO-style singularity test,
/// see FactorOptions::min_pivot_ratio).
struct PivotRatio {
  double ratio;
  std::int64_t permuted_column;  ///< j
  std::int64_t column;           ///< Perm[j], the input numbering
};
/// x: the factor's numeric values in CHOLMOD's supernodal layout (L.x for CHOLMOD's own factor).
PivotRatio min_pivot_ratio(const cholmod_factor& L, const double* x, const SparseMatrix& A);

/// (min_j |L_jj| / max_j |L_jj|)^2 of a supernodal LL^T factor with values x in CHOLMOD's layout:
/// what cholmod_l_rcond reports for it.
double reciprocal_condition(const cholmod_factor& L, const double* x);

}  // namespace ffr::preproc::detail
