#pragma once
// Small sparse helpers of the reductions.
#include "ffr/preproc/model/sparse.hpp"
#include "ffr/preproc/solver/sparse_types.hpp"
#include "../run_parts.hpp"

#include <algorithm>
#include <vector>

namespace ffr::preproc::detail {

/// If T's columns (all, or those in `columns`) are a selection (each one entry 1.0, rows strictly
/// increasing from column to column): the row of each. Else empty. Holding nodes and picking
/// interior DOFs give such T, and then T^T A T (over those columns) is a principal submatrix.
inline std::vector<std::int64_t> selected_rows(const SparseMatrix& T, const std::vector<std::int64_t>* columns = nullptr) {
  std::vector<std::int64_t> rows;
  const std::int64_t count = columns ? static_cast<std::int64_t>(columns->size()) : T.cols();
  if (count == 0) return rows;
  rows.reserve(static_cast<std::size_t>(count));
  for (std::int64_t k = 0; k < count; ++k) {
    const std::int64_t j = columns ? (*columns)[static_cast<std::size_t>(k)] : k;
    if (j < 0 || j >= T.cols()) return {};
    SparseMatrix::InnerIterator it(T, j);
    if (!it || it.value() != 1.0 || (!rows.empty() && it.row() <= rows.back())) return {};
    rows.push_back(it.row());
    if (++it) return {};
  }
  return rows;
}

/// A(rows, rows) (sorted, distinct rows), or only its upper triangle: one pass over the kept
/// columns, no products (a sparse product T^T A T costs ~10x more time and two temporaries).
/// The columns go to the threads in parts (run_parts.hpp), each counting and then writing its
/// own: on the 100k-DOF plate of tools/bench/reduce the constraints stage (K's extraction, then
/// M's) was 0.14 s on one core at two threads.
inline SparseMatrix principal_submatrix(const SparseMatrix& A, const std::vector<std::int64_t>& rows, bool upper_only) {
  std::vector<std::int64_t> new_of_old(static_cast<std::size_t>(A.rows()), -1);
  for (std::size_t j = 0; j < rows.size(); ++j) new_of_old[static_cast<std::size_t>(rows[j])] = static_cast<std::int64_t>(j);
  const auto n = static_cast<std::int64_t>(rows.size());
  // f(i, value) for the kept entries of column j, rows ascending (new_of_old is increasing).
  const auto kept = [&](std::int64_t j, auto&& f) {
    for (SparseMatrix::InnerIterator it(A, rows[static_cast<std::size_t>(j)]); it; ++it) {
      const std::int64_t i = new_of_old[static_cast<std::size_t>(it.row())];
      if (i >= 0 && (!upper_only || i <= j)) f(i, it.value());
    }
  };
  const unsigned parts = parts_for(A.nonZeros(), std::int64_t{1} << 20);
  const auto split = [&](unsigned p) { return n * static_cast<std::int64_t>(p) / static_cast<std::int64_t>(parts); };
  SparseMatrix S(n, n);
  auto* outer = S.outerIndexPtr();
  run_parts(parts, split, [&](unsigned, std::int64_t j0, std::int64_t j1) {
    for (std::int64_t j = j0; j < j1; ++j) {
      std::int64_t count = 0;
      kept(j, [&count](std::int64_t, double) { ++count; });
      outer[j + 1] = count;
    }
  });
  outer[0] = 0;
  for (std::int64_t j = 0; j < n; ++j) outer[j + 1] += outer[j];
  S.resizeNonZeros(outer[n]);
  auto* inner = S.innerIndexPtr();
  double* val = S.valuePtr();
  run_parts(parts, split, [&](unsigned, std::int64_t j0, std::int64_t j1) {
    for (std::int64_t j = j0; j < j1; ++j) {
      std::int64_t k = outer[j];
      kept(j, [&](std::int64_t i, double v) {
        inner[k] = i;
        val[k++] = v;
      });
    }
  });
  return S;
}

/// T^T A T (or its upper triangle), by extraction when T is a selection.
inline SparseMatrix congruence(const SparseMatrix& T, const SparseMatrix& A, bool upper_only = false) {
  const auto rows = selected_rows(T);
  if (!rows.empty()) return principal_submatrix(A, rows, upper_only);
  const SparseMatrix AT = A * T;
  SparseMatrix C(T.transpose() * AT);
  if (upper_only) C = C.triangularView<Eigen::Upper>();
  return C;
}

/// Selection matrix S (n x idx.size()) with S(idx[j], j) = 1.
inline SparseMatrix selection(std::int64_t n, const std::vector<std::int64_t>& idx) {
  std::vector<Triplet> t;
  t.reserve(idx.size());
  for (std::size_t j = 0; j < idx.size(); ++j) t.emplace_back(idx[j], static_cast<std::int64_t>(j), 1.0);
  SparseMatrix S(n, static_cast<std::int64_t>(idx.size()));
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

struct Split {
  std::vector<std::int64_t> interior;  ///< DOFs that are not boundary, ascending
  SparseMatrix Kii, Mii, Kib;
};

/// Whether A and B store the same entries (same size, column starts and row indices).
inline bool same_structure(const SparseMatrix& A, const SparseMatrix& B) {
  if (A.rows() != B.rows() || A.cols() != B.cols() || A.nonZeros() != B.nonZeros() || !A.isCompressed() ||
      !B.isCompressed())
    return false;
  return std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1, B.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), B.innerIndexPtr());
}

/// A += s B entry by entry, for B of A's structure (same_structure).
inline void add_scaled_values(SparseMatrix& A, const SparseRef& B, double s) {
  double* a = A.valuePtr();
  const double* b = B.valuePtr();
  for (std::int64_t k = 0; k < A.nonZeros(); ++k) a[k] += s * b[k];
}

/// The DOFs of 0..n-1 that are not in `boundary`, ascending.
inline std::vector<std::int64_t> interior_of(std::int64_t n, const std::vector<std::int64_t>& boundary) {
  std::vector<bool> is_b(static_cast<std::size_t>(n), false);
  for (auto b : boundary) is_b[static_cast<std::size_t>(b)] = true;
  std::vector<std::int64_t> interior;
  for (std::int64_t i = 0; i < n; ++i)
    if (!is_b[static_cast<std::size_t>(i)]) interior.push_back(i);
  return interior;
}

/// Partitions K and M into interior and boundary DOFs.
inline Split split(const SparseMatrix& K, const SparseMatrix& M, const std::vector<std::int64_t>& boundary) {
  Split s;
  s.interior = interior_of(K.rows(), boundary);
  const SparseMatrix Si = selection(K.rows(), s.interior), Sb = selection(K.rows(), boundary);
  s.Kii = congruence(Si, K);
  s.Mii = congruence(Si, M);
  const SparseMatrix KSb = K * Sb;
  s.Kib = SparseMatrix(Si.transpose() * KSb);
  return s;
}

}  // namespace ffr::preproc::detail
