// The loads that joints apply at the interface nodes of flexible bodies, for the interface-load
// stiffening (SID /stiffening/interfaces, FORMULATION.md 7).
#include "ffr/runtime/dynamics.hpp"

namespace ffr::runtime {
namespace {

// The interface of the body's stiffening terms at node `node`, or -1.
int interface_at(const StiffeningTerms& s, int node) {
  for (std::size_t i = 0; i < s.interfaces.size(); ++i)
    if (s.interfaces[i].node == node) return static_cast<int>(i);
  return -1;
}

}  // namespace

// A joint's force on body i is -Phi_q^T lambda over the body's columns. Its r0 columns give the
// force F (global: a point's Jacobian has I there, an axis's none), its frame columns
// Q_A = [xbar_a F + 1/2 tau x A_a]_a, from which the moment about the origin is
// sum_a A_a x Q_A,a; about the node it is that less (A xbar_p) x F. Both are then resolved in K.
// The multipliers are the current ones and the Jacobian the last evaluated (frozen within the
// iterate, like the accelerations of the inertial load cases).
void interface_loads(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    if (!b.stiffening || b.stiffening->interfaces.empty() || !data.integrated[i]) continue;
    BodyData& bd = data.bodies[i];
    bd.iface_load.setZero();
    const int o = b.offset, body = static_cast<int>(i);
    for (const ConstraintBlock& blk : model.blocks) {
      if (blk.kind == BlockKind::RigidBody || (blk.body1 != body && blk.body2 != body)) continue;
      const Joint& jt = model.joints[static_cast<std::size_t>(blk.kind == BlockKind::Joint ? blk.index : model.motions[static_cast<std::size_t>(blk.index)].joint)];
      const Marker& m1 = model.markers[static_cast<std::size_t>(jt.m1)];
      const Marker& m2 = model.markers[static_cast<std::size_t>(jt.m2)];
      if (m1.body == body && m2.body == body) continue;  // a body jointed to itself loads nothing
      const Marker& mk = m1.body == body ? m1 : m2;
      if (mk.node < 0) continue;
      const int s = interface_at(*b.stiffening, mk.node);
      if (s < 0) continue;
      const auto lam = data.lambda.segment(blk.row0, blk.rows);
      const Vector3d F = -(data.Phiq.middleRows(blk.row0, blk.rows).middleCols<3>(o).transpose() * lam);
      const Eigen::Matrix<double, 9, 1> QA = -(data.Phiq.middleRows(blk.row0, blk.rows).middleCols<9>(o + 3).transpose() * lam);
      Vector3d M = Vector3d::Zero();
      for (int a = 0; a < 3; ++a) M += Vector3d(bd.A.col(a)).cross(Vector3d(QA.segment<3>(3 * a)));
      const NodeSlice& n = b.nodes[static_cast<std::size_t>(mk.node)];
      Vector3d xbar = n.origin;
      xbar.noalias() += n.phi * data.q.segment(o + 12, b.nq);
      M -= (bd.A * xbar).cross(F);
      bd.iface_load.col(s).head<3>() += bd.A.transpose() * F;
      bd.iface_load.col(s).tail<3>() += bd.A.transpose() * M;
    }
  }
}

}  // namespace ffr::runtime
