#pragma once
// Small sparse helpers of the reductions.
#include "ffr/preproc/model/sparse.hpp"

#include <vector>

namespace ffr::preproc::detail {

/// T^T A T.
inline SparseMatrix congruence(const SparseMatrix& T, const SparseMatrix& A) {
  const SparseMatrix AT = A * T;
  return SparseMatrix(T.transpose() * AT);
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

/// Partitions K and M into interior and boundary DOFs.
inline Split split(const SparseMatrix& K, const SparseMatrix& M, const std::vector<std::int64_t>& boundary) {
  Split s;
  std::vector<bool> is_b(static_cast<std::size_t>(K.rows()), false);
  for (auto b : boundary) is_b[static_cast<std::size_t>(b)] = true;
  for (std::int64_t i = 0; i < K.rows(); ++i)
    if (!is_b[static_cast<std::size_t>(i)]) s.interior.push_back(i);
  const SparseMatrix Si = selection(K.rows(), s.interior), Sb = selection(K.rows(), boundary);
  s.Kii = congruence(Si, K);
  s.Mii = congruence(Si, M);
  const SparseMatrix KSb = K * Sb;
  s.Kib = SparseMatrix(Si.transpose() * KSb);
  return s;
}

}  // namespace ffr::preproc::detail
