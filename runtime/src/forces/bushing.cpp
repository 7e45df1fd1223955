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
#include "../joints/weighted_gram.hpp"

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

void bushing_forces(const Model& model, const Bushing& bu, Data& data, bool add_q, bool tangents,
                    Eigen::Matrix<double, 12, 2>* ends) {
  const Marker* mm[2] = {&model.markers[bu.m1], &model.markers[bu.m2]};
  const MarkerData* md[2] = {&data.markers[bu.m1], &data.markers[bu.m2]};
  const int body[2] = {mm[0]->body, mm[1]->body};
  const int nb[2] = {ncoord(model, body[0]), ncoord(model, body[1])};
  const int col0[2] = {0, nb[0]};
  const int ntot = nb[0] + nb[1];

  // Every measure is a sum of dot products of the ends' points and axes, so its gradient is
  // g_i = X_i [J_1; J_2], J_s end s's stacked Jacobian [J_p; J_e0; J_e1; J_e2] ([12, nb_s]) and
  // X_i the other factors of its dot terms. With the tangent's weights below summed the same
  // way, a pair of ends costs one product per matrix, in place of a small product for each dot
  // term and an outer product for each measure: those were most of what the bushings cost where
  // their ends span a flexible body's coordinates.
  const auto row = [](int side, int k) { return 12 * side + 3 * (k + 1); };
  Eigen::Matrix<double, 6, 24> X = Eigen::Matrix<double, 6, 24>::Zero();
  Vector6d s = Vector6d::Zero(), sd = Vector6d::Zero();
  for (int i = 0; i < 6; ++i)
    for (const DotTerm& t : kTerms[i]) {
      const Vector3d& xa = value(*md[t.ma], t.ka);
      const Vector3d& xb = value(*md[t.mb], t.kb);
      s(i) += t.coef * xa.dot(xb);
      sd(i) += t.coef * (rate(*md[t.ma], t.ka).dot(xb) + xa.dot(rate(*md[t.mb], t.kb)));
      X.block<1, 3>(i, row(t.ma, t.ka)) += t.coef * xb.transpose();
      X.block<1, 3>(i, row(t.mb, t.kb)) += t.coef * xa.transpose();
    }
  auto g = data.fg.leftCols(ntot);
  for (int side = 0; side < 2; ++side) {
    if (!nb[side]) continue;
    auto J = data.bJ[side].leftCols(nb[side]);
    J.topRows<3>() = md[side]->Jp;
    for (int k = 0; k < 3; ++k) J.middleRows<3>(3 + 3 * k) = md[side]->Je[k];
    g.middleCols(col0[side], nb[side]).noalias() = X.middleCols<12>(12 * side).lazyProduct(J);
  }
  Vector6d F, slope;
  elastic(bu, s - bu.s0, F, slope);
  F += bu.c.cwiseProduct(sd);
  for (int side = 0; side < 2 && add_q; ++side)
    if (nb[side])
      data.Q.segment(offset(model, body[side]), nb[side]).noalias() -= g.middleCols(col0[side], nb[side]).transpose() * F;
  // Each end's own part, from its own columns of g (also when both ends are on one body).
  if (ends) {
    ends->setZero();
    for (int side = 0; side < 2; ++side)
      if (nb[side]) ends->col(side).noalias() = -(g.middleCols(col0[side], 12).transpose() * F);
  }
  if (!tangents) return;

  // K = sum_i k_i g_i^T g_i + c_i g_i^T (H_i z)^T + F_i H_i,  C = sum_i c_i g_i^T g_i, as
  //   K = g^T P + J^T W J + (the ends' node terms of F_i H_i),  C = g^T diag(c) g,
  // with P = diag(k) g + diag(c) (H z)^T ([6, ntot]; H_i z = Y_i J + the node terms, Y_i weighing
  // J's rows by the other factor's J z) and W = sum_i F_i W_i = Omega (x) I3 (Omega 8 x 8: the
  // weight of each pair of quantities a dot term joins). The rank-six parts cost 6 ntot^2 each;
  // only F_i H_i needs J.
  Eigen::Matrix<double, 24, 1> Jz = Eigen::Matrix<double, 24, 1>::Zero();
  for (int side = 0; side < 2; ++side)
    if (nb[side])
      Jz.segment<12>(12 * side).noalias() =
          data.bJ[side].leftCols(nb[side]) * data.state.qd.segment(offset(model, body[side]), nb[side]);
  Eigen::Matrix<double, 8, 8> Omega = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 3, 8> node_f = Eigen::Matrix<double, 3, 8>::Zero();  // column: end 4 s + quantity (point, e0..e2)
  Eigen::Matrix<double, 6, 24> Y = Eigen::Matrix<double, 6, 24>::Zero();
  auto P = data.bP.leftCols(ntot);
  P.setZero();
  for (int i = 0; i < 6; ++i) {
    if (slope(i) == 0 && bu.c(i) == 0 && F(i) == 0) continue;
    for (const DotTerm& t : kTerms[i]) {
      const int sa = t.ma, sb = t.mb, ra = row(sa, t.ka), rb = row(sb, t.kb);
      const Vector3d& xa = value(*md[sa], t.ka);
      const Vector3d& xb = value(*md[sb], t.kb);
      const double w = F(i) * t.coef;
      Omega(ra / 3, rb / 3) += w;
      Omega(rb / 3, ra / 3) += w;
      // The node terms of F_i H_i are linear in the other factor: summed per end and quantity
      // first (node_f), then one add_jt_f_derivative each below.
      node_f.col(ra / 3) += w * xb;
      node_f.col(rb / 3) += w * xa;
      if (bu.c(i) == 0) continue;
      Y.block<1, 3>(i, ra) += (bu.c(i) * t.coef) * Jz.segment<3>(rb).transpose();
      Y.block<1, 3>(i, rb) += (bu.c(i) * t.coef) * Jz.segment<3>(ra).transpose();
      for (int e = 0; e < 2; ++e) {
        const int side = e == 0 ? sa : sb, k = e == 0 ? t.ka : t.kb;
        if (on_node(model, *mm[side]))
          add_jt_f_derivative_times(slice(*mm[side], k), e == 0 ? xb : xa, bu.c(i) * t.coef,
                                    data.state.qd.segment(offset(model, body[side]), nb[side]),
                                    P.row(i).segment(col0[side], nb[side]));
      }
    }
  }
  for (int side = 0; side < 2; ++side) {
    if (!on_node(model, *mm[side])) continue;
    const int o = offset(model, body[side]);
    for (int k = -1; k < 3; ++k)
      if (const Vector3d f = node_f.col(4 * side + k + 1); !f.isZero(0))
        add_jt_f_derivative(slice(*mm[side], k), f, 1.0, data.K.block(o, o, nb[side], nb[side]));
  }
  P.noalias() += slope.asDiagonal() * g;
  for (int side = 0; side < 2; ++side)
    if (nb[side]) P.middleCols(col0[side], nb[side]).noalias() += Y.middleCols<12>(12 * side).lazyProduct(data.bJ[side].leftCols(nb[side]));
  const bool damped = !bu.c.isZero(0);
  // The products as sums of column updates over the transposed left factors (weight_rows,
  // add_weighted_product): Eigen's lazy products of a transposed column-major block formed each
  // coefficient as a dot product with a horizontal sum, and the products were most of the
  // tangent's time in models whose bushings join a flexible body (the vehicle, the washing
  // machine).
  static constexpr double kOnes[12] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  for (int a = 0; a < 2; ++a) {
    if (!nb[a]) continue;
    const double* ga = g.data() + 6 * col0[a];
    double* gt = data.bt.data();      // g_a^T             [nb_a, 6]
    double* gct = gt + 6 * nb[a];     // (diag(c) g_a)^T   [nb_a, 6]
    double* Jt = gct + 6 * nb[a];     // J_a^T             [nb_a, 12]
    weight_rows(ga, 6, 6, nb[a], kOnes, gt);
    if (damped) weight_rows(ga, 6, 6, nb[a], bu.c.data(), gct);
    weight_rows(data.bJ[a].data(), 12, 12, nb[a], kOnes, Jt);
    for (int b = 0; b < 2; ++b) {
      if (!nb[b]) continue;
      double* Kab = &data.K(offset(model, body[a]), offset(model, body[b]));
      const Eigen::Index ldk = data.K.rows();
      add_weighted_product(gt, 6, nb[a], P.data() + 6 * col0[b], 6, nb[b], Kab, ldk);
      // T = (Omega_ab (x) I3) J_b: row block u of T is sum_v Omega(u, v) times row block v of J_b.
      auto T = data.bT.leftCols(nb[b]);
      const auto Jb = data.bJ[b].leftCols(nb[b]);
      T.setZero();
      for (int u = 0; u < 4; ++u)
        for (int v = 0; v < 4; ++v)
          if (const double o = Omega(4 * a + u, 4 * b + v); o != 0) T.middleRows<3>(3 * u) += o * Jb.middleRows<3>(3 * v);
      add_weighted_product(Jt, 6, nb[a], T.data(), 12, nb[b], Kab, ldk);
      add_weighted_product(Jt + 6 * nb[a], 6, nb[a], T.data() + 6, 12, nb[b], Kab, ldk);
      if (damped)
        add_weighted_product(gct, 6, nb[a], g.data() + 6 * col0[b], 6, nb[b],
                             &data.C(offset(model, body[a]), offset(model, body[b])), data.C.rows());
    }
  }
}

}  // namespace ffr::runtime::detail
