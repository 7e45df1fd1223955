// 6-DOF bushing, linear or with a characteristic per axis, and a preload. Its six measures are sums of dot products of the markers' points and
// axes (E1 = [e1 f1 g1] of marker 1, E2 of marker 2, d = p2 - p1):
//   s_k     = E1_k . d                                   (k = x, y, z)
//   theta_x = (g1.f2 - f1.g2)/2, theta_y = (e1.g2 - g1.e2)/2, theta_z = (f1.e2 - e1.f2)/2
// (the small relative rotation of triad 2, in triad 1). The generalized force is
// Q = -sum_i F_i grad s_i with F_i = f_i(s_i - s0_i) + c_i s_dot_i + P_i (f_i linear, k_i x, or
// a table; P_i the preload), and its exact tangent with k_i = f_i'(s_i - s0_i)
// K = sum_i k_i g_i^T g_i + c_i g_i^T (H_i z_dot)^T + F_i H_i,  C = sum_i c_i g_i^T g_i.
#include "force_helpers.hpp"
#include "forces.hpp"

namespace ffr::runtime::detail {
namespace {

// A dot product term coef * (x_a . x_b); x = marker (0 or 1) and quantity (-1 point, k axis).
struct DotTerm {
  double coef;
  int ma, ka, mb, kb;
};

// Term lists of the six measures.
const DotTerm kTerms[6][2] = {
    {{1, 0, 0, 1, -1}, {-1, 0, 0, 0, -1}},
    {{1, 0, 1, 1, -1}, {-1, 0, 1, 0, -1}},
    {{1, 0, 2, 1, -1}, {-1, 0, 2, 0, -1}},
    {{0.5, 0, 2, 1, 1}, {-0.5, 0, 1, 1, 2}},
    {{0.5, 0, 0, 1, 2}, {-0.5, 0, 2, 1, 0}},
    {{0.5, 0, 1, 1, 0}, {-0.5, 0, 0, 1, 1}},
};

const Vector3d& value(const MarkerData& md, int k) { return k < 0 ? md.p : md.e[k]; }
const Vector3d& rate(const MarkerData& md, int k) { return k < 0 ? md.pd : md.ed[k]; }
const Matrix3N& jac(const MarkerData& md, int k) { return k < 0 ? md.Jp : md.Je[k]; }

Vector6d measures(const Bushing& bu, const Data& data) {
  const MarkerData* md[2] = {&data.markers[bu.m1], &data.markers[bu.m2]};
  Vector6d s = Vector6d::Zero();
  for (int i = 0; i < 6; ++i)
    for (const DotTerm& t : kTerms[i]) s(i) += t.coef * value(*md[t.ma], t.ka).dot(value(*md[t.mb], t.kb));
  return s;
}

}  // namespace

Vector6d bushing_measures(const Model& model, const Bushing& bu, const Data& data) {
  (void)model;
  return measures(bu, data);
}

namespace {

// The elastic part of each axis's force (linear k or its table, plus the preload) and its slope.
void elastic(const Bushing& bu, const Vector6d& ds, Vector6d& F, Vector6d& slope) {
  for (int i = 0; i < 6; ++i) {
    if (bu.tables[i].empty()) {
      F(i) = bu.k(i) * ds(i);
      slope(i) = bu.k(i);
    } else {
      double d2;
      bu.tables[i].eval(ds(i), 0, F(i), slope(i), d2);
    }
    F(i) += bu.preload(i);
  }
}

}  // namespace

Vector6d bushing_force(const Model& model, const Bushing& bu, const Data& data) {
  // The measures' rates from the markers' (as bushing_forces computes them).
  const MarkerData* md[2] = {&data.markers[bu.m1], &data.markers[bu.m2]};
  Vector6d sd = Vector6d::Zero();
  for (int i = 0; i < 6; ++i)
    for (const DotTerm& t : kTerms[i])
      sd(i) += t.coef * (rate(*md[t.ma], t.ka).dot(value(*md[t.mb], t.kb)) + value(*md[t.ma], t.ka).dot(rate(*md[t.mb], t.kb)));
  Vector6d F, slope;
  elastic(bu, bushing_measures(model, bu, data) - bu.s0, F, slope);
  return F + bu.c.cwiseProduct(sd);
}

double bushing_energy(const Model& model, const Bushing& bu, Data& data) {
  const Vector6d ds = bushing_measures(model, bu, data) - bu.s0;
  double e = 0;
  for (int i = 0; i < 6; ++i) {
    e += bu.tables[i].empty() ? 0.5 * bu.k(i) * ds(i) * ds(i) : bu.tables[i].integral(ds(i), 0) - bu.tables[i].integral(0.0, 0);
    e += bu.preload(i) * ds(i);
  }
  return e;
}

void bushing_forces(const Model& model, const Bushing& bu, Data& data, bool add_q, bool tangents) {
  const int mk[2] = {bu.m1, bu.m2};
  const Marker* mm[2] = {&model.markers[bu.m1], &model.markers[bu.m2]};
  const MarkerData* md[2] = {&data.markers[bu.m1], &data.markers[bu.m2]};
  const int body[2] = {mm[0]->body, mm[1]->body};
  const int nb[2] = {ncoord(model, body[0]), ncoord(model, body[1])};
  const int col0[2] = {0, nb[0]};
  const int ntot = nb[0] + nb[1];
  (void)mk;

  // Gradients of the six measures over [z1, z2] and their values and rates.
  auto g = data.fg.leftCols(ntot);
  g.setZero();
  Vector6d s = Vector6d::Zero(), sd = Vector6d::Zero();
  for (int i = 0; i < 6; ++i)
    for (const DotTerm& t : kTerms[i]) {
      const Vector3d& xa = value(*md[t.ma], t.ka);
      const Vector3d& xb = value(*md[t.mb], t.kb);
      s(i) += t.coef * xa.dot(xb);
      sd(i) += t.coef * (rate(*md[t.ma], t.ka).dot(xb) + xa.dot(rate(*md[t.mb], t.kb)));
      if (nb[t.ma]) g.row(i).segment(col0[t.ma], nb[t.ma]).noalias() += t.coef * xb.transpose() * jac(*md[t.ma], t.ka);
      if (nb[t.mb]) g.row(i).segment(col0[t.mb], nb[t.mb]).noalias() += t.coef * xa.transpose() * jac(*md[t.mb], t.kb);
    }
  Vector6d F, slope;
  elastic(bu, s - bu.s0, F, slope);
  F += bu.c.cwiseProduct(sd);
  for (int side = 0; side < 2 && add_q; ++side)
    if (nb[side])
      data.Q.segment(offset(model, body[side]), nb[side]).noalias() -= g.middleCols(col0[side], nb[side]).transpose() * F;
  if (!tangents) return;

  auto Kc = data.fK.topLeftCorner(ntot, ntot);
  auto Cc = data.fC.topLeftCorner(ntot, ntot);
  auto z = data.fz.head(ntot);
  // Row i: H_i z (fH's first six rows as workspace: no tangent below reads fH).
  auto HZ = data.fH.topLeftCorner(6, ntot);
  for (int side = 0; side < 2; ++side)
    if (nb[side]) z.segment(col0[side], nb[side]) = data.state.qd.segment(offset(model, body[side]), nb[side]);
  // H_i is linear in its dot-product terms, so sum_i F_i H_i is accumulated term by term with the
  // weights F_i coef straight into Kc, and H_i z from the terms' Jacobian-vector products: no
  // [ntot, ntot] H_i is formed (six of them, each cleared, multiplied by z and added, were a
  // sixth of the bushings' cost on the washing machine, whose gasket and feet span a flexible
  // body's coordinates). Same sums, in another order.
  Kc.setZero();
  HZ.setZero();
  Vector3d Jz[2][4];  // J_x z of each marker quantity (point, axes 0-2) that a term uses
  for (int side = 0; side < 2; ++side)
    for (int k = -1; k < 3; ++k)
      Jz[side][k + 1] = nb[side] ? Vector3d(jac(*md[side], k) * z.segment(col0[side], nb[side])) : Vector3d::Zero();
  for (int i = 0; i < 6; ++i) {
    if (slope(i) == 0 && bu.c(i) == 0 && F(i) == 0) continue;
    for (const DotTerm& t : kTerms[i]) {
      const int sa = t.ma, sb = t.mb;
      const Vector3d& xa = value(*md[sa], t.ka);
      const Vector3d& xb = value(*md[sb], t.kb);
      const double w = F(i) * t.coef;
      if (nb[sa] && nb[sb] && w != 0) {
        Kc.block(col0[sa], col0[sb], nb[sa], nb[sb]).noalias() += w * jac(*md[sa], t.ka).transpose() * jac(*md[sb], t.kb);
        Kc.block(col0[sb], col0[sa], nb[sb], nb[sa]).noalias() += w * jac(*md[sb], t.kb).transpose() * jac(*md[sa], t.ka);
      }
      if (on_node(model, *mm[sa]) && w != 0) add_jt_f_derivative(slice(*mm[sa], t.ka), xb, w, Kc.block(col0[sa], col0[sa], nb[sa], nb[sa]));
      if (on_node(model, *mm[sb]) && w != 0) add_jt_f_derivative(slice(*mm[sb], t.kb), xa, w, Kc.block(col0[sb], col0[sb], nb[sb], nb[sb]));
      if (bu.c(i) == 0) continue;
      if (nb[sa] && nb[sb]) {
        HZ.row(i).segment(col0[sa], nb[sa]).noalias() += (t.coef * Jz[sb][t.kb + 1]).transpose() * jac(*md[sa], t.ka);
        HZ.row(i).segment(col0[sb], nb[sb]).noalias() += (t.coef * Jz[sa][t.ka + 1]).transpose() * jac(*md[sb], t.kb);
      }
      if (on_node(model, *mm[sa]))
        add_jt_f_derivative_times(slice(*mm[sa], t.ka), xb, t.coef, z.segment(col0[sa], nb[sa]), HZ.row(i).segment(col0[sa], nb[sa]));
      if (on_node(model, *mm[sb]))
        add_jt_f_derivative_times(slice(*mm[sb], t.kb), xa, t.coef, z.segment(col0[sb], nb[sb]), HZ.row(i).segment(col0[sb], nb[sb]));
    }
  }
  // K = sum_i k_i g_i^T g_i + c_i g_i^T (H_i z)^T + F_i H_i,  C = sum_i c_i g_i^T g_i (outer
  // products with scalar factors: no temporaries, the step stays allocation-free).
  Cc.setZero();
  for (int i = 0; i < 6; ++i) {
    if (slope(i) != 0) Kc.noalias() += slope(i) * g.row(i).transpose() * g.row(i);
    if (bu.c(i) == 0) continue;
    Kc.noalias() += bu.c(i) * g.row(i).transpose() * HZ.row(i);
    Cc.noalias() += bu.c(i) * g.row(i).transpose() * g.row(i);
  }
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      if (nb[a] && nb[b]) {
        const int oa = offset(model, body[a]), ob = offset(model, body[b]);
        data.K.block(oa, ob, nb[a], nb[b]) += Kc.block(col0[a], col0[b], nb[a], nb[b]);
        data.C.block(oa, ob, nb[a], nb[b]) += Cc.block(col0[a], col0[b], nb[a], nb[b]);
      }
}

}  // namespace ffr::runtime::detail
