// Linear spring-damper between two marker points: tension F = k (l - l0) + c l_dot along the
// line of the points; force +F n on point 1 and -F n on point 2 (n from 1 to 2).
#include "forces.hpp"
#include "force_helpers.hpp"

#include <cmath>

namespace ffr::runtime::detail {
namespace {

struct SpringState {
  Vector3d d, dd, n;
  double l = 0, ldot = 0, F = 0;
  bool valid = false;
};

SpringState spring_state(const Model& model, const SpringDamper& s, const Data& data) {
  const MarkerData& a = data.markers[s.m1];
  const MarkerData& b = data.markers[s.m2];
  SpringState st;
  st.d = b.p - a.p;
  st.dd = b.pd - a.pd;
  st.l = st.d.norm();
  // A spring squeezed to a point has no direction: it exerts nothing there (and the model
  // loader refuses springs whose ends coincide initially unless length0 = 0).
  st.valid = st.l > 1e-14 * model.length;
  if (!st.valid) return st;
  st.n = st.d / st.l;
  st.ldot = st.n.dot(st.dd);
  st.F = s.k * (st.l - s.length0) + s.c * st.ldot;
  return st;
}

}  // namespace

void spring_forces(const Model& model, const SpringDamper& s, Data& data) {
  const SpringState st = spring_state(model, s, data);
  if (!st.valid) return;
  const Vector3d f2 = -st.F * st.n;
  const int b1 = model.markers[s.m1].body, b2 = model.markers[s.m2].body;
  if (b1 != kGround) data.Q.segment(offset(model, b1), ncoord(model, b1)).noalias() -= data.markers[s.m1].Jp.transpose() * f2;
  if (b2 != kGround) data.Q.segment(offset(model, b2), ncoord(model, b2)).noalias() += data.markers[s.m2].Jp.transpose() * f2;
}

double spring_energy(const Model& model, const SpringDamper& s, const Data& data) {
  const SpringState st = spring_state(model, s, data);
  return st.valid ? 0.5 * s.k * (st.l - s.length0) * (st.l - s.length0) : 0.5 * s.k * s.length0 * s.length0;
}

void spring_tangents(const Model& model, const SpringDamper& s, Data& data) {
  const SpringState st = spring_state(model, s, data);
  if (!st.valid) return;
  const Matrix3d P = Matrix3d::Identity() - st.n * st.n.transpose();
  // f2 = -F(d, d_dot) n(d): its derivatives with respect to d and d_dot.
  const Matrix3d Dd = -(s.k * st.n * st.n.transpose() + s.c * st.n * (P * st.dd).transpose() / st.l + st.F * P / st.l);
  const Matrix3d Dv = -s.c * st.n * st.n.transpose();
  const Vector3d f2 = -st.F * st.n;
  const int mk[2] = {s.m1, s.m2};
  const double sign[2] = {-1.0, 1.0};  // d = p2 - p1 and f_i = sign_i f2
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
      const MarkerData& di = data.markers[mk[i]];
      data.K.block(oi, oj, nbi, nbj).noalias() -= sign[i] * di.Jp.transpose() * DD;
      data.C.block(oi, oj, nbi, nbj).noalias() -= sign[i] * di.Jp.transpose() * DC;
    }
    add_jt_f_derivative(mj.phi, sign[j] * f2, -1.0, data.K.block(oj, oj, nbj, nbj));
  }
}

}  // namespace ffr::runtime::detail
