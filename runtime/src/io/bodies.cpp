// Rigid and flexible bodies from their physical description (FORMULATION.md section 3).
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/load.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>

namespace ffr::runtime {
namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace

Body make_rigid_body(const std::string& name, double mass, const Vector3d& com, const Matrix3d& inertia,
                     const Vector3d& position, const Matrix3d& orientation, const std::string& file,
                     const std::string& field) {
  if (!(mass > 0)) throw ModelError(file, field + ".mass", "must be positive");
  const double scale = inertia.cwiseAbs().maxCoeff();
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw ModelError(file, field + ".inertia", "must be symmetric");
  // The pseudo-inertia 1/2 tr(I) 1 - I must be positive definite, or a rotation would cost no
  // kinetic energy and the mass matrix would be singular: strict triangle inequalities.
  Eigen::SelfAdjointEigenSolver<Matrix3d> es(inertia);
  const Vector3d p = es.eigenvalues();
  if (!(p.minCoeff() > 0))
    throw ModelError(file, field + ".inertia", "principal moments must be positive (found " + num(p(0)) + ", " + num(p(1)) + ", " + num(p(2)) + ")");
  if (!(p(0) + p(1) > p(2) * (1 + 1e-12)))
    throw ModelError(file, field + ".inertia",
                     "principal moments " + num(p(0)) + ", " + num(p(1)) + ", " + num(p(2)) +
                         " violate the triangle inequality I1 + I2 > I3 (no real body has them; a slender rod "
                         "still needs its small axial moment)");
  Body b;
  b.name = name;
  b.flexible = false;
  b.nq = 0;
  b.mass = mass;
  b.r0 = position;
  b.A0 = orientation;
  const Vector3d cG = orientation.transpose() * (com - position);
  const Matrix3d IG = orientation.transpose() * inertia * orientation;
  b.rdm = mass * cG;
  b.J0 = 0.5 * IG.trace() * Matrix3d::Identity() - IG + mass * cG * cG.transpose();
  b.Myy.resize(0, 0);
  b.Ke.resize(0, 0);
  b.De.resize(0, 0);
  b.Pdm.resize(3, 0);
  for (auto& r : b.rPdm) r.resize(3, 0);
  b.PsiI.resize(0, 3);
  b.y0.resize(0);
  b.yd0.resize(0);
  return b;
}

Body make_flexible_body(const std::string& name, const formats::Sid& sid, const Vector3d& position,
                        const Matrix3d& orientation, std::optional<double> ratio, bool stiffening,
                        const std::string& file, const std::string& field, std::vector<std::string>* notes) {
  const int nq = static_cast<int>(sid.nq());
  Body b;
  b.name = name;
  b.flexible = true;
  b.nq = nq;
  b.mass = sid.refmod.mass;
  b.r0 = position;
  b.A0 = orientation;
  const auto& I = sid.integrals;
  b.rdm = I.rdm;
  // Point rotary inertia as pseudo-inertia: 1/2 omega^T I omega = 1/2 tr(Omega J Omega^T) with
  // J = 1/2 tr(I) 1 - I on the constraint manifold (FORMULATION.md section 3).
  b.J0 = I.rrdm + 0.5 * sid.rotary.I.trace() * Matrix3d::Identity() - sid.rotary.I;
  b.Pdm = I.Pdm;
  b.rPdm = I.rPdm;
  b.PPdm = I.PPdm;
  b.PsiI = sid.rotary.PsiI;
  b.has_rotary_coupling = nq > 0 && b.PsiI.cwiseAbs().maxCoeff() > 0;
  b.Myy = MatrixXd::Zero(nq, nq);
  for (int a = 0; a < 3; ++a) b.Myy += I.PPdm[a][a];
  b.Myy += sid.rotary.PsiIPsi;
  b.Myy = 0.5 * (b.Myy + b.Myy.transpose());
  b.Ke = sid.Ke;
  b.De = sid.De;
  const double me_scale = std::max(1e-300, sid.Me.cwiseAbs().maxCoeff());
  if (notes && nq > 0 && (b.Myy - sid.Me).cwiseAbs().maxCoeff() > 1e-6 * me_scale)
    notes->push_back("body '" + name + "': /sid/Me differs from the modal mass of /integrals (relative " +
                     num((b.Myy - sid.Me).cwiseAbs().maxCoeff() / me_scale) + "); the integrals are used");
  if (nq > 0) {
    Eigen::SelfAdjointEigenSolver<MatrixXd> em(b.Myy);
    if (!(em.eigenvalues().minCoeff() > 1e-12 * em.eigenvalues().maxCoeff()))
      throw ModelError(file, "/integrals/PPdm", "the modal mass matrix is not positive definite (referenced by " + field + ")");
  }
  if (ratio && *ratio > 0 && nq > 0) {
    // Modal damping of the given ratio on the body's own modes (Ke x = w^2 Myy x, x^T Myy x = 1):
    // D = Myy X diag(2 zeta w) X^T Myy, added to the SID's De.
    Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> ge(0.5 * (b.Ke + b.Ke.transpose()), b.Myy);
    const VectorXd w = ge.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    const MatrixXd MX = b.Myy * ge.eigenvectors();
    b.De += MX * (2.0 * *ratio * w).asDiagonal() * MX.transpose();
  }
  if (stiffening && sid.stiffening && nq > 0) {
    StiffeningTerms s;
    for (int c = 0; c < 3; ++c) {
      s.Kt[c] = MatrixXd::Zero(nq, nq);
      s.Kr[c] = MatrixXd::Zero(nq, nq);
    }
    for (auto& k : s.Kw) k = MatrixXd::Zero(nq, nq);
    for (int k = 0; k < nq; ++k)
      for (int i = 0; i < nq; ++i) {
        for (int c = 0; c < 3; ++c) {
          s.Kt[c](i, k) = sid.stiffening->K0t[k](i, c);
          s.Kr[c](i, k) = sid.stiffening->K0r[k](i, c);
        }
        for (int j = 0; j < 6; ++j) s.Kw[j](i, k) = sid.stiffening->K0om[k](i, j);
      }
    b.stiffening = std::move(s);
  }
  for (const auto& n : sid.nodes) b.nodes.push_back({n.name, n.origin, n.phi, n.psi});
  b.y0 = VectorXd::Zero(nq);
  b.yd0 = VectorXd::Zero(nq);
  return b;
}

}  // namespace ffr::runtime
