// validate: every SID member against its formula from the primitive integrals (SPEC.md 8).
#include "context.hpp"

namespace ffr::formats::validation {
namespace {

using Eigen::Matrix3d;

// R_k(a,b) = rPdm[a](b,k) = int c_a Phi_bk dm.
Matrix3d R_of(const Integrals& I, Eigen::Index k) {
  Matrix3d r;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) r(a, b) = I.rPdm[a](b, k);
  return r;
}

// v_c = eps_cab X(a,b): the vector of the antisymmetric part (times 2).
Eigen::Vector3d eps(const Matrix3d& X) { return {X(1, 2) - X(2, 1), X(2, 0) - X(0, 2), X(0, 1) - X(1, 0)}; }

std::string at(Eigen::Index k) { return open_index({k}); }

}  // namespace

void check_members_vs_integrals(Context& cx) {
  const Sid& s = cx.sid;
  const Integrals& I = s.integrals;
  const Rotary& rot = s.rotary;
  const Eigen::Index nq = s.nq();
  const double tol = cx.opt.identity_rtol;
  const auto& sc = cx.sc;
  const Matrix3d Id = Matrix3d::Identity();
  auto P = [&](int a, int b, Eigen::Index k, Eigen::Index i) { return I.PPdm[a][b](k, i); };

  { Worst w; w.add_matrix((s.mdCM.M0 - I.rdm).transpose(), "[");
    cx.record("mdCM.M0 = rdm", "/sid/mdCM/M0 /integrals/rdm", w, sc.m * sc.L, tol); }
  { Worst w; w.add_matrix(s.mdCM.M1 - I.Pdm.transpose(), "[");
    cx.record("mdCM.M1 = Pdm^T", "/sid/mdCM/M1 /integrals/Pdm", w, sc.t1(), tol); }
  { Worst w; w.add_matrix(s.Ct.M0 - I.Pdm.transpose(), "[");
    cx.record("Ct.M0 = Pdm^T", "/sid/Ct/M0 /integrals/Pdm", w, sc.t1(), tol); }
  { Worst w; w.add_matrix(s.J.M0 - (I.rrdm.trace() * Id - I.rrdm + rot.I), "[");
    cx.record("J.M0 = tr(rrdm) I - rrdm + rotary.I", "/sid/J/M0 /integrals/rrdm /integrals/rotary/I", w, sc.m * sc.L * sc.L, tol); }

  Worst wJ, wCr0, wGr, wOe0, wCr1, wGe, wOe1, wMe;
  for (Eigen::Index k = 0; k < nq; ++k) {
    const Matrix3d R = R_of(I, k);
    wJ.add_matrix(s.J.M1[k] - (2 * R.trace() * Id - R - R.transpose()), at(k));
    wGr.add_matrix(s.Gr[k] - (2 * R.trace() * Id - 2 * R.transpose()), at(k));
    const Eigen::Vector3d cr = eps(R) + rot.PsiI.row(k).transpose();
    wCr0.add_matrix((s.Cr.M0.row(k).transpose() - cr).transpose(), at(k));
    Eigen::Matrix<double, 1, 6> oe;
    oe << R(0, 0) - R.trace(), R(1, 1) - R.trace(), R(2, 2) - R.trace(), R(0, 1) + R(1, 0), R(1, 2) + R(2, 1),
        R(0, 2) + R(2, 0);
    wOe0.add_matrix(s.Oe.M0.row(k) - oe, at(k));
    for (Eigen::Index i = 0; i < nq; ++i) {
      Matrix3d Pki, Pik;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          Pki(a, b) = P(a, b, k, i);
          Pik(a, b) = P(a, b, i, k);
        }
      const Eigen::Vector3d kr = eps(Pki);
      const std::string where = open_index({k, i});
      wCr1.add_matrix((s.Cr.M1[k].row(i).transpose() - kr).transpose(), where);
      wGe.add_matrix((s.Ge[k].row(i).transpose() - 2 * kr).transpose(), where);
      Eigen::Matrix<double, 1, 6> o1;
      o1 << Pik(0, 0) - Pik.trace(), Pik(1, 1) - Pik.trace(), Pik(2, 2) - Pik.trace(), Pik(0, 1) + Pik(1, 0),
          Pik(1, 2) + Pik(2, 1), Pik(0, 2) + Pik(2, 0);
      wOe1.add_matrix(s.Oe.M1[k].row(i) - o1, where);
      wMe.add(s.Me(k, i) - (Pki.trace() + rot.PsiIPsi(k, i)), index({k, i}));
    }
  }
  cx.record("J.M1 = 2 tr(R_k) I - R_k - R_k^T", "/sid/J/M1 /integrals/rPdm", wJ, sc.r1(), tol);
  cx.record("Gr = 2 tr(R_k) I - 2 R_k^T", "/sid/Gr/M0 /integrals/rPdm", wGr, sc.r1(), tol);
  cx.record("Cr.M0 = eps R_k + rotary.PsiI", "/sid/Cr/M0 /integrals/rPdm /integrals/rotary/PsiI", wCr0, sc.r1(), tol);
  cx.record("Oe.M0 from rPdm", "/sid/Oe/M0 /integrals/rPdm", wOe0, sc.r1(), tol);
  cx.record("Cr.M1 = eps PPdm", "/sid/Cr/M1 /integrals/PPdm", wCr1, sc.q2(), tol);
  cx.record("Ge = 2 eps PPdm", "/sid/Ge/M0 /integrals/PPdm", wGe, sc.q2(), tol);
  cx.record("Oe.M1 from PPdm", "/sid/Oe/M1 /integrals/PPdm", wOe1, sc.q2(), tol);
  cx.record("Me = sum_a PPdm[a][a] + rotary.PsiIPsi", "/sid/Me/M0 /integrals/PPdm /integrals/rotary/PsiIPsi", wMe, sc.q2(), tol);
}

}  // namespace ffr::formats::validation
