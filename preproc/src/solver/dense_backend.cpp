// Dense backend for small problems (and the fallback when Lanczos cannot run because the
// requested modes leave no room for the Krylov basis, nev >= n). Deflation is done by an
// explicit basis Q2 of the M-orthogonal complement of R: Q2 spans null((M R)^T), taken
// from a full Householder QR of M R, and the pencil is reduced to (Q2^T K Q2, Q2^T M Q2).

#include "eigen_backends.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace ffr::preproc::detail {

namespace {
Eigen::MatrixXd to_dense(const SparseRef& A, SymmetricStorage s) {
  if (s == SymmetricStorage::UpperOnly) return Eigen::MatrixXd(SparseMatrix(A.selfadjointView<Eigen::Upper>()));
  return Eigen::MatrixXd(A);
}
}  // namespace

BackendOutcome run_dense(const SparseRef& K, SymmetricStorage sK, const SparseRef& M,
                         SymmetricStorage sM, const Deflation& deflation, double sigma) {
  BackendOutcome out;
  Eigen::MatrixXd Kd = to_dense(K, sK), Md = to_dense(M, sM);
  Eigen::MatrixXd Q2;
  if (!deflation.empty()) {
    const Eigen::Index n = K.rows(), r = deflation.rank();
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(deflation.MR);
    Q2 = (qr.householderQ() * Eigen::MatrixXd::Identity(n, n)).rightCols(n - r);
    Kd = Q2.transpose() * Kd * Q2;
    Md = Q2.transpose() * Md * Q2;
  }
  Kd = 0.5 * (Kd + Kd.transpose());
  Md = 0.5 * (Md + Md.transpose());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(Kd, Md);
  if (ges.info() != Eigen::Success) {
    out.message = "dense generalized eigen-solver failed (is M positive definite on the "
                  "complement of the deflation basis?)";
    return out;
  }
  const Eigen::VectorXd& l = ges.eigenvalues();  // ascending
  Eigen::Index first = 0;
  while (first < l.size() && l[first] <= sigma) ++first;
  const Eigen::Index m = l.size() - first;
  out.lambda = l.tail(m);
  out.X = ges.eigenvectors().rightCols(m);
  if (!deflation.empty()) out.X = Q2 * out.X;
  out.converged = static_cast<int>(m);
  out.success = true;
  return out;
}

}  // namespace ffr::preproc::detail
