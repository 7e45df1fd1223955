// Forces along the line of two points (line_force.hpp).
#include "line_force.hpp"

#include "force_helpers.hpp"
#include "../joints/weighted_gram.hpp"

namespace ffr::runtime::detail {

LineState line_state(const Model& model, int m1, int m2, const Data& data) {
  const MarkerData& a = data.markers[m1];
  const MarkerData& b = data.markers[m2];
  LineState st;
  st.d = b.p - a.p;
  st.dd = b.pd - a.pd;
  st.l = st.d.norm();
  st.valid = st.l > 1e-14 * model.length;
  if (!st.valid) return st;
  st.n = st.d / st.l;
  st.ldot = st.n.dot(st.dd);
  return st;
}

void add_line_force(const Model& model, int m1, int m2, const LineState& st, double T, Data& data,
                    Eigen::Matrix<double, 12, 2>* ends) {
  if (ends) ends->setZero();
  if (!st.valid) return;
  const Vector3d f2 = -T * st.n;
  const int b1 = model.markers[m1].body, b2 = model.markers[m2].body;
  if (ends && b1 != kGround) ends->col(0).noalias() = -(data.markers[m1].Jp.leftCols<12>().transpose() * f2);
  if (ends && b2 != kGround) ends->col(1).noalias() = data.markers[m2].Jp.leftCols<12>().transpose() * f2;
  if (b1 != kGround) data.Q.segment(offset(model, b1), ncoord(model, b1)).noalias() -= data.markers[m1].Jp.transpose() * f2;
  if (b2 != kGround) data.Q.segment(offset(model, b2), ncoord(model, b2)).noalias() += data.markers[m2].Jp.transpose() * f2;
}

void add_line_tangents(const Model& model, int m1, int m2, const LineState& st, double T, double kl, double cl,
                       Data& data) {
  if (!st.valid) return;
  const Matrix3d P = Matrix3d::Identity() - st.n * st.n.transpose();
  // f2 = -T(d, d_dot) n(d): its derivatives with respect to d and d_dot.
  const Matrix3d Dd = -(kl * st.n * st.n.transpose() + cl * st.n * (P * st.dd).transpose() / st.l + T * P / st.l);
  const Matrix3d Dv = -cl * st.n * st.n.transpose();
  const Vector3d f2 = -T * st.n;
  const int mk[2] = {m1, m2};
  const double sign[2] = {-1.0, 1.0};  // d = p2 - p1 and f_i = sign_i f2
  // -sign_i Jp_i^T of each end, once (lt: [nb_i, 3] per end): the products below are column
  // updates over it (weighted_gram.hpp); Eigen's product of a transposed 3-row matrix packed both
  // operands first, and that was a tenth of the washing machine's step.
  const int nb_max = static_cast<int>(data.lt.size() / 6);
  for (int i = 0; i < 2; ++i) {
    const Marker& mi = model.markers[mk[i]];
    if (mi.body == kGround) continue;
    const double w[3] = {-sign[i], -sign[i], -sign[i]};
    weight_rows(data.markers[mk[i]].Jp.data(), 3, 3, ncoord(model, mi.body), w, data.lt.data() + 3 * nb_max * i);
  }
  for (int j = 0; j < 2; ++j) {
    const Marker& mj = model.markers[mk[j]];
    if (mj.body == kGround) continue;
    const int nbj = ncoord(model, mj.body), oj = offset(model, mj.body);
    const MarkerData& dj = data.markers[mk[j]];
    // G = dd/dz_j, V = d(d_dot)/dz_j through J_j(z_j), then DD = Dd G + Dv V.
    auto V = data.w3[0].leftCols(nbj);
    jzd_derivative(mj.phi, data.bodies[mj.body].Ad, data.state.qd.segment(oj + 12, nbj - 12), V);
    auto DD = data.w3[1].leftCols(nbj);
    DD.noalias() = sign[j] * Dd * dj.Jp;
    DD.noalias() += sign[j] * Dv * V;
    auto DC = data.w3[2].leftCols(nbj);
    DC.noalias() = sign[j] * Dv * dj.Jp;
    for (int i = 0; i < 2; ++i) {
      const Marker& mi = model.markers[mk[i]];
      if (mi.body == kGround) continue;
      const int nbi = ncoord(model, mi.body), oi = offset(model, mi.body);
      const double* lt = data.lt.data() + 3 * nb_max * i;  // K_ij -= sign_i Jp_i^T DD, C_ij likewise with DC
      add_weighted_product(lt, 3, nbi, DD.data(), 3, nbj, &data.K(oi, oj), data.K.rows());
      add_weighted_product(lt, 3, nbi, DC.data(), 3, nbj, &data.C(oi, oj), data.C.rows());
    }
    add_jt_f_derivative(mj.phi, sign[j] * f2, -1.0, data.K.block(oj, oj, nbj, nbj));
  }
}

}  // namespace ffr::runtime::detail
