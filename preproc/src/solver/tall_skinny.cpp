// Tall-skinny products for the block Gram-Schmidt (see tall_skinny.hpp).
#include "tall_skinny.hpp"

#include "dense_kernels.hpp"
#include "../run_parts.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <vector>

namespace ffr::preproc::detail {

using Index = std::int64_t;

namespace {
// The rule of DenseKernelChoice::Auto (the part file's choice is the factorization's).
const DenseKernels& gram_kernels() { return select_dense_kernels(DenseKernelChoice::Auto); }
}  // namespace

void add_transposed_product(const double* Q, Index ldq, Index k, const double* V, Index ldv, Index p, Index r0,
                            Index r1, double* C) {
  const int K = static_cast<int>(k), P = static_cast<int>(p), rows = static_cast<int>(r1 - r0);
  const int lq = static_cast<int>(ldq), lv = static_cast<int>(ldv);
  if (K > 0 && P > 0 && rows > 0) gram_kernels().gemm('T', 'N', K, P, rows, 1.0, Q + r0, lq, V + r0, lv, 1.0, C, K);
}

void subtract_product(const double* Q, Index ldq, Index k, const double* C, Index p, Index r0, Index r1, double* V,
                      Index ldv) {
  const int K = static_cast<int>(k), P = static_cast<int>(p), rows = static_cast<int>(r1 - r0);
  const int lq = static_cast<int>(ldq), lv = static_cast<int>(ldv);
  if (K > 0 && P > 0 && rows > 0) gram_kernels().gemm('N', 'N', rows, P, K, -1.0, Q + r0, lq, C, K, 1.0, V + r0, lv);
}

namespace {

// How many parts for work of about n * width values: the eigen-solver's threshold for vector
// work.
unsigned row_parts(Index n, Index width) { return parts_for(n * width, Index{1} << 18); }

// body(part, r0, r1) over `parts` parts of n rows, split at multiples of `align` rows.
template <class Body>
void over_row_parts(Index n, unsigned parts, Index align, Body&& body) {
  const auto split = [&](unsigned part) {
    if (part >= parts) return n;
    return n * static_cast<Index>(part) / static_cast<Index>(parts) / align * align;
  };
  run_parts(parts, split, body);
}

}  // namespace

void rotate_columns_in_place(Eigen::MatrixXd& Q, Eigen::Index k, const Eigen::Ref<const Eigen::MatrixXd>& S) {
  const Eigen::Index n = Q.rows(), m = S.cols();
  constexpr Eigen::Index kBand = 256;
  over_row_parts(n, row_parts(n, k), kBand, [&](unsigned, Index b, Index e) {
    Eigen::MatrixXd band(kBand, m);
    for (Eigen::Index r0 = b; r0 < e; r0 += kBand) {
      const Eigen::Index rows = std::min(kBand, e - r0);
      band.topRows(rows).noalias() = Q.block(r0, 0, rows, k) * S;
      Q.block(r0, 0, rows, m) = band.topRows(rows);
    }
  });
}

Eigen::MatrixXd transposed_product(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B) {
  const Index n = A.rows(), k = A.cols(), p = B.cols();
  const unsigned parts = row_parts(n, k);
  std::vector<Eigen::MatrixXd> partial(parts, Eigen::MatrixXd::Zero(k, p));
  over_row_parts(n, parts, 1, [&](unsigned part, Index r0, Index r1) {
    add_transposed_product(A.data(), A.outerStride(), k, B.data(), B.outerStride(), p, r0, r1, partial[part].data());
  });
  for (std::size_t part = 1; part < partial.size(); ++part) partial[0] += partial[part];
  return std::move(partial[0]);
}

void solve_upper_on_right(const Eigen::Ref<const Eigen::MatrixXd>& U, Eigen::MatrixXd& X) {
  const auto upper = U.triangularView<Eigen::Upper>();
  over_row_parts(X.rows(), row_parts(X.rows(), X.cols()), 1, [&](unsigned, Index r0, Index r1) {
    auto rows = X.middleRows(r0, r1 - r0);
    upper.solveInPlace<Eigen::OnTheRight>(rows);
  });
}

}  // namespace ffr::preproc::detail
