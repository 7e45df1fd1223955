#include "static_solver.hpp"

#include "sparse_ops.hpp"

#include <Eigen/Dense>

namespace ffr::preproc::detail {

StaticSolver::StaticSolver(const FeModel& model, const Assembled& fe, const std::vector<InterfaceState>& states)
    : t_(build_transform(model, states)) {
  K_ = t_.identity ? fe.K : congruence(t_.T, fe.K);
  M_ = t_.identity ? fe.M : congruence(t_.T, fe.M);
  bool held = false;
  for (auto s : states) held = held || s == InterfaceState::Held;
  relief_ = !held;
  if (!relief_) {
    factor_.factorize(K_);
    return;
  }
  // Rigid-body modes, M-orthonormal.
  Eigen::MatrixXd R = rigid_body_modes(model, t_);
  const Eigen::MatrixXd RtMR = R.transpose() * (M_ * R);
  const Eigen::LLT<Eigen::MatrixXd> llt(RtMR);
  R_ = R * llt.matrixU().solve(Eigen::MatrixXd::Identity(6, 6));
  // Six support DOFs: the pivots of a column-pivoted QR of R^T (rows = motions, cols = DOFs).
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(R.transpose());
  std::vector<bool> support(static_cast<std::size_t>(t_.num_ind()), false);
  for (int i = 0; i < 6; ++i) support[static_cast<std::size_t>(qr.colsPermutation().indices()(i))] = true;
  for (Index i = 0; i < t_.num_ind(); ++i)
    if (!support[static_cast<std::size_t>(i)]) free_.push_back(i);
  factor_.factorize(congruence(selection(t_.num_ind(), free_), K_));
}

Eigen::MatrixXd StaticSolver::solve(const Eigen::MatrixXd& F_full) const {
  Eigen::MatrixXd F = t_.identity ? F_full : Eigen::MatrixXd(t_.T.transpose() * F_full);
  Eigen::MatrixXd U;
  if (!relief_) {
    U = factor_.solve(F);
  } else {
    F -= (M_ * R_) * (R_.transpose() * F);  // remove the rigid-body part of the load
    Eigen::MatrixXd Ff(static_cast<Index>(free_.size()), F.cols());
    for (std::size_t i = 0; i < free_.size(); ++i) Ff.row(static_cast<Index>(i)) = F.row(free_[i]);
    const Eigen::MatrixXd Uf = factor_.solve(Ff);
    U = Eigen::MatrixXd::Zero(t_.num_ind(), F.cols());
    for (std::size_t i = 0; i < free_.size(); ++i) U.row(free_[i]) = Uf.row(static_cast<Index>(i));
    U -= R_ * (R_.transpose() * (M_ * U));  // the deformation, without rigid-body motion
  }
  return t_.identity ? U : Eigen::MatrixXd(t_.T * U);
}

}  // namespace ffr::preproc::detail
