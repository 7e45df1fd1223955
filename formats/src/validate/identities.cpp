// validate: the cross-member identities of SPEC.md section 9.
#include "context.hpp"

namespace ffr::formats::validation {

void check_identities(Context& cx) {
  const Sid& s = cx.sid;
  const Eigen::Index nq = s.nq();
  const double tol = cx.opt.identity_rtol;
  const auto& sc = cx.sc;

  { Worst w; w.add_matrix(s.mdCM.M1 - s.Ct.M0, "[");
    cx.record("mdCM.M1 = Ct.M0", "/sid/mdCM/M1 /sid/Ct/M0", w, sc.t1(), tol); }

  Worst wsym, wdiag, wJsym, wJd, wJo, wGe, wKr, wOe, wSum;
  static const int off[3][2] = {{0, 1}, {1, 2}, {0, 2}};  // xy, yz, xz -> columns 3, 4, 5
  for (Eigen::Index k = 0; k < nq; ++k) {
    const std::string K = open_index({k});
    const Eigen::Matrix3d& G = s.Gr[k];
    const Eigen::Matrix3d& J1 = s.J.M1[k];
    wsym.add_matrix(G + G.transpose() - 2 * J1, K);
    wdiag.add_matrix((G.diagonal() - J1.diagonal()).transpose(), K);
    wJsym.add_matrix(J1 - J1.transpose(), K);
    for (int a = 0; a < 3; ++a) wJd.add(J1(a, a) + 2 * s.Oe.M0(k, a), index({k, a}));
    for (int o = 0; o < 3; ++o) wJo.add(J1(off[o][0], off[o][1]) + s.Oe.M0(k, 3 + o), index({k, 3 + o}));
    for (Eigen::Index i = 0; i < nq; ++i) {
      const std::string KI = open_index({k, i});
      wGe.add_matrix(s.Ge[k].row(i) - 2 * s.Cr.M1[k].row(i), KI);
      wKr.add_matrix(s.Cr.M1[k].row(i) + s.Cr.M1[i].row(k), KI);
      wOe.add_matrix(s.Oe.M1[k].row(i) - s.Oe.M1[i].row(k), KI);
      const double sum = s.Oe.M1[k](i, kXX) + s.Oe.M1[k](i, kYY) + s.Oe.M1[k](i, kZZ);
      wSum.add(sum + 2 * (s.Me(k, i) - s.rotary.PsiIPsi(k, i)), index({k, i}));
    }
  }
  cx.record("Gr + Gr^T = 2 J.M1", "/sid/Gr/M0 /sid/J/M1", wsym, sc.r1(), tol);
  cx.record("diag Gr = diag J.M1", "/sid/Gr/M0 /sid/J/M1", wdiag, sc.r1(), tol);
  cx.record("J.M1 symmetric", "/sid/J/M1", wJsym, sc.r1(), tol);
  cx.record("J.M1 diagonal = -2 Oe.M0 (xx,yy,zz)", "/sid/J/M1 /sid/Oe/M0", wJd, sc.r1(), tol);
  cx.record("J.M1 off-diagonal = -Oe.M0 (xy,yz,xz)", "/sid/J/M1 /sid/Oe/M0", wJo, sc.r1(), tol);
  cx.record("Ge = 2 Kr (Cr.M1)", "/sid/Ge/M0 /sid/Cr/M1", wGe, sc.q2(), tol);
  cx.record("Kr antisymmetric in (i,k)", "/sid/Cr/M1", wKr, sc.q2(), tol);
  cx.record("Oe.M1 symmetric in (i,k)", "/sid/Oe/M1", wOe, sc.q2(), tol);
  cx.record("sum of Oe.M1 (xx,yy,zz) = -2 (Me - PsiIPsi)", "/sid/Oe/M1 /sid/Me/M0 /integrals/rotary/PsiIPsi", wSum, sc.q2(), tol);

  // PPdm[a][b](k,i) = PPdm[b][a](i,k) by definition.
  Worst wP;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      wP.add_matrix(s.integrals.PPdm[a][b] - s.integrals.PPdm[b][a].transpose(),
                    open_index({a, b}));
  cx.record("PPdm[a][b] = PPdm[b][a]^T", "/integrals/PPdm", wP, sc.q2(), tol);
}

}  // namespace ffr::formats::validation
