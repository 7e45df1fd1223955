#pragma once
// FNV-1a over the upper-triangle pattern of a matrix: decides whether a matrix given to
// factorize can reuse the analysis of an earlier one (cholmod_factor.cpp). Shared with the
// analysis from the node graph (reduce/pattern_analysis.cpp), which hashes the structure of the
// matrix to come without forming it.

#include "ffr/preproc/model/sparse.hpp"

#include <cstdint>

namespace ffr::preproc::detail {

class PatternHash {
 public:
  explicit PatternHash(std::int64_t rows) { mix(static_cast<std::uint64_t>(rows)); }
  /// Column j starts: its upper rows follow, ascending as stored.
  void column(std::int64_t j) { mix(0xC011u + static_cast<std::uint64_t>(j)); }
  void row(std::int64_t i) {
    mix(static_cast<std::uint64_t>(i));
    ++count_;
  }
  std::uint64_t value() const { return h_; }
  std::int64_t entries() const { return count_; }

 private:
  void mix(std::uint64_t v) {
    h_ ^= v;
    h_ *= 1099511628211ull;
  }
  std::uint64_t h_ = 1469598103934665603ull;
  std::int64_t count_ = 0;
};

/// The hash of A's upper triangle (entries with row <= column, full or upper storage); its
/// entry count in *upper_nnz.
inline std::uint64_t upper_pattern_hash(const SparseMatrix& A, std::int64_t* upper_nnz) {
  PatternHash h(A.rows());
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    h.column(j);
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() <= it.col()) h.row(it.row());
  }
  *upper_nnz = h.entries();
  return h.value();
}

}  // namespace ffr::preproc::detail
