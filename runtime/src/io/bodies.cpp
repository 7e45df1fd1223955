// Rigid and flexible bodies from their physical description (FORMULATION.md section 3).
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/load.hpp"
#include "../number_text.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace ffr::runtime {
namespace {

// /sid/Ke/M1, checked: nq slices of nq x nq, finite, each symmetric (Phi_i^T K_G Phi_j).
struct ModalStress {
  std::vector<MatrixXd> M1;
};

ModalStress modal_stress(const formats::Sid& sid, const std::string& file) {
  ModalStress out;
  if (sid.KeM1.empty()) return out;
  const auto nq = sid.nq();
  if (static_cast<formats::Index>(sid.KeM1.size()) != nq)
    throw ModelError(file, "/sid/Ke/M1", "wrong shape: expected [" + std::to_string(nq) + "," + std::to_string(nq) + "," +
                                             std::to_string(nq) + "], found " + std::to_string(sid.KeM1.size()) + " slices");
  double scale = 0;
  for (const auto& M : sid.KeM1) {
    if (M.rows() != nq || M.cols() != nq)
      throw ModelError(file, "/sid/Ke/M1", "wrong shape: expected slices [" + std::to_string(nq) + "," + std::to_string(nq) +
                                               "], found [" + std::to_string(M.rows()) + "," + std::to_string(M.cols()) + "]");
    if (!M.allFinite()) throw ModelError(file, "/sid/Ke/M1", "not finite");
    scale = std::max(scale, M.cwiseAbs().maxCoeff());
  }
  for (std::size_t k = 0; k < sid.KeM1.size(); ++k) {
    const double asym = (sid.KeM1[k] - sid.KeM1[k].transpose()).cwiseAbs().maxCoeff();
    if (asym > 1e-9 * scale)
      throw ModelError(file, "/sid/Ke/M1",
                       "slice " + std::to_string(k) + " is not symmetric in (i, j) (|M1 - M1^T| = " + num(asym) + " of " +
                           num(scale) + "): M1[k](i,j) = Phi_i^T K_G(sigma_k) Phi_j is");
    out.M1.push_back(0.5 * (sid.KeM1[k] + sid.KeM1[k].transpose()));
  }
  return out;
}

// Ke^+ restricted to the modes in `use` (a pseudo-inverse: rigid or null directions get none).
MatrixXd static_flexibility(const MatrixXd& Ke, const std::vector<int>& use) {
  const int n = static_cast<int>(use.size()), nq = static_cast<int>(Ke.rows());
  MatrixXd K(n, n);
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < n; ++c) K(a, c) = Ke(use[a], use[c]);
  Eigen::SelfAdjointEigenSolver<MatrixXd> es(0.5 * (K + K.transpose()));
  const VectorXd& ev = es.eigenvalues();
  const double tol = 1e-10 * std::max(1e-300, ev.cwiseAbs().maxCoeff());
  VectorXd inv = VectorXd::Zero(n);
  for (int a = 0; a < n; ++a)
    if (ev(a) > tol) inv(a) = 1.0 / ev(a);
  const MatrixXd Kp = es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose();
  MatrixXd F = MatrixXd::Zero(nq, nq);
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < n; ++c) F(use[a], use[c]) = Kp(a, c);
  return F;
}

