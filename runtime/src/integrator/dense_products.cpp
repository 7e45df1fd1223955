#include "dense_products.hpp"

#include "kernel_clones.hpp"

// Compiled at -O3 and for AVX2 as well (kernel_clones.hpp).

namespace ffr::runtime::detail {

void times(const Eigen::MatrixXd& A, Eigen::Index m, Eigen::Index n, const Eigen::VectorXd& x, Eigen::VectorXd& y,
           bool accumulate) {
  eigen_assert(m <= A.rows() && n <= A.cols() && x.size() >= n && y.size() >= m);
  times(A.data(), A.rows(), m, n, x.data(), y.data(), accumulate);
}

FFR_RT_CLONES
void times(const double* A, Eigen::Index ld, Eigen::Index m, Eigen::Index n, const double* x, double* y, bool accumulate) {
  const double* __restrict a = A;
  const double* __restrict xv = x;
  double* __restrict yv = y;
  if (!accumulate)
    for (Eigen::Index i = 0; i < m; ++i) yv[i] = 0.0;
  // Four columns at a time; columns whose coefficients are all zero (coordinates the vector
  // does not move) are skipped. (A last block of four rows overlapping the whole ones, in place
  // of the remainder loop, made the step slower: its load of y straddles the block just stored.)
  Eigen::Index j = 0;
  for (; j + 4 <= n; j += 4) {
    const double x0 = xv[j], x1 = xv[j + 1], x2 = xv[j + 2], x3 = xv[j + 3];
    if (x0 == 0.0 && x1 == 0.0 && x2 == 0.0 && x3 == 0.0) continue;
    const double* __restrict c = a + j * ld;
    for (Eigen::Index i = 0; i < m; ++i) yv[i] += c[i] * x0 + c[ld + i] * x1 + c[2 * ld + i] * x2 + c[3 * ld + i] * x3;
  }
  for (; j < n; ++j) {
    const double xj = xv[j];
    if (xj == 0.0) continue;
    const double* __restrict c = a + j * ld;
    for (Eigen::Index i = 0; i < m; ++i) yv[i] += c[i] * xj;
  }
}

FFR_RT_CLONES
void add_transpose_times(const Eigen::MatrixXd& A, Eigen::Index m, Eigen::Index n, const Eigen::VectorXd& x,
                         Eigen::VectorXd& y) {
  const Eigen::Index ld = A.rows(), m4 = m - m % 4;
  eigen_assert(m <= ld && n <= A.cols() && x.size() >= m && y.size() >= n);
  const double* __restrict a = A.data();
  const double* __restrict xv = x.data();
  double* __restrict yv = y.data();
  // Four columns at a time, each with a vector of partial sums. The last few rows (m not a
  // multiple of four) as one more block ending at row m - 1, with the entries of x the whole
  // blocks took made zero: a scalar remainder loop per four columns cost as much as the blocks
  // (m = 18 rows on the runtime benchmark). (Only loads overlap here; see times().)
  const bool tail = m4 < m && m >= 4;
  const simd::v4 x_tail = tail ? (simd::lanes_from(static_cast<long long>(m4 - (m - 4))) ? simd::load(xv + m - 4) : simd::v4{})
                               : simd::v4{};
  Eigen::Index j = 0;
  for (; j + 4 <= n; j += 4) {
    const double* c = a + j * ld;
    simd::v4 s0 = {}, s1 = {}, s2 = {}, s3 = {};
    for (Eigen::Index i = 0; i < m4; i += 4) {
      const simd::v4 xi = simd::load(xv + i);
      s0 += simd::load(c + i) * xi;
      s1 += simd::load(c + ld + i) * xi;
      s2 += simd::load(c + 2 * ld + i) * xi;
      s3 += simd::load(c + 3 * ld + i) * xi;
    }
    if (tail) {
      s0 += simd::load(c + m - 4) * x_tail;
      s1 += simd::load(c + ld + m - 4) * x_tail;
      s2 += simd::load(c + 2 * ld + m - 4) * x_tail;
      s3 += simd::load(c + 3 * ld + m - 4) * x_tail;
    }
    double t[4] = {(s0[0] + s0[1]) + (s0[2] + s0[3]), (s1[0] + s1[1]) + (s1[2] + s1[3]),
                   (s2[0] + s2[1]) + (s2[2] + s2[3]), (s3[0] + s3[1]) + (s3[2] + s3[3])};
    if (!tail)
      for (Eigen::Index i = m4; i < m; ++i)
        for (int k = 0; k < 4; ++k) t[k] += c[k * ld + i] * xv[i];
    for (int k = 0; k < 4; ++k) yv[j + k] += t[k];
  }
  for (; j < n; ++j) {
    const double* c = a + j * ld;
    double s = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) s += c[i] * xv[i];
    yv[j] += s;
  }
}

}  // namespace ffr::runtime::detail
