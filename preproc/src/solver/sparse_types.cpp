#include "ffr/preproc/solver/sparse_types.hpp"

#include "../run_parts.hpp"
#include "kernel_clones.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffr::preproc {

SymmetricStorage detect_storage(const SparseRef& A) {
  bool upper = false, lower = false;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (SparseRef::InnerIterator it(A, j); it; ++it) {
      if (it.row() < it.col()) upper = true;
      else if (it.row() > it.col()) lower = true;
    }
    if (upper && lower) return SymmetricStorage::Full;
  }
  if (upper) return SymmetricStorage::UpperOnly;
  if (lower) return SymmetricStorage::LowerOnly;
  return SymmetricStorage::Diagonal;
}

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Y += A X for an upper-only symmetric A and row-major X, Y: one pass over A, each stored
// entry applied to a row of X and to its mirror (Eigen's products of a column-major sparse
// matrix with a column-major X, and its selfadjointView products, pass over A once per column,
// on one thread). W fixes the row width at compile time where the eigen-solvers need it (a
// multiple of 4: rows of simd::v4; 0 for any width, not vectorized). Kept because it saves
// about 5 % of the 100k-DOF plate's run of tools/bench/reduce at one thread against
// A.selfadjointView<Upper>() * X (RESULTS.md there), and more at two, where it runs on both.
template <int W>
void upper_times_rows(const SparseRef& A, const RowMajorMatrix& X, Eigen::Index j0, Eigen::Index j1, double* y) {
  const auto* outer = A.outerIndexPtr();
  const auto* rows = A.innerIndexPtr();
  const double* vals = A.valuePtr();
  const double* x = X.data();
  if constexpr (W > 0) {
    using detail::simd::load;
    using detail::simd::store;
    using detail::simd::v4;
    constexpr int NV = W / 4;
    for (Eigen::Index j = j0; j < j1; ++j) {
      v4 xj[NV], acc[NV] = {};
      for (int k = 0; k < NV; ++k) xj[k] = load(x + j * W + 4 * k);
      const auto end = outer[j + 1];  // compressed: SparseRef guarantees it
      for (auto e = outer[j]; e < end; ++e) {
        const Eigen::Index i = rows[e];
        const double a = vals[e];
        if (i < j) {
          for (int k = 0; k < NV; ++k) {
            store(y + i * W + 4 * k, load(y + i * W + 4 * k) + a * xj[k]);  // the stored A(i, j)
            acc[k] += a * load(x + i * W + 4 * k);                          // its mirror A(j, i)
          }
        } else if (i == j) {
          for (int k = 0; k < NV; ++k) acc[k] += a * xj[k];
        }
      }
      for (int k = 0; k < NV; ++k) store(y + j * W + 4 * k, load(y + j * W + 4 * k) + acc[k]);
    }
  } else {
    const Eigen::Index m = X.cols();
    for (Eigen::Index j = j0; j < j1; ++j) {
      const auto end = outer[j + 1];  // compressed: SparseRef guarantees it
      for (auto e = outer[j]; e < end; ++e) {
        const Eigen::Index i = rows[e];
        const double a = vals[e];
        if (i < j) {
          for (Eigen::Index c = 0; c < m; ++c) {
            y[i * m + c] += a * x[j * m + c];
            y[j * m + c] += a * x[i * m + c];
          }
        } else if (i == j) {
          for (Eigen::Index c = 0; c < m; ++c) y[j * m + c] += a * x[j * m + c];
        }
      }
    }
  }
}

// The widths the eigen-solvers use, each compiled for AVX-512 and AVX2 as well.
FFR_KERNEL_CLONES
void upper_times_rows_any(const SparseRef& A, const RowMajorMatrix& X, Eigen::Index j0, Eigen::Index j1, double* y) {
  switch (X.cols()) {
    case 4: upper_times_rows<4>(A, X, j0, j1, y); break;
    case 8: upper_times_rows<8>(A, X, j0, j1, y); break;
    case 16: upper_times_rows<16>(A, X, j0, j1, y); break;
    default: upper_times_rows<0>(A, X, j0, j1, y); break;
  }
}

// Y = A X over the columns of A split into parts of about equal stored entries. A part writes
// the rows of its own columns and, through the mirrored entries, rows of earlier columns; so
// each part after the first accumulates into its own zeroed buffer, added to Y at the end.
void upper_times_rows(const SparseRef& A, const RowMajorMatrix& X, RowMajorMatrix& Y) {
  const Eigen::Index n = A.outerSize();
  const unsigned parts = detail::parts_for(A.nonZeros(), Eigen::Index{1} << 18);
  std::vector<RowMajorMatrix> extra(parts > 1 ? parts - 1 : 0);
  const auto* outer = A.outerIndexPtr();
  const auto split = [&](unsigned p) -> Eigen::Index {
    if (p == 0) return 0;
    if (p >= parts) return n;
    const auto target = static_cast<std::int64_t>(static_cast<double>(outer[n]) * p / parts);
    return static_cast<Eigen::Index>(std::lower_bound(outer, outer + n + 1, target) - outer);
  };
  detail::run_parts(parts, split, [&](unsigned p, Eigen::Index j0, Eigen::Index j1) {
    double* y = Y.data();
    if (p > 0) {
      extra[p - 1] = RowMajorMatrix::Zero(j1, X.cols());  // rows beyond j1 are not written
      y = extra[p - 1].data();
    }
    upper_times_rows_any(A, X, j0, j1, y);
  });
  for (const RowMajorMatrix& e : extra) Y.topRows(e.rows()) += e;
}

