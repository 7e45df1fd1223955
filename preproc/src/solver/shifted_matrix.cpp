// C = A - sigma*B as one upper-triangle matrix: the two sorted column patterns are merged
// in one counting pass and one filling pass, so the only allocation is C itself (half the
// size of a full-storage sum, and no temporaries as Eigen's expression A - sigma*B would
// need for the triangular extraction afterwards).

#include "ffr/preproc/solver/cholmod_factor.hpp"

#include <sstream>
#include <stdexcept>

namespace ffr::preproc {

namespace {
using SI = SparseMatrix::StorageIndex;

// Range of the upper part (row <= j) of column j: [begin, end) into inner/value arrays.
struct ColumnRange {
  SI begin, end;
};
ColumnRange upper_range(const SparseRef& A, Eigen::Index j) {
  const SI b = A.outerIndexPtr()[j];
  const SI e = A.outerIndexPtr()[j + 1];  // compressed: SparseRef guarantees it
  SI k = b;
  const SI* rows = A.innerIndexPtr();
  while (k < e && rows[k] <= j) ++k;  // inner indices sorted: the upper part is a prefix
  return {b, k};
}

// Merges column j of A and B; calls emit(row, value) in increasing row order.
template <typename Emit>
void merge_column(const SparseRef& A, const SparseRef& B, double sigma, Eigen::Index j,
                  Emit&& emit) {
  const ColumnRange a = upper_range(A, j), b = upper_range(B, j);
  const SI *ra = A.innerIndexPtr(), *rb = B.innerIndexPtr();
  const double *va = A.valuePtr(), *vb = B.valuePtr();
  SI p = a.begin, q = b.begin;
  while (p < a.end || q < b.end) {
    if (q >= b.end || (p < a.end && ra[p] < rb[q])) {
      emit(ra[p], va[p]);
      ++p;
    } else if (p >= a.end || rb[q] < ra[p]) {
      emit(rb[q], -sigma * vb[q]);
      ++q;
    } else {
      emit(ra[p], va[p] - sigma * vb[q]);
      ++p;
      ++q;
    }
  }
}
}  // namespace

SparseMatrix shifted_upper(const SparseRef& A, const SparseRef& B, double sigma) {
  if (A.rows() != A.cols() || B.rows() != B.cols() || A.rows() != B.rows()) {
    std::ostringstream os;
    os << "A - sigma*B: A is " << A.rows() << " x " << A.cols() << ", B is " << B.rows() << " x "
       << B.cols() << " (both must be square of the same size)";
    throw std::invalid_argument(os.str());
  }
  const Eigen::Index n = A.cols();
  SparseMatrix C(n, n);
  SI* outer = C.outerIndexPtr();
  // Pass 1: count the merged upper entries per column.
  outer[0] = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    SI count = 0;
    merge_column(A, B, sigma, j, [&count](SI, double) { ++count; });
    outer[j + 1] = outer[j] + count;
  }
  C.resizeNonZeros(outer[n]);
  // Pass 2: fill.
  SI* rows = C.innerIndexPtr();
  double* vals = C.valuePtr();
  for (Eigen::Index j = 0; j < n; ++j) {
    SI k = outer[j];
    merge_column(A, B, sigma, j, [&](SI r, double v) {
      rows[k] = r;
      vals[k] = v;
      ++k;
    });
  }
  return C;
}

}  // namespace ffr::preproc
