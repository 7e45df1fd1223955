// The loads that joints and force elements apply at the interface nodes of flexible bodies, for
// the interface-load stiffening (SID /stiffening/interfaces, FORMULATION.md 7).
#include "ffr/runtime/dynamics.hpp"
#include "../forces/forces.hpp"

namespace ffr::runtime {
namespace {

// The interface of the body's stiffening terms at node `node`, or -1.
int interface_at(const StiffeningTerms& s, int node) {
  for (std::size_t i = 0; i < s.interfaces.size(); ++i)
    if (s.interfaces[i].node == node) return static_cast<int>(i);
  return -1;
}

// The load whose generalized force over the body's frame columns is F (r0) and QA (the nine
// columns of A): the force F (global: a point's Jacobian has I there), the moment about the
// origin sum_a A_a x QA_a, about the node that less (A xbar_p) x F; both resolved in K.
// add_node_load adds it to interface `slot` of body i.
Eigen::Matrix<double, 6, 1> node_load(const Body& b, const BodyData& bd, const Data& data, int node, const Vector3d& F,
                                      const Eigen::Ref<const Eigen::Matrix<double, 9, 1>>& QA) {
  Vector3d M = Vector3d::Zero();
  for (int a = 0; a < 3; ++a) M += Vector3d(bd.A.col(a)).cross(Vector3d(QA.segment<3>(3 * a)));
  const NodeSlice& n = b.nodes[static_cast<std::size_t>(node)];
  Vector3d xbar = n.origin;
  xbar += n.displacement(data.state.q.segment(b.offset + 12, b.nq));
  M -= (bd.A * xbar).cross(F);
  Eigen::Matrix<double, 6, 1> L;
  L << bd.A.transpose() * F, bd.A.transpose() * M;
  return L;
}

void add_node_load(const Body& b, BodyData& bd, const Data& data, int slot, int node, const Vector3d& F,
                   const Eigen::Ref<const Eigen::Matrix<double, 9, 1>>& QA) {
  bd.iface_load.col(slot) += node_load(b, bd, data, node, F, QA);
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

// Calls fn(slot, node, F, QA) for each joint, motion or coupler of body i that acts on it through
// a marker on one of its stiffening interfaces: its generalized force -Phi_q^T lam over the
// body's frame columns (F on r0, QA on the nine columns of A), with the last evaluated
// constraint Jacobian.
template <class Fn>
void for_each_joint_load(const Model& model, const Data& data, std::size_t i, const VectorXd& lam, Fn&& fn) {
  const Body& b = model.bodies[i];
  const int o = b.offset, body = static_cast<int>(i);
  for (const ConstraintBlock& blk : model.blocks) {
    if (blk.kind == BlockKind::RigidBody || (blk.body1 != body && blk.body2 != body && blk.body3 != body && blk.body4 != body)) continue;
    const Marker* mk = nullptr;
    if (blk.kind == BlockKind::Coupler) {
      // A coupler's rows load body i through the markers its two joints have on it: it acts at
      // that node when they sit on one node (a joint of the body to itself is skipped, as below);
      // markers on two different nodes share one load that cannot be split between them.
      const Coupler& cp = model.couplers[static_cast<std::size_t>(blk.index)];
      bool split = false;
      for (const int j : {cp.joint1, cp.joint2}) {
        const Joint& jt = model.joints[static_cast<std::size_t>(j)];
        const Marker& m1 = model.markers[static_cast<std::size_t>(jt.m1)];
        const Marker& m2 = model.markers[static_cast<std::size_t>(jt.m2)];
        if (m1.body == body && m2.body == body) continue;
        const Marker* m = m1.body == body ? &m1 : m2.body == body ? &m2 : nullptr;
        if (!m) continue;
        if (mk && mk->node != m->node) split = true;
        mk = m;
      }
      if (split) continue;
    } else {
      const Joint& jt = model.joints[static_cast<std::size_t>(blk.kind == BlockKind::Joint ? blk.index : model.motions[static_cast<std::size_t>(blk.index)].joint)];
      const Marker& m1 = model.markers[static_cast<std::size_t>(jt.m1)];
      const Marker& m2 = model.markers[static_cast<std::size_t>(jt.m2)];
      if (m1.body == body && m2.body == body) continue;  // a body jointed to itself loads nothing
      mk = m1.body == body ? &m1 : &m2;
    }
    if (!mk || mk->node < 0) continue;
    const int s = interface_at(*b.stiffening, mk->node);
    if (s < 0) continue;
    const auto l = lam.segment(blk.row0, blk.rows);
    const Vector3d F = -(data.Phiq.middleRows(blk.row0, blk.rows).middleCols<3>(o).transpose() * l);
    const Eigen::Matrix<double, 9, 1> QA = -(data.Phiq.middleRows(blk.row0, blk.rows).middleCols<9>(o + 3).transpose() * l);
    fn(s, mk->node, F, QA);
  }
}

bool has_interfaces(const Model& model, const Data& data, std::size_t i) {
  const Body& b = model.bodies[i];
  return b.stiffening && !b.stiffening->interfaces.empty() && data.integrated[i];
}

}  // namespace

// A joint's force on body i is -Phi_q^T lambda over the body's columns. The multipliers are the
// current ones and the Jacobian the last evaluated (frozen within the iterate, like the
// accelerations of the inertial load cases).
void interface_loads(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!has_interfaces(model, data, i)) continue;
    const Body& b = model.bodies[i];
    BodyData& bd = data.bodies[i];
    bd.iface_load.setZero();
    for_each_joint_load(model, data, i, data.state.lambda, [&](int s, int node, const Vector3d& F, const Eigen::Matrix<double, 9, 1>& QA) {
      add_node_load(b, bd, data, s, node, F, QA);
    });
  }
}

