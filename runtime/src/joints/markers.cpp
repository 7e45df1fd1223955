// Marker kinematics: a point p = r0 + A (c + phi y) and axes e_k = A (E_k + phiE_k y), with
// Jacobians J = [I, xbar_0 I, xbar_1 I, xbar_2 I, A phi] (no I block for an axis) and the
// acceleration bias J_dot z_dot = 2 A_dot phi y_dot (FORMULATION.md section 5).
#include "ffr/runtime/kinematics.hpp"

#include "../bodies/plate_triad.hpp"

namespace ffr::runtime {
namespace {

// S y for a 3 x n slice (a mode slice, a marker's Jacobian), column by column in fixed-size
// arithmetic: a dynamic-size Eigen product of this shape costs a call and its set-up, more than
// its 3n multiply-adds, and the markers make dozens of them per evaluation.
inline Vector3d slice_times(const Matrix3Xd& S, const double* y) {
  Vector3d v = Vector3d::Zero();
  for (Eigen::Index k = 0; k < S.cols(); ++k) v += S.col(k) * y[k];
  return v;
}

// Fills J = [I?, x0 I, x1 I, x2 I, A S] for a local vector x with mode slice S.
void local_jacobian(const Matrix3d& A, const Vector3d& x, const Matrix3Xd* S, bool point, Matrix3N& J) {
  J.leftCols<12>().setZero();
  if (point) J.block<3, 3>(0, 0).setIdentity();
  for (int a = 0; a < 3; ++a) J.block<3, 3>(0, 3 + 3 * a).diagonal().setConstant(x(a));
  if (J.cols() > 12) {
    if (S)
      for (Eigen::Index k = 0; k < S->cols(); ++k) J.col(12 + k).noalias() = A * S->col(k);
    else
      J.rightCols(J.cols() - 12).setZero();
  }
}

// A plate node's exact triad (Marker::triad): the Gram-Schmidt frame of its gradients.
detail::PlateTriad node_triad(const Marker& mk, const double* y) {
  detail::PlateTriad T;
  detail::plate_triad(mk.triad_x0 + Eigen::Map<const Vector3d>(y + mk.triad), mk.triad_y0 + Eigen::Map<const Vector3d>(y + mk.triad + 3),
                      T);
  return T;
}

}  // namespace

void marker_kinematics(const Model& model, const Marker& mk, const Data& data, MarkerData& md) {
  if (mk.body == kGround) {
    md.p = mk.c;
    md.pd.setZero();
    md.pb.setZero();
    for (int k = 0; k < 3; ++k) {
      md.e[k] = mk.E.col(k);
      md.ed[k].setZero();
      md.eb[k].setZero();
    }
    return;
  }
  const Body& b = model.bodies[mk.body];
  const BodyData& bd = data.bodies[mk.body];
  const int o = b.offset;
  const bool on_node = mk.node >= 0 && b.nq > 0;
  md.xbar = mk.c;
  const double* y = data.state.q.data() + o + 12;
  if (on_node) md.xbar += slice_times(mk.phi, y);
  md.p = data.state.q.segment<3>(o);
  md.p.noalias() += bd.A * md.xbar;
  local_jacobian(bd.A, md.xbar, on_node ? &mk.phi : nullptr, true, md.Jp);
  if (on_node && mk.triad >= 0) {
    // ebar_k = T R_k, exact at any rotation; its columns in y are A dT R_k / d(r_x, r_y).
    const detail::PlateTriad T = node_triad(mk, y);
    for (int k = 0; k < 3; ++k) {
      if (!mk.axes[k]) continue;
      detail::Matrix36 G;
      md.ebar[k] = detail::triad_axis(T, mk.triad_R.col(k), &G);
      md.e[k].noalias() = bd.A * md.ebar[k];
      local_jacobian(bd.A, md.ebar[k], nullptr, false, md.Je[k]);
      md.Je[k].block<3, 6>(0, 12 + mk.triad).noalias() = bd.A * G;
    }
    marker_rates(model, mk, data, md);
    return;
  }
  for (int k = 0; k < 3; ++k) {
    if (!mk.axes[k]) continue;  // nothing reads it (Marker::axes)
    md.ebar[k] = mk.E.col(k);
    if (on_node) md.ebar[k] += slice_times(mk.phiE[k], y);
    md.e[k].noalias() = bd.A * md.ebar[k];
    local_jacobian(bd.A, md.ebar[k], on_node ? &mk.phiE[k] : nullptr, false, md.Je[k]);
  }
  marker_rates(model, mk, data, md);
}

void marker_rates(const Model& model, const Marker& mk, const Data& data, MarkerData& md) {
  if (mk.body == kGround) return;  // at rest; set by marker_kinematics
  const Body& b = model.bodies[mk.body];
  const BodyData& bd = data.bodies[mk.body];
  const int o = b.offset;
  const bool on_node = mk.node >= 0 && b.nq > 0;
  md.pd = data.state.qd.segment<3>(o);
  md.pd.noalias() += bd.Ad * md.xbar;
  md.pb.setZero();
  const double* yd = data.state.qd.data() + o + 12;
  if (on_node) {
    const Vector3d py = slice_times(mk.phi, yd);
    md.pd.noalias() += bd.A * py;
    md.pb.noalias() = 2.0 * bd.Ad * py;
  }
  if (on_node && mk.triad >= 0) {
    // e_dd = A_dd ebar + 2 A_d G y_d + A (G y_dd + D2ebar[y_d, y_d]): the bias is all but the
    // frame's and y's accelerations.
    const detail::PlateTriad T = node_triad(mk, data.state.q.data() + o + 12);
    const detail::Vector6 z = Eigen::Map<const detail::Vector6>(yd + mk.triad);
    for (int k = 0; k < 3; ++k) {
      if (!mk.axes[k]) continue;
      detail::Matrix36 G;
      detail::triad_axis(T, mk.triad_R.col(k), &G);
      const Vector3d Gz = G * z;
      md.ed[k].noalias() = bd.Ad * md.ebar[k];
      md.ed[k].noalias() += bd.A * Gz;
      md.eb[k].noalias() = 2.0 * bd.Ad * Gz;
      md.eb[k].noalias() += bd.A * detail::triad_axis_second(T, mk.triad_R.col(k), z);
    }
  }
  const bool triad = on_node && mk.triad >= 0;
  for (int k = 0; k < 3; ++k) {
    if (!mk.axes[k] || triad) continue;  // (a triad's axes are done above)
    md.ed[k].noalias() = bd.Ad * md.ebar[k];
    if (on_node) {
      const Vector3d py = slice_times(mk.phiE[k], yd);
      md.ed[k].noalias() += bd.A * py;
      md.eb[k].noalias() = 2.0 * bd.Ad * py;
    } else {
      md.eb[k].setZero();
    }
  }
  // A driven body's accelerations are given (drive_bodies), not unknowns: its markers' biases
  // are then their whole accelerations, J z_ddot + J_dot z_dot, which the constraints' gamma
  // takes as it takes the ground's zeros.
  if (!integrated(data, mk.body)) {
    const double* zdd = data.state.qdd.data() + o;
    md.pb += slice_times(md.Jp, zdd);
    for (int k = 0; k < 3; ++k)
      if (mk.axes[k]) md.eb[k] += slice_times(md.Je[k], zdd);
  }
}

void update_markers(const Model& model, Data& data, Scope scope) {
  for (std::size_t i = 0; i < model.markers.size(); ++i)
    if (scope == Scope::All || integrated(data, model.markers[i].body))
      marker_kinematics(model, model.markers[i], data, data.markers[i]);
}

void update_marker_rates(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.markers.size(); ++i) marker_rates(model, model.markers[i], data, data.markers[i]);
}

Vector3d initial_marker_position(const Model& model, const Marker& mk) {
  if (mk.body == kGround) return mk.c;
  const Body& b = model.bodies[mk.body];
  Vector3d x = mk.c;
  if (mk.node >= 0 && b.nq > 0) x += mk.phi * b.y0;
  return b.r0 + b.A0 * x;
}

Vector3d initial_marker_axis(const Model& model, const Marker& mk, int k) {
  if (mk.body == kGround) return mk.E.col(k);
  const Body& b = model.bodies[mk.body];
  Vector3d x = mk.E.col(k);
  if (mk.node >= 0 && b.nq > 0 && mk.triad >= 0)
    x = detail::triad_axis(node_triad(mk, b.y0.data()), mk.triad_R.col(k));
  else if (mk.node >= 0 && b.nq > 0)
    x += mk.phiE[k] * b.y0;
  return b.A0 * x;
}

}  // namespace ffr::runtime
