// Marker kinematics: a point p = r0 + A (c + phi y) and axes e_k = A (E_k + phiE_k y), with
// Jacobians J = [I, xbar_0 I, xbar_1 I, xbar_2 I, A phi] (no I block for an axis) and the
// acceleration bias J_dot z_dot = 2 A_dot phi y_dot (FORMULATION.md section 5).
#include "ffr/runtime/kinematics.hpp"

namespace ffr::runtime {
namespace {

// Fills J = [I?, x0 I, x1 I, x2 I, A S] for a local vector x with mode slice S.
void local_jacobian(const Matrix3d& A, const Vector3d& x, const Matrix3Xd* S, bool point, Matrix3N& J) {
  J.leftCols<12>().setZero();
  if (point) J.block<3, 3>(0, 0).setIdentity();
  for (int a = 0; a < 3; ++a) J.block<3, 3>(0, 3 + 3 * a).diagonal().setConstant(x(a));
  if (J.cols() > 12) {
    if (S)
      J.rightCols(J.cols() - 12).noalias() = A * (*S);
    else
      J.rightCols(J.cols() - 12).setZero();
  }
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
  if (on_node) md.xbar.noalias() += mk.phi * data.q.segment(o + 12, b.nq);
  md.p = data.q.segment<3>(o);
  md.p.noalias() += bd.A * md.xbar;
  local_jacobian(bd.A, md.xbar, on_node ? &mk.phi : nullptr, true, md.Jp);
  for (int k = 0; k < 3; ++k) {
    md.ebar[k] = mk.E.col(k);
    if (on_node) md.ebar[k].noalias() += mk.phiE[k] * data.q.segment(o + 12, b.nq);
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
  md.pd = data.qd.segment<3>(o);
  md.pd.noalias() += bd.Ad * md.xbar;
  md.pb.setZero();
  if (on_node) {
    const auto yd = data.qd.segment(o + 12, b.nq);
    const Vector3d py = mk.phi * yd;
    md.pd.noalias() += bd.A * py;
    md.pb.noalias() = 2.0 * bd.Ad * py;
  }
  for (int k = 0; k < 3; ++k) {
    md.ed[k].noalias() = bd.Ad * md.ebar[k];
    if (on_node) {
      const Vector3d py = mk.phiE[k] * data.qd.segment(o + 12, b.nq);
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
    const auto zdd = data.qdd.segment(o, b.ncoord());
    md.pb.noalias() += md.Jp * zdd;
    for (int k = 0; k < 3; ++k) md.eb[k].noalias() += md.Je[k] * zdd;
  }
}

void update_markers(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.markers.size(); ++i)
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
  if (mk.node >= 0 && b.nq > 0) x += mk.phiE[k] * b.y0;
  return b.A0 * x;
}

}  // namespace ffr::runtime