// The interface loads are linear in the multipliers, so the stiffening force's derivative along
// mu is the stiffening of the loads of mu alone: -dQ_y/dlambda mu = sum_c (F_c(mu) KF[c] +
// M_c(mu) KM[c]) y, with the same Jacobian and node positions as interface_loads. Each joint's
// load is applied to y as it is found: no load table is kept (nothing allocated).
void detail::add_interface_multiplier_forces(const Model& model, const Data& data, const VectorXd& mu, VectorXd& r) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!has_interfaces(model, data, i)) continue;
    const Body& b = model.bodies[i];
    const BodyData& bd = data.bodies[i];
    const auto y = data.state.q.segment(b.offset + 12, b.nq);
    auto ry = r.segment(b.offset + 12, b.nq);
    for_each_joint_load(model, data, i, mu, [&](int s, int node, const Vector3d& F, const Eigen::Matrix<double, 9, 1>& QA) {
      const Eigen::Matrix<double, 6, 1> L = node_load(b, bd, data, node, F, QA);
      const InterfaceStiffening& itf = b.stiffening->interfaces[static_cast<std::size_t>(s)];
      for (int c = 0; c < 3; ++c) {
        if (L(c) != 0) ry.noalias() += L(c) * (itf.KF[c] * y);
        if (L(3 + c) != 0) ry.noalias() += L(3 + c) * (itf.KM[c] * y);
      }
    });
  }
}

InterfaceLoadCapture::InterfaceLoadCapture(const Model& model, const Data& data, int m1, int m2)
    : InterfaceLoadCapture(model, data, m1 >= 0 ? &model.markers[static_cast<std::size_t>(m1)] : nullptr,
                           m2 >= 0 ? &model.markers[static_cast<std::size_t>(m2)] : nullptr) {}

InterfaceLoadCapture::InterfaceLoadCapture(const Model& model, const Data& data, const Marker* m1, const Marker* m2) {
  // An element between two points of one body: its frame columns hold the sum of both ends'
  // loads, which cannot be told apart there; the element gives them end by end instead
  // (detail::add_end_loads).
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

namespace detail {

bool same_body_interfaces(const Model& model, const Data& data, int m1, int m2) {
  const Marker& a = model.markers[static_cast<std::size_t>(m1)];
  const Marker& b = model.markers[static_cast<std::size_t>(m2)];
  return a.body == b.body && (site_of(model, data, &a).slot >= 0 || site_of(model, data, &b).slot >= 0);
}

void add_end_loads(const Model& model, Data& data, int m1, int m2, const Eigen::Matrix<double, 12, 2>& ends) {
  const int mk[2] = {m1, m2};
  for (int e = 0; e < 2; ++e) {
    const InterfaceSite s = site_of(model, data, &model.markers[static_cast<std::size_t>(mk[e])]);
    if (s.slot < 0) continue;
    const Body& b = model.bodies[static_cast<std::size_t>(s.body)];
    add_node_load(b, data.bodies[static_cast<std::size_t>(s.body)], data, s.slot, s.node, ends.col(e).head<3>(),
                  ends.col(e).tail<9>());
  }
}

}  // namespace detail
}  // namespace ffr::runtime
