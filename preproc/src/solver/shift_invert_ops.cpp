#include "ffr/preproc/solver/shift_invert_ops.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace ffr::preproc {

using Eigen::Map;
using Eigen::VectorXd;

void Deflation::project(double* x) const {
  if (empty()) return;
  Map<VectorXd> v(x, R.rows());
  const VectorXd c = MR.transpose() * v;
  v.noalias() -= R * c;
}

void Deflation::project_dual(double* f) const {
  if (empty()) return;
  Map<VectorXd> v(f, R.rows());
  const VectorXd c = R.transpose() * v;
  v.noalias() -= MR * c;
}

Deflation make_deflation(const SparseRef& M, SymmetricStorage storage,
                         const Eigen::Ref<const Eigen::MatrixXd>& R_in, double rank_tol) {
  Deflation d;
  if (R_in.cols() == 0) return d;
  if (R_in.rows() != M.rows()) {
    std::ostringstream os;
    os << "deflation basis: has " << R_in.rows() << " rows, the matrices have " << M.rows();
    throw std::invalid_argument(os.str());
  }
  if (!R_in.allFinite()) throw std::invalid_argument("deflation basis: non-finite entries");
  Eigen::MatrixXd R = R_in;
  // Pass 1: R <- R V diag(1/sqrt(mu)) with R^T M R = V diag(mu) V^T. Reveals dependence.
  Eigen::MatrixXd G = R.transpose() * sym_multiply(M, storage, R);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (G + G.transpose()));
  const VectorXd mu = es.eigenvalues();
  if (!(mu.maxCoeff() > 0) || mu.minCoeff() < rank_tol * mu.maxCoeff()) {
    std::ostringstream os;
    os << "deflation basis: its " << R.cols() << " columns are (nearly) linearly dependent in "
       << "the M inner product (eigenvalues of R^T M R from " << mu.minCoeff() << " to "
       << mu.maxCoeff() << ", ratio below " << rank_tol << ")";
    throw std::invalid_argument(os.str());
  }
  R = R * (es.eigenvectors() * mu.cwiseSqrt().cwiseInverse().asDiagonal());
  // Pass 2: Cholesky clean-up of the round-off left by pass 1.
  Eigen::MatrixXd MR = sym_multiply(M, storage, R);
  G = R.transpose() * MR;
  Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (G + G.transpose()));
  const Eigen::MatrixXd Linv =
      llt.matrixL().solve(Eigen::MatrixXd::Identity(G.rows(), G.cols()));
  d.R = R * Linv.transpose();
  d.MR = MR * Linv.transpose();
  return d;
}

ShiftInvertOp::ShiftInvertOp(const CholmodFactor& factor, const Deflation* deflation)
    : factor_(factor), deflation_(deflation && !deflation->empty() ? deflation : nullptr),
      work_(factor.rows()) {
  if (!factor.factorized()) throw std::logic_error("ShiftInvertOp: the factor is not factorized");
}

void ShiftInvertOp::set_shift(double sigma) {
  const double have = factor_.info().shift;
  if (std::abs(sigma - have) > 1e-12 * std::max(1.0, std::abs(have))) {
    std::ostringstream os;
    os << "ShiftInvertOp: solver shift " << sigma << " differs from the factorized shift " << have;
    throw std::logic_error(os.str());
  }
}

void ShiftInvertOp::perform_op(const double* x_in, double* y_out) const {
  if (deflation_) {
    work_ = Map<const VectorXd>(x_in, rows());
    deflation_->project_dual(work_.data());
    factor_.solve(work_.data(), y_out);
    deflation_->project(y_out);
  } else {
    factor_.solve(x_in, y_out);
  }
  ++applications_;
  if (observer_) observer_(applications_);
}

Eigen::MatrixXd ShiftInvertOp::apply_block(const Eigen::MatrixXd& X) const {
  Eigen::MatrixXd Y;
  apply_block(X, Y);
  return Y;
}

void ShiftInvertOp::apply_block(const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) const {
  if (&Y != &X) Y = X;
  if (deflation_)
    for (Eigen::Index j = 0; j < Y.cols(); ++j) deflation_->project_dual(Y.col(j).data());
  factor_.solve(Y, Y);  // the substitutions read each chunk of right-hand sides before writing it
  if (deflation_)
    for (Eigen::Index j = 0; j < Y.cols(); ++j) deflation_->project(Y.col(j).data());
  applications_ += X.cols();
  if (observer_) observer_(applications_);
}

void MassOp::perform_op(const double* x_in, double* y_out) const {
  const Eigen::Index n = M_.cols();
  const auto bytes = static_cast<std::size_t>(n) * sizeof(double);
  if (last_x_.size() == n && std::memcmp(last_x_.data(), x_in, bytes) == 0) {
    std::memmove(y_out, last_y_.data(), bytes);
    ++hits_;
    return;
  }
  Map<const VectorXd> x(x_in, n);
  Map<VectorXd> y(y_out, M_.rows());
  if (storage_ == SymmetricStorage::UpperOnly) y = M_.selfadjointView<Eigen::Upper>() * x;
  else y = M_.transpose() * x;  // M symmetric: the row-wise (gather) traversal, no scatter
  last_x_ = x;
  last_y_ = y;
  ++products_;
}

}  // namespace ffr::preproc
