// The loads that joints and force elements apply at the interface nodes of flexible bodies, for
// the interface-load stiffening (SID /stiffening/interfaces, FORMULATION.md 7).
#include "ffr/runtime/dynamics.hpp"

namespace ffr::runtime {
namespace {

// The interface of the body's stiffening terms at node `node`, or -1.
int interface_at(const StiffeningTerms& s, int node) {
  for (std::size_t i = 0; i < s.interfaces.size(); ++i)
    if (s.interfaces[i].node == node) return static_cast<int>(i);
  return -1;
}

// Adds to interface `slot` of body i the load whose generalized force over the body's frame
// columns is QF (r0) and QA (the nine columns of A): the force F = QF (global: a point's Jacobian
// has I there), the moment about the origin sum_a A_a x QA_a, about the node that less
// (A xbar_p) x F; both resolved in K.
void add_node_load(const Body& b, BodyData& bd, const Data& data, int slot, int node, const Vector3d& F,
                   const Eigen::Ref<const Eigen::Matrix<double, 9, 1>>& QA) {
  Vector3d M = Vector3d::Zero();
  for (int a = 0; a < 3; ++a) M += Vector3d(bd.A.col(a)).cross(Vector3d(QA.segment<3>(3 * a)));
  const NodeSlice& n = b.nodes[static_cast<std::size_t>(node)];
  Vector3d xbar = n.origin;
  xbar.noalias() += n.phi * data.state.q.segment(b.offset + 12, b.nq);
  M -= (bd.A * xbar).cross(F);
  bd.iface_load.col(slot).head<3>() += bd.A.transpose() * F;
  bd.iface_load.col(slot).tail<3>() += bd.A.transpose() * M;
}

// The stiffening interface that marker `m` sits on (body integrated, stiffened), or slot -1.
struct InterfaceSite {
  int body = -1, node = -1, slot = -1;
};

InterfaceSite site_of(const Model& model, const Data& data, const Marker* marker) {
  InterfaceSite s;
  if (!marker) return s;
  const Marker& mk = *marker;
  if (mk.body == kGround || mk.node < 0 || !data.integrated[static_cast<std::size_t>(mk.body)]) return s;
  const Body& b = model.bodies[static_cast<std::size_t>(mk.body)];
  if (!b.stiffening || b.stiffening->interfaces.empty()) return s;
  s.slot = interface_at(*b.stiffening, mk.node);
  if (s.slot >= 0) {
    s.body = mk.body;
    s.node = mk.node;
  }
  return s;
}

}  // namespace

// A joint's force on body i is -Phi_q^T lambda over the body's columns. The multipliers are the
// current ones and the Jacobian the last evaluated (frozen within the iterate, like the
// accelerations of the inertial load cases).
void interface_loads(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    if (!b.stiffening || b.stiffening->interfaces.empty() || !data.integrated[i]) continue;
    BodyData& bd = data.bodies[i];
    bd.iface_load.setZero();
    const int o = b.offset, body = static_cast<int>(i);
    for (const ConstraintBlock& blk : model.blocks) {
      if (blk.kind == BlockKind::RigidBody || (blk.body1 != body && blk.body2 != body)) continue;
      if (blk.kind == BlockKind::Coupler) continue;  // not an interface load (FORMULATION.md 12)
      const Joint& jt = model.joints[static_cast<std::size_t>(blk.kind == BlockKind::Joint ? blk.index : model.motions[static_cast<std::size_t>(blk.index)].joint)];
      const Marker& m1 = model.markers[static_cast<std::size_t>(jt.m1)];
      const Marker& m2 = model.markers[static_cast<std::size_t>(jt.m2)];
      if (m1.body == body && m2.body == body) continue;  // a body jointed to itself loads nothing
      const Marker& mk = m1.body == body ? m1 : m2;
      if (mk.node < 0) continue;
      const int s = interface_at(*b.stiffening, mk.node);
      if (s < 0) continue;
      const auto lam = data.state.lambda.segment(blk.row0, blk.rows);
      const Vector3d F = -(data.Phiq.middleRows(blk.row0, blk.rows).middleCols<3>(o).transpose() * lam);
      const Eigen::Matrix<double, 9, 1> QA = -(data.Phiq.middleRows(blk.row0, blk.rows).middleCols<9>(o + 3).transpose() * lam);
      add_node_load(b, bd, data, s, mk.node, F, QA);
    }
  }
}

InterfaceLoadCapture::InterfaceLoadCapture(const Model& model, const Data& data, int m1, int m2)
    : InterfaceLoadCapture(model, data, m1 >= 0 ? &model.markers[static_cast<std::size_t>(m1)] : nullptr,
                           m2 >= 0 ? &model.markers[static_cast<std::size_t>(m2)] : nullptr) {}

InterfaceLoadCapture::InterfaceLoadCapture(const Model& model, const Data& data, const Marker* m1, const Marker* m2) {
  // An element between two points of one body: its frame columns hold the sum of both ends'
  // loads, which cannot be told apart there; it is left out (FORMULATION.md 12).
  if (m1 && m2 && m1->body == m2->body) return;
  int n = 0;
  for (const InterfaceSite& s : {site_of(model, data, m1), site_of(model, data, m2)}) {
    if (s.slot < 0) continue;
    Side& d = side_[n++];
    d.body = s.body;
    d.node = s.node;
    d.slot = s.slot;
    d.Q0 = data.Q.segment<12>(model.bodies[static_cast<std::size_t>(s.body)].offset);
  }
}

void InterfaceLoadCapture::add_to_interfaces(const Model& model, Data& data) const {
  for (const Side& d : side_) {
    if (d.slot < 0) continue;
    const Body& b = model.bodies[static_cast<std::size_t>(d.body)];
    const Eigen::Matrix<double, 12, 1> dQ = data.Q.segment<12>(b.offset) - d.Q0;
    add_node_load(b, data.bodies[static_cast<std::size_t>(d.body)], data, d.slot, d.node, dQ.head<3>(), dQ.tail<9>());
  }
}

}  // namespace ffr::runtime
