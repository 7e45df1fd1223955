#include "ffr/preproc/solver/sparse_types.hpp"

#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

namespace ffr::preproc {

SymmetricStorage detect_storage(const SparseMatrix& A) {
  bool upper = false, lower = false;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      if (it.row() < it.col()) upper = true;
      else if (it.row() > it.col()) lower = true;
    }
    if (upper && lower) return SymmetricStorage::Full;
  }
  if (upper) return SymmetricStorage::UpperOnly;
  if (lower) return SymmetricStorage::LowerOnly;
  return SymmetricStorage::Diagonal;
}

Eigen::MatrixXd sym_multiply(const SparseMatrix& A, SymmetricStorage storage,
                             const Eigen::Ref<const Eigen::MatrixXd>& X) {
  Eigen::MatrixXd Y(A.rows(), X.cols());
  if (storage == SymmetricStorage::UpperOnly)
    Y.noalias() = A.selfadjointView<Eigen::Upper>() * X;
  else
    Y.noalias() = A * X;
  return Y;
}

double sym_norm1(const SparseMatrix& A, SymmetricStorage storage) {
  Eigen::VectorXd colsum = Eigen::VectorXd::Zero(A.cols());
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      colsum[it.col()] += std::abs(it.value());
      // An upper-only matrix implies the mirrored entry in column it.row().
      if (storage == SymmetricStorage::UpperOnly && it.row() != it.col())
        colsum[it.row()] += std::abs(it.value());
    }
  return A.cols() > 0 ? colsum.maxCoeff() : 0.0;
}

SymmetricStorage validate_symmetric(const SparseMatrix& A, const char* what,
                                    double symmetry_tol) {
  const std::string name(what);
  if (A.rows() != A.cols()) {
    std::ostringstream os;
    os << name << ": matrix must be square, got " << A.rows() << " x " << A.cols();
    throw std::invalid_argument(os.str());
  }
  if (A.rows() == 0) throw std::invalid_argument(name + ": matrix is empty (0 x 0)");
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
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