// Each load-case matrix less the part that the body's own modal stress (Ke/M1) gives at the
// load's quasi-static modal response q_L (FORMULATION.md 7): K0_L - sum_k q_L,k M1[k]. q_L
// solves Ke q = Phi^T f_L under the conditions the reducer solved the case under: the inertial
// cases with the Craig-Bampton interfaces held (constraint-mode coordinates zero), the
// interface forces with only the frame held (every mode).
void remove_modal_part(const formats::Sid& sid, const ModalStress& ms, StiffeningTerms& s) {
  const int nq = static_cast<int>(sid.nq());
  std::vector<int> all, normal;
  for (int k = 0; k < nq; ++k) {
    all.push_back(k);
    if (static_cast<std::size_t>(k) >= sid.refmod.mode_type.size() || sid.refmod.mode_type[static_cast<std::size_t>(k)] != formats::ModeType::Constraint)
      normal.push_back(k);
  }
  const MatrixXd F_all = static_flexibility(sid.Ke, all), F_held = static_flexibility(sid.Ke, normal);
  auto modal = [&](const MatrixXd& F, const VectorXd& g) {
    const VectorXd q = F * g;
    MatrixXd C = MatrixXd::Zero(nq, nq);
    for (int k = 0; k < nq; ++k) C += q(k) * ms.M1[static_cast<std::size_t>(k)];
    return C;
  };
  // Modal loads of the inertial cases: -int Phi^T (e_c, e_c x c, C_j c) dm.
  for (int c = 0; c < 3; ++c) {
    if (sid.Ct.M0.rows() == nq) s.Kt[c] -= modal(F_held, -sid.Ct.M0.col(c));
    if (sid.Cr.M0.rows() == nq) s.Kr[c] -= modal(F_held, -sid.Cr.M0.col(c));
  }
  if (sid.Oe.M0.rows() == nq)
    for (int j = 0; j < 6; ++j) s.Kw[j] -= modal(F_held, -sid.Oe.M0.col(j));
  for (auto& is : s.interfaces) {
    const auto& n = sid.nodes[static_cast<std::size_t>(is.node)];
    for (int c = 0; c < 3; ++c) {
      is.KF[c] -= modal(F_all, n.phi.row(c).transpose());
      is.KM[c] -= modal(F_all, n.psi.row(c).transpose());
    }
  }
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
  const ModalStress ms = modal_stress(sid, file);
  if (stiffening && !ms.M1.empty()) {
    ModalStressStiffness m;
    // by_mode carries Ke^+ in its last nq rows (the quartic closure, FORMULATION.md 7).
    m.by_mode.resize(nq * nq + nq, nq);
    m.by_coeff.resize(nq * nq, nq);
    for (int k = 0; k < nq; ++k) {
      m.by_mode.block(k * nq, 0, nq, nq) = ms.M1[static_cast<std::size_t>(k)];
      m.by_coeff.col(k) = ms.M1[static_cast<std::size_t>(k)].reshaped();
    }
    std::vector<int> all(static_cast<std::size_t>(nq));
    for (int k = 0; k < nq; ++k) all[static_cast<std::size_t>(k)] = k;
    m.by_mode.bottomRows(nq) = static_flexibility(sid.Ke, all);
    b.modal_stress = std::move(m);
  }
  if (stiffening && nq > 0 && sid.ksigma.M0.size() == nq && sid.ksigma.M1.rows() == nq && sid.ksigma.M1.cols() == nq &&
      (sid.ksigma.M0.cwiseAbs().maxCoeff() > 0 || sid.ksigma.M1.cwiseAbs().maxCoeff() > 0)) {
    const double scale = std::max(1e-300, sid.ksigma.M1.cwiseAbs().maxCoeff());
    if ((sid.ksigma.M1 - sid.ksigma.M1.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
      throw ModelError(file, "/sid/ksigma/M1", "not symmetric (a geometric stiffness is; referenced by " + field + ")");
    b.prestress = Prestress{sid.ksigma.M0, 0.5 * (sid.ksigma.M1 + sid.ksigma.M1.transpose())};
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
    for (const auto& itf : sid.stiffening->interfaces) {
      InterfaceStiffening is;
      is.name = itf.name;
      for (const auto& si : sid.interfaces)
        if (si.name == itf.name) is.node = static_cast<int>(si.node);
      if (is.node < 0) is.node = static_cast<int>(sid.find_node(itf.name));
      if (is.node < 0 || is.node >= static_cast<int>(sid.nodes.size()))
        throw ModelError(file, "/stiffening/interfaces/" + itf.name, "names no interface or node of the SID");
      for (int c = 0; c < 3; ++c) {
        is.KF[c] = MatrixXd::Zero(nq, nq);
        is.KM[c] = MatrixXd::Zero(nq, nq);
        for (int k = 0; k < nq; ++k)
          for (int i = 0; i < nq; ++i) {
            is.KF[c](i, k) = itf.K0F[static_cast<std::size_t>(k)](i, c);
            is.KM[c](i, k) = itf.K0M[static_cast<std::size_t>(k)](i, c);
          }
      }
      s.interfaces.push_back(std::move(is));
    }
    if (!ms.M1.empty()) remove_modal_part(sid, ms, s);
    for (const auto t : sid.refmod.mode_type) s.use_mean_spin = s.use_mean_spin || t == formats::ModeType::Constraint;
    const auto& rP = sid.integrals.rPdm;
    s.spin_h.resize(3, nq);
    for (int k = 0; k < nq; ++k)
      s.spin_h.col(k) = Vector3d(rP[1](2, k) - rP[2](1, k), rP[2](0, k) - rP[0](2, k), rP[0](1, k) - rP[1](0, k)) +
                        Vector3d(sid.rotary.PsiI.row(k).transpose());
    b.stiffening = std::move(s);
  }
  for (const auto& n : sid.nodes) b.nodes.push_back({n.name, n.origin, n.phi, n.psi});
  b.y0 = VectorXd::Zero(nq);
  b.yd0 = VectorXd::Zero(nq);
  return b;
}

}  // namespace ffr::runtime
