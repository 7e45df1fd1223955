// Point forces and torques (tables and external inputs).
//
// A force f at a marker point does virtual work f . dp, so Q = J_p^T f. A torque tau on a body
// does tau . dtheta with dtheta = 1/2 sum_a A_a x dA_a (exact on the constraint manifold), so
// Q_Aa = 1/2 tau x A_a; at a node the elastic rotation A psi dy adds Q_y = psi^T A^T tau.
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "force_helpers.hpp"
#include "forces.hpp"

namespace ffr::runtime::detail {
namespace {

Matrix3d skew(const Vector3d& v) {
  Matrix3d S;
  S << 0, -v(2), v(1), v(2), 0, -v(0), -v(1), v(0), 0;
  return S;
}

}  // namespace

void marker_load(const Model& model, const Marker& mk, const MarkerData& md, const Vector3d& f, bool torque,
                 Data& data, bool add_q, bool tangents) {
  if (mk.body == kGround) return;
  const Body& b = model.bodies[mk.body];
  const BodyData& bd = data.bodies[mk.body];
  const int o = b.offset, nb = b.ncoord();
  const bool node = on_node(model, mk);
  if (!torque) {
    if (add_q) data.Q.segment(o, nb).noalias() += md.Jp.transpose() * f;
    if (tangents && node) add_jt_f_derivative(mk.phi, f, -1.0, data.K.block(o, o, nb, nb));
    return;
  }
  if (add_q) {
    for (int a = 0; a < 3; ++a) data.Q.segment<3>(o + 3 + 3 * a) += 0.5 * f.cross(bd.A.col(a));
  }
  if (add_q && node) data.Q.segment(o + 12, b.nq).noalias() += mk.psi.transpose() * (bd.A.transpose() * f);
  if (!tangents) return;
  const Matrix3d S = skew(f);
  for (int a = 0; a < 3; ++a) {
    data.K.block<3, 3>(o + 3 + 3 * a, o + 3 + 3 * a) -= 0.5 * S;
    if (node) data.K.block(o + 12, o + 3 + 3 * a, b.nq, 3).noalias() -= mk.psi.row(a).transpose() * f.transpose();
  }
}

void point_loads(const Model& model, Data& data, double t, bool add_q, bool tangents) {
  for (const PointLoad& l : model.loads) {
    Vector3d f;
    for (int c = 0; c < 3; ++c) f(c) = l.table.value(t, c);
    // The load at a stiffening interface (FORMULATION.md 7), only while forces are added.
    const InterfaceLoadCapture at(model, data, add_q ? l.marker : -1, -1);
    marker_load(model, model.markers[l.marker], data.markers[l.marker], f, l.torque, data, add_q, tangents);
    if (add_q) at.add_to_interfaces(model, data);
  }
}

void external_loads(const Model& model, Data& data, bool add_q, bool tangents) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    for (const int s : data.ext_list[b]) {
      const Marker& mk = model.load_slots[b][static_cast<std::size_t>(s)];
      MarkerData& md = data.ext_marker[b];
      marker_kinematics(model, mk, data, md);
      const Vector3d f = data.ext_force[b].col(static_cast<Eigen::Index>(s));
      const Vector3d tau = data.ext_torque[b].col(static_cast<Eigen::Index>(s));
      const InterfaceLoadCapture at(model, data, add_q ? &mk : nullptr, nullptr);
      if (!f.isZero(0)) marker_load(model, mk, md, f, false, data, add_q, tangents);
      if (!tau.isZero(0)) marker_load(model, mk, md, tau, true, data, add_q, tangents);
      if (add_q) at.add_to_interfaces(model, data);
    }
  }
}

}  // namespace ffr::runtime::detail
