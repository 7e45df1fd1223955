#pragma once
// LU factorisation with partial pivoting of the small dense tangent (tens of coordinates),
// in place in buffers sized once: compute() and solve() allocate nothing.
//
// Why not Eigen::PartialPivLU: it cannot know that a multibody tangent has zero blocks (a body
// couples only with the bodies it is jointed to). Here the right-looking elimination updates
// only the columns that have a nonzero in the pivot row, over the rows down to the pivot
// column's last nonzero; the solves likewise run each column of L and U only over its nonzero
// span. Pivoting is partial pivoting over the column (its rows below the last nonzero are
// zero). The raw loops are compiled per instruction set (small_lu.cpp), blocked in panels of
// four columns with a pivot search of four independent maxima. With Eigen::PartialPivLU in its
// place (compute and solve on the same buffers) the step of tools/bench/runtime_step took about
// a quarter longer (RESULTS.md there), far above the 5 % for which an own kernel is kept.

#include <Eigen/Core>

namespace ffr::runtime {

class SmallLU {
 public:
  /// A k x k matrix in the own buffer (leading dimension k + 2 kPad, see below).
  using MatrixMap = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

  SmallLU() = default;
  explicit SmallLU(Eigen::Index n) { resize(n); }
  /// Buffers for matrices of up to n x n.
  void resize(Eigen::Index n);

  /// Factorises A (any k x k expression with k <= the size given to resize, evaluated into the
  /// own buffer: a scaled matrix is scaled there, not copied first). Returns false, and ok()
  /// stays false until the next success, when a pivot column is exactly zero or NaN (the
  /// matrix is singular).
  template <class Derived>
  bool compute(const Eigen::MatrixBase<Derived>& A) {
    eigen_assert(A.rows() == A.cols() && A.rows() <= capacity_);
    MatrixMap a = begin(A.rows());
    a = A;  // in the buffer: no allocation
    return factorize();
  }
  /// Factorises the k x k matrix that fill(MatrixMap&) writes into the own buffer (for gathers
  /// an expression cannot state cheaply); otherwise as compute.
  template <class Fill>
  bool compute_filled(Eigen::Index k, Fill&& fill) {
    eigen_assert(k <= capacity_);
    MatrixMap a = begin(k);
    fill(a);
    return factorize();
  }
  /// Factorises the k x k matrix whose column j is zero outside rows first[j] .. last[j]
  /// (first[j] <= j <= last[j]): fill(MatrixMap&) writes those rows of each column and nothing
  /// else. Why: on a banded tangent (an ancf beam's) clearing, gathering and scanning the whole
  /// k x k matrix grew with k^2 (the gather alone was a tenth of a 32-element beam's step);
  /// this clears only what the last factorisation left outside the new spans and takes the
  /// spans as the envelope's bounds.
  /// The same factors as compute_filled.
  template <class Fill>
  bool compute_within(Eigen::Index k, const int* first, const int* last, Fill&& fill) {
    eigen_assert(k <= capacity_);
    clear_outside(k, first, last);
    MatrixMap a = begin(k);
    fill(a);
    return factorize(first, last);
  }
  /// x <- A^-1 x with the last factorisation (its first k entries; x may be longer). Uses a
  /// work vector of the object: one solve at a time.
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const;

  bool ok() const { return ok_; }
  Eigen::Index size() const { return n_; }

 private:
  /// Zero rows above and below every column of the buffer and of the solves' work vector.
  /// Why: the kernels' loops over a column's rows then run in whole blocks of four, reading
  /// at most three rows past the column's nonzero span (zeros, so nothing changes), with no
  /// scalar remainder loop; with the tangent's columns of 1 to 25 rows, the loops' set-up and
  /// remainders were most of a solve's instructions.
  static constexpr Eigen::Index kPad = 4;

  MatrixMap begin(Eigen::Index k) {
    spans_bound_buffer_ = false;  // the caller writes the buffer
    n_ = k;
    ld_ = k + 2 * kPad;
    return MatrixMap(buffer_.data() + kPad, k, k, Eigen::OuterStride<>(ld_));
  }
  /// In place on the buffer; first/last (or null: found by scanning) bound each column's rows.
  bool factorize(const int* first = nullptr, const int* last = nullptr);
  /// Zeroes the k x k buffer outside the columns' spans first .. last: whole when the last
  /// factorisation was of another size or failed, else what its factors left outside them.
  void clear_outside(Eigen::Index k, const int* first, const int* last);

  /// Packed factors of the last matrix (k x k, column-major from buffer_ + kPad, leading
  /// dimension ld_): unit lower L below the diagonal, U on and above.
  Eigen::VectorXd buffer_;
  Eigen::Index capacity_ = 0, n_ = 0, ld_ = 0;
  Eigen::VectorXi row_of_;  ///< the row swaps so far: row k of the factors is row row_of_(k) of A
  Eigen::VectorXi lower_;   ///< last nonzero row of L's column k (k when none)
  Eigen::VectorXi upper_;   ///< first nonzero row of U's column k above the diagonal (k when none)
  Eigen::VectorXi row_last_;  ///< factorize's bound on each row's last nonzero column
  Eigen::VectorXd inv_diag_;  ///< 1 / U(k, k)
  mutable Eigen::VectorXd work_;  ///< the solves' right-hand side, kPad zeros either side
  bool ok_ = false;
  /// lower_ and upper_ bound the buffer's nonzeros (a successful factorisation of size n_ set
  /// them and nothing has written the buffer since): clear_outside need not clear it whole.
  bool spans_bound_buffer_ = false;
};

}  // namespace ffr::runtime
