// SID members from the primitive integrals: formats/SPEC.md sections 6 and 8, with
//   R_k(a,b)   = rPdm[a](b,k)  = int c_a Phi_{k,b} dm
//   P[a][b](i,k) = PPdm[a][b](i,k) = int Phi_{i,a} Phi_{k,b} dm.
#include "ffr/preproc/reduce/invariants.hpp"

namespace ffr::preproc {

void members_from_integrals(formats::Sid& s) {
  const Index nq = s.nq();
  const auto& I = s.integrals;
  const auto& P = I.PPdm;
  const Eigen::Matrix3d E = Eigen::Matrix3d::Identity();
  s.mdCM.M0 = I.rdm;
  s.J.M0 = I.rrdm.trace() * E - I.rrdm + s.rotary.I;
  s.mdCM.M1 = I.Pdm.transpose();
  s.Ct.M0 = I.Pdm.transpose();
  s.Me = P[0][0] + P[1][1] + P[2][2] + s.rotary.PsiIPsi;
  for (Index k = 0; k < nq; ++k) {
    Eigen::Matrix3d R;
    for (int a = 0; a < 3; ++a) R.row(a) = I.rPdm[a].col(k).transpose();
    const double tr = R.trace();
    s.J.M1[static_cast<std::size_t>(k)] = 2 * tr * E - R - R.transpose();
    // int c x Phi_k dm, plus the rotary part sum Psi_k^T I_p.
    s.Cr.M0.row(k) = Eigen::RowVector3d(R(1, 2) - R(2, 1), R(2, 0) - R(0, 2), R(0, 1) - R(1, 0)) + s.rotary.PsiI.row(k);
    s.Gr[static_cast<std::size_t>(k)] = 2 * (tr * E - R.transpose());
    const auto& J1 = s.J.M1[static_cast<std::size_t>(k)];
    s.Oe.M0.row(k) << -J1(0, 0) / 2, -J1(1, 1) / 2, -J1(2, 2) / 2, -J1(0, 1), -J1(1, 2), -J1(0, 2);
    auto& Kr = s.Cr.M1[static_cast<std::size_t>(k)];
    auto& Oe1 = s.Oe.M1[static_cast<std::size_t>(k)];
    for (Index i = 0; i < nq; ++i) {
      // (Phi_k x Phi_i)_c
      Kr(i, 0) = P[1][2](k, i) - P[2][1](k, i);
      Kr(i, 1) = P[2][0](k, i) - P[0][2](k, i);
      Kr(i, 2) = P[0][1](k, i) - P[1][0](k, i);
      // Phi_i^T (coefficient of omega_bar_j in skew(w) skew(w)) Phi_k
      const double dot = P[0][0](i, k) + P[1][1](i, k) + P[2][2](i, k);
      Oe1(i, formats::kXX) = P[0][0](i, k) - dot;
      Oe1(i, formats::kYY) = P[1][1](i, k) - dot;
      Oe1(i, formats::kZZ) = P[2][2](i, k) - dot;
      Oe1(i, formats::kXY) = P[0][1](i, k) + P[1][0](i, k);
      Oe1(i, formats::kYZ) = P[1][2](i, k) + P[2][1](i, k);
      Oe1(i, formats::kXZ) = P[0][2](i, k) + P[2][0](i, k);
    }
    s.Ge[static_cast<std::size_t>(k)] = 2 * Kr;
  }
}

}  // namespace ffr::preproc