// Width of the next chunk of columns: the widest compiled row width that fits (a pass over A
// per chunk). The dynamic-width kernel is not vectorized, and 20 columns took it about half as
// long again as chunks of 16 and 4.
Eigen::Index chunk_width(Eigen::Index left) {
  for (Eigen::Index w : {16, 8, 4})
    if (left >= w) return w;
  return left;
}

// The product for the columns [c0, c1) of X into the same columns of Y.
void product_columns(const SparseRef& A, SymmetricStorage storage, const Eigen::Ref<const Eigen::MatrixXd>& X,
                     Eigen::Index c0, Eigen::Index c1, Eigen::MatrixXd& Y) {
  const RowMajorMatrix Xr = X.middleCols(c0, c1 - c0);
  RowMajorMatrix Yr = RowMajorMatrix::Zero(A.rows(), c1 - c0);
  if (storage == SymmetricStorage::UpperOnly) upper_times_rows(A, Xr, Yr);
  else Yr.noalias() = A * Xr;  // row j of X scattered along column j of A: one pass
  Y.middleCols(c0, c1 - c0) = Yr;
}

}  // namespace

Eigen::MatrixXd sym_multiply(const SparseRef& A, SymmetricStorage storage,
                             const Eigen::Ref<const Eigen::MatrixXd>& X) {
  Eigen::MatrixXd Y(A.rows(), X.cols());
  sym_multiply(A, storage, X, Y);
  return Y;
}

void sym_multiply(const SparseRef& A, SymmetricStorage storage, const Eigen::Ref<const Eigen::MatrixXd>& X,
                  Eigen::MatrixXd& Y) {
  Y.resize(A.rows(), X.cols());  // no reallocation at the same size
  if (X.cols() == 1) {
    if (storage == SymmetricStorage::UpperOnly)
      Y.noalias() = A.selfadjointView<Eigen::Upper>() * X;
    else
      Y.noalias() = A * X;
    return;
  }
  // Several columns: one pass over A with contiguous rows of X and Y (Eigen's products of a
  // column-major sparse matrix with a column-major X, and its selfadjointView products with
  // any X, pass over A once per column, which dominated the checks of 20-30 modes).
  if (storage != SymmetricStorage::UpperOnly) {
    product_columns(A, storage, X, 0, X.cols(), Y);
  } else {
    for (Eigen::Index c0 = 0; c0 < X.cols();) {
      const Eigen::Index w = chunk_width(X.cols() - c0);
      product_columns(A, storage, X, c0, c0 + w, Y);
      c0 += w;
    }
  }
}

double sym_norm1(const SparseRef& A, SymmetricStorage storage) {
  Eigen::VectorXd colsum = Eigen::VectorXd::Zero(A.cols());
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseRef::InnerIterator it(A, j); it; ++it) {
      colsum[it.col()] += std::abs(it.value());
      // An upper-only matrix implies the mirrored entry in column it.row().
      if (storage == SymmetricStorage::UpperOnly && it.row() != it.col())
        colsum[it.row()] += std::abs(it.value());
    }
  return A.cols() > 0 ? colsum.maxCoeff() : 0.0;
}

SymmetricStorage validate_symmetric(const SparseRef& A, const char* what,
                                    double symmetry_tol) {
  const std::string name(what);
  if (A.rows() != A.cols()) {
    std::ostringstream os;
    os << name << ": matrix must be square, got " << A.rows() << " x " << A.cols();
    throw std::invalid_argument(os.str());
  }
  if (A.rows() == 0) throw std::invalid_argument(name + ": matrix is empty (0 x 0)");
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseRef::InnerIterator it(A, j); it; ++it)
      if (!std::isfinite(it.value())) {
        std::ostringstream os;
        os << name << ": non-finite entry " << it.value() << " at (row " << it.row()
           << ", column " << it.col() << ")";
        throw std::invalid_argument(os.str());
      }
  const SymmetricStorage storage = detect_storage(A);
  if (storage == SymmetricStorage::LowerOnly)
    throw std::invalid_argument(name + ": lower-triangle-only storage is not accepted; pass full "
                                       "storage or the upper triangle (row <= col)");
  if (storage == SymmetricStorage::Full) {
    // Random probe: A x versus A^T x. The transpose product is a different traversal of the
    // same storage, so this detects any asymmetric entry without building A^T.
    std::mt19937_64 rng(0x5eed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd x(A.cols());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = u(rng);
    const Eigen::VectorXd d = A * x - A.transpose() * x;
    const double scale = sym_norm1(A, storage) * x.norm();
    if (d.norm() > symmetry_tol * scale) {
      Eigen::Index worst = 0;
      d.cwiseAbs().maxCoeff(&worst);
      std::ostringstream os;
      os << name << ": matrix is not symmetric (probe ||(A - A^T) x|| / (||A||_1 ||x||) = "
         << d.norm() / scale << " > " << symmetry_tol << ", largest mismatch in row " << worst
         << ")";
      throw std::invalid_argument(os.str());
    }
  }
  return storage;
}

}  // namespace ffr::preproc
