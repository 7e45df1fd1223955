// Joint reactions and force-element forces (MODEL_FILE.md "Outputs", FORMULATION.md 13).
//
// A constraint row Phi_i with multiplier lambda_i acts on the bodies with the generalized force
// -lambda_i dPhi_i/dq (M q_dd = Q - Phi_q^T lambda). The reaction on body2 is that force
// expressed as a force and torque: the row's variation under a virtual rigid motion of marker
// 2 (translation dx, rotation dth about its point p2) is dPhi_i = g_F . dx + g_T . dth, and the
// wrench is (F, T) = -sum_i lambda_i (g_F, g_T). Each row is a dot product of marker quantities:
// a term x . y with y marker 2's point gives g_F += x; with y an axis e of marker 2 (dy = dth x e)
// g_T += e x x. Computed from the markers alone, it needs no Jacobian columns, so a joint to the
// ground or to a driven body has its reaction as well (once its rows are among the unknowns',
// see find_drives in model.cpp).
#include "ffr/runtime/outputs.hpp"

#include "../forces/forces.hpp"

#include <cmath>

namespace ffr::runtime {
namespace {

struct Wrench {
  Vector3d F = Vector3d::Zero(), T = Vector3d::Zero();
};

// Row `row` of the joint (0-based, as in constraints.cpp's joint_rows) with multiplier lam.
void joint_row_wrench(const Model& model, const Joint& j, const MarkerData& a, const MarkerData& b, int row, double lam,
                      Wrench& w) {
  const double L = model.length;
  // Rotation rows: L (e1_k . e2_l): g_T = L e2_l x e1_k.
  auto turn = [&](int k, int l) { w.T -= lam * L * b.e[l].cross(a.e[k]); };
  switch (j.type) {
    case JointType::Spherical:
    case JointType::Revolute:
    case JointType::Universal:
    case JointType::Fixed:
      if (row < 3) {  // p2 - p1
        w.F(row) -= lam;
        return;
      }
      if (j.type == JointType::Revolute) turn(0, row == 3 ? 1 : 2);
      if (j.type == JointType::Universal) turn(0, 0);
      if (j.type == JointType::Fixed) {
        if (row == 3) turn(0, 1);
        if (row == 4) turn(0, 2);
        if (row == 5) turn(1, 2);
      }
      return;
    case JointType::Cylindrical:
    case JointType::Prismatic:
      // (p2 - p1) . f1, (p2 - p1) . g1, then L e1 . f2, L e1 . g2 and (prismatic) L f1 . g2.
      if (row == 0) w.F -= lam * a.e[1];
      if (row == 1) w.F -= lam * a.e[2];
      if (row == 2) turn(0, 1);
      if (row == 3) turn(0, 2);
      if (row == 4) turn(1, 2);
      return;
  }
}

// A motion's row on joint j: scale (coordinate - target), the scale L for an angle.
void motion_row_wrench(const Model& model, const Motion& mo, const MarkerData& a, const MarkerData& b, double lam,
                       Wrench& w) {
  if (mo.coordinate == JointCoordinate::Displacement) {  // (p2 - p1) . e1
    w.F -= lam * a.e[0];
    return;
  }
  // theta = atan2(g1 . f2, f1 . f2): d theta = (x dy - y dx) / rho^2 with dx = dth . (f2 x f1),
  // dy = dth . (f2 x g1).
  const double x = a.e[1].dot(b.e[1]), y = a.e[2].dot(b.e[1]);
  const double rho2 = x * x + y * y;
  const Vector3d g = (x * b.e[1].cross(a.e[2]) - y * b.e[1].cross(a.e[1])) / rho2;
  w.T -= lam * model.length * g;
}

}  // namespace

Vector6d joint_reaction(const Model& model, const Data& data, int joint) {
  const Joint& j = model.joints[static_cast<std::size_t>(joint)];
  const MarkerData& a = data.markers[static_cast<std::size_t>(j.m1)];
  const MarkerData& b = data.markers[static_cast<std::size_t>(j.m2)];
  Wrench w;
  for (const ConstraintBlock& blk : model.blocks) {
    if (blk.kind == BlockKind::Joint && blk.index == joint) {
      for (int r = 0; r < blk.rows; ++r) joint_row_wrench(model, j, a, b, blk.first + r, data.reaction_lambda(blk.row0 + r), w);
    } else if (blk.kind == BlockKind::Motion && model.motions[static_cast<std::size_t>(blk.index)].joint == joint) {
      motion_row_wrench(model, model.motions[static_cast<std::size_t>(blk.index)], a, b, data.reaction_lambda(blk.row0), w);
    }
  }
  // A beam node as body2 (FORMULATION.md 15): its rows read the slope's turn theta = t0 x (r_x - t0),
  // which a rigid rotation dth of the node changes by |r_x| (dth less its part along the slope)
  // where the joint holds theta = 0 (a clamp): the torque is that of the rigid-marker rows
  // projected off the slope and scaled by its length. (No torque acts about the slope: the node
  // has no torsion.)
  const Marker& mk2 = model.markers[static_cast<std::size_t>(j.m2)];
  if (mk2.body != kGround && model.bodies[static_cast<std::size_t>(mk2.body)].beam && mk2.node >= 0) {
    const Body& beam = model.bodies[static_cast<std::size_t>(mk2.body)];
    const int k = beam_node_index(*beam.beam, mk2.node);
    const Vector3d rx = beam.beam->q0.segment<3>(6 * k + 3) + data.state.q.segment<3>(beam.offset + 12 + 6 * k + 3);
    const double len = rx.norm();
    const Vector3d t = rx / len;
    w.T = len * (w.T - t.dot(w.T) * t);
  }
  Vector6d out;
  out << w.F, w.T;
  return out;
}

void element_force(const Model& model, const Data& data, ForceElementKind kind, int index, double* out) {
  const auto e = static_cast<std::size_t>(index);
  // The laws are the force elements' own (forces.hpp): tables, preloads and friction included.
  if (kind == ForceElementKind::SpringDamper) {
    out[0] = detail::spring_force(model, model.springs[e], data);  // tension, zero where the ends meet
    return;
  }
  if (kind == ForceElementKind::Tire) {
    detail::tire_output(model, model.tires[e], data, out);
    return;
  }
  if (kind == ForceElementKind::FrictionDamper) {
    out[0] = detail::friction_force(model, model.friction_dampers[e], data.state.friction[e], data);
    return;
  }
  // A bushing's measures s_i (bushing.cpp) with forces F_i (detail::bushing_force) act on
  // body2 as -sum_i F_i ds_i/d(dx, dth) (marker 2's virtual rigid motion about its point):
  //   s_k = E1_k . (p2 - p1)                  g_F = E1_k
  //   theta_x = (g1.f2 - f1.g2)/2, ...        g_T = (f2 x g1 - g2 x f1)/2, ...
  const Bushing& bu = model.bushings[e];
  const MarkerData& a = data.markers[static_cast<std::size_t>(bu.m1)];
  const MarkerData& b = data.markers[static_cast<std::size_t>(bu.m2)];
  Vector3d gT[3];
  const int cyc[3][2] = {{2, 1}, {0, 2}, {1, 0}};  // theta_i = (E1_p . E2_r - E1_r . E2_p) / 2, (p, r) = cyc[i]
  for (int k = 0; k < 3; ++k) {
    const int p = cyc[k][0], r = cyc[k][1];
    gT[k] = 0.5 * (b.e[r].cross(a.e[p]) - b.e[p].cross(a.e[r]));
  }
  const Vector6d F = detail::bushing_force(model, bu, data);
  Vector3d force = Vector3d::Zero(), torque = Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    force -= F(k) * a.e[k];
    torque -= F(3 + k) * gT[k];
  }
  for (int i = 0; i < 3; ++i) {
    out[i] = force(i);
    out[3 + i] = torque(i);
  }
}

}  // namespace ffr::runtime
