// transform_modes(): the same body in the modal basis Phi' = Phi T (see diff.hpp).
#include "ffr/formats/diff.hpp"

#include <stdexcept>

namespace ffr::formats {
namespace {

using Eigen::MatrixXd;

// One mode index, stacked: X'[k] = sum_j T(j,k) X[j].
template <class M>
std::vector<M> first_order_stack(const std::vector<M>& X, const MatrixXd& T) {
  std::vector<M> out(X.size());
  for (std::size_t k = 0; k < X.size(); ++k) {
    out[k] = M::Zero(X.empty() ? 0 : X[0].rows(), X.empty() ? 0 : X[0].cols());
    for (std::size_t j = 0; j < X.size(); ++j) out[k] += T(j, k) * X[j];
  }
  return out;
}

// Two mode indices, X[k] has the second one as rows: X'[k].row(i) = sum_jl T(j,k) T(l,i) X[j].row(l).
template <class M>
std::vector<M> second_order_stack(const std::vector<M>& X, const MatrixXd& T) {
  auto out = first_order_stack(X, T);
  for (auto& m : out) m = (T.transpose() * m).eval();
  return out;
}

MatrixXd bilinear(const MatrixXd& X, const MatrixXd& T) { return T.transpose() * X * T; }

}  // namespace

Sid transform_modes(const Sid& s, const MatrixXd& T) {
  const Eigen::Index nq = s.nq();
  if (T.rows() != nq || T.cols() != nq) throw std::invalid_argument("transform_modes: T must be nq x nq");
  Sid o = s;
  const MatrixXd Tt = T.transpose();
  // Mode index as rows.
  o.mdCM.M1 = Tt * s.mdCM.M1;
  o.Ct.M0 = Tt * s.Ct.M0;
  o.Cr.M0 = Tt * s.Cr.M0;
  o.Oe.M0 = Tt * s.Oe.M0;
  o.rotary.PsiI = Tt * s.rotary.PsiI;
  o.ksigma.M0 = Tt * s.ksigma.M0;
  // Mode index as columns.
  o.integrals.Pdm = s.integrals.Pdm * T;
  for (int a = 0; a < 3; ++a) o.integrals.rPdm[a] = s.integrals.rPdm[a] * T;
  for (auto& n : o.nodes) {
    n.phi = n.phi * T;
    n.psi = n.psi * T;
  }
  // Stacks over the first mode index.
  o.J.M1 = first_order_stack(s.J.M1, T);
  o.Gr = first_order_stack(s.Gr, T);
  if (!s.visual.empty()) o.visual.modes = first_order_stack(s.visual.modes, T);
  // Two mode indices.
  o.Me = bilinear(s.Me, T);
  o.Ke = bilinear(s.Ke, T);
  o.De = bilinear(s.De, T);
  o.ksigma.M1 = bilinear(s.ksigma.M1, T);
  o.rotary.PsiIPsi = bilinear(s.rotary.PsiIPsi, T);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) o.integrals.PPdm[a][b] = bilinear(s.integrals.PPdm[a][b], T);
  o.Cr.M1 = second_order_stack(s.Cr.M1, T);
  o.Ge = second_order_stack(s.Ge, T);
  o.Oe.M1 = second_order_stack(s.Oe.M1, T);
  // Three mode indices: KeM1'[k] = sum_j T(j,k) T^T KeM1[j] T.
  if (!s.KeM1.empty()) {
    o.KeM1 = first_order_stack(s.KeM1, T);
    for (auto& m : o.KeM1) m = bilinear(m, T);
  }
  if (s.stiffening) {
    auto& st = *o.stiffening;
    st.K0t = second_order_stack(s.stiffening->K0t, T);
    st.K0r = second_order_stack(s.stiffening->K0r, T);
    st.K0om = second_order_stack(s.stiffening->K0om, T);
    for (std::size_t i = 0; i < st.interfaces.size(); ++i) {
      st.interfaces[i].K0F = second_order_stack(s.stiffening->interfaces[i].K0F, T);
      st.interfaces[i].K0M = second_order_stack(s.stiffening->interfaces[i].K0M, T);
    }
  }
  return o;
}

}  // namespace ffr::formats
