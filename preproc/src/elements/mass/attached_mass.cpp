// A rigid body on one 6-DOF node (see attached_mass.hpp). The second moments about the centre,
// S = int s s^T dm, follow from the inertia tensor I = int (|s|^2 1 - s s^T) dm as
// S = tr(I)/2 1 - I; six points at ± a_k v_k along S's eigenvectors with m/6 each reproduce
// m, a zero first moment about the centre and S exactly.

#include "ffr/preproc/elements/attached_mass.hpp"

#include "../shell/material_check.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace ffr::preproc {

ElementMatrices attached_mass(const Eigen::Vector3d& p_node, double mass, const Eigen::Vector3d& e,
                              const Eigen::Matrix3d& I) {
  const std::string who = "attached mass";
  structural::check_positive(who, "mass", mass);
  if (!p_node.allFinite() || !e.allFinite()) structural::fail(who, "position or com_offset contains NaN or infinity");
  if (!I.allFinite()) structural::fail(who, "inertia contains NaN or infinity");
  const double scale = std::max(I.cwiseAbs().maxCoeff(), 1e-300);
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) structural::fail(who, "inertia must be symmetric");

  const Eigen::Matrix3d S = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (S + S.transpose()));
  const Eigen::Vector3d lam = eig.eigenvalues();
  if (lam.minCoeff() < -1e-9 * std::max(scale, 0.0))
    structural::fail(who, "inertia is not that of a physical body (principal moments must be >= 0 and satisfy the "
                      "triangle inequalities Ia + Ib >= Ic)");

  ElementMatrices out;
  out.dofs_per_node = 6;
  out.K = Eigen::MatrixXd::Zero(6, 6);
  out.M = Eigen::MatrixXd::Zero(6, 6);
  for (int k = 0; k < 3; ++k) {
    const double a = std::sqrt(3 * std::max(lam(k), 0.0) / mass);
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d s = sign * a * eig.eigenvectors().col(k);
      MassSample smp;
      smp.w = mass / 6;
      smp.c = p_node + e + s;
      smp.N.resize(3, 6);
      smp.N.leftCols<3>() = Eigen::Matrix3d::Identity();
      smp.N.rightCols<3>() = -structural::skew(e + s);  // theta x (e + s)
      out.M.noalias() += smp.w * smp.N.transpose() * smp.N;
      out.samples.push_back(std::move(smp));
    }
  }
  return out;
}

}  // namespace ffr::preproc
