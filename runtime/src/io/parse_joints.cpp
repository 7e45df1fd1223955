// "joints": markers on both bodies at a common point (global `at`, or SID nodes), with a triad
// built from the joint's axis.
#include "parse.hpp"

#include <set>

namespace ffr::runtime::detail {

int node_ref(const Field& f, const Model& m, int& body) {
  const std::string n = f.string();
  if (body == kGround) f.fail("the ground has no nodes");
  if (const int g = ge_beam_of(m, body); g >= 0) return ge_beam_node(f, m, g, body);
  const Body& b = m.bodies[body];
  if (!b.flexible) f.fail("body '" + b.name + "' is rigid and has no nodes (use \"at\")");
  const int k = b.find_node(n);
  if (k < 0) {
    std::string known;
    for (const auto& node : b.nodes) known += (known.empty() ? "" : ", ") + node.name;
    f.fail("body '" + b.name + "' has no node '" + n + "' (nodes: " + (known.empty() ? "none" : known) + ")");
  }
  return k;
}

void node_offset(const Field& parent, const char* key, const Model& m, Attachment& a) {
  const auto f = parent.find(key);
  if (!f) return;
  if (a.node < 0) f->fail("is an offset from a node: give the node too");
  if (m.bodies[a.body].beam)
    f->fail("is not supported at a beam node: the ancf node has no rotation beyond its slope's direction to carry it");
  if (m.bodies[a.body].plate)
    f->fail("is not supported at a plate node: the node's rotation is its gradients' linearised turn, which an offset would read as exact");
  a.offset = f->vec3();
  // Where the node carries it in the initial configuration (its initial rotation Psi y0 too).
  const Body& b = m.bodies[a.body];
  const Vector3d theta = b.nodes[a.node].psi * b.y0;
  a.point += b.A0 * (a.offset + theta.cross(a.offset));
}

Vector3d node_position(const Model& m, int body, int node) {
  const Body& b = m.bodies[body];
  const NodeSlice& n = b.nodes[node];
  return b.r0 + b.A0 * (n.origin + n.displacement(b.y0));
}

int add_marker(Model& m, const Attachment& a, const Matrix3d& E) {
  Marker mk;
  mk.body = a.body;
  if (a.body == kGround) {
    mk.c = a.point;
    mk.E = E;
  } else {
    const Body& b = m.bodies[a.body];
    mk.E = b.A0.transpose() * E;
    if (a.node >= 0) {
      // A point at offset o from the node moves by phi y + (psi y) x o = (phi - [o]x psi) y.
      const Vector3d& o = a.offset;
      Matrix3d ox;
      ox << 0, -o(2), o(1), o(2), 0, -o(0), -o(1), o(0), 0;
      mk.node = a.node;
      mk.c = b.nodes[a.node].origin + o;
      mk.phi = b.nodes[a.node].phi - ox * b.nodes[a.node].psi;
      mk.psi = b.nodes[a.node].psi;
    } else {
      mk.c = b.A0.transpose() * (a.point - b.r0);
      mk.phi.resize(3, 0);
      mk.psi.resize(3, 0);
    }
  }
  m.markers.push_back(std::move(mk));
  return static_cast<int>(m.markers.size()) - 1;
}

namespace {

JointType joint_type(const Field& f) {
  const std::string t = f.string();
  if (t == "revolute") return JointType::Revolute;
  if (t == "spherical") return JointType::Spherical;
  if (t == "fixed") return JointType::Fixed;
  if (t == "prismatic") return JointType::Prismatic;
  if (t == "cylindrical") return JointType::Cylindrical;
  if (t == "universal") return JointType::Universal;
  f.fail("unknown joint type '" + t + "' (expected revolute, spherical, fixed, prismatic, cylindrical or universal)");
}

}  // namespace

/// Resolves the common point of a two-body connection: `at`, else the first node given, else the
/// frame origin of a flexible body (docs/contract.md: "a flexible body without either is joined at its
/// frame origin"). Each side without a node is attached rigidly to its frame at that point.
void connection_points(const Field& j, const Model& m, Attachment& a1, Attachment& a2, bool within_flexible) {
  a1.body = body_ref(j.at("body1"), m);
  a2.body = body_ref(j.at("body2"), m);
  const bool within = within_flexible && a1.body == a2.body && a1.body != kGround && m.bodies[a1.body].flexible;
  if (a1.body == a2.body && !within)
    j.at("body2").fail(within_flexible ? "a connection needs two different bodies, or two nodes of one flexible body"
                                       : "a connection needs two different bodies");
  if (auto n = j.find("node1")) a1.node = node_ref(*n, m, a1.body);
  if (auto n = j.find("node2")) a2.node = node_ref(*n, m, a2.body);
  if (within && (a1.node < 0 || a2.node < 0 || a1.node == a2.node))
    j.at("body2").fail("within one flexible body, give two different nodes (node1, node2)");
  // `at` with a node would put the node's side at the node and the other side at `at`: refused.
  if (j.has("at") && (a1.node >= 0 || a2.node >= 0))
    j.at("at").fail(std::string("give either at or ") + (a1.node >= 0 ? "node1" : "node2") +
                    " (the joint point is the node, or with offset1/offset2 a point carried by it)");
  if (a1.node >= 0) a1.point = node_position(m, a1.body, a1.node);
  if (a2.node >= 0) a2.point = node_position(m, a2.body, a2.node);
  node_offset(j, "offset1", m, a1);
  node_offset(j, "offset2", m, a2);
  Vector3d P;
  if (auto at = j.find("at")) {
    P = at->vec3();
  } else if (a1.node >= 0) {
    P = a1.point;
  } else if (a2.node >= 0) {
    P = a2.point;
  } else if (a2.body != kGround && m.bodies[a2.body].flexible) {
    P = m.bodies[a2.body].r0;
  } else if (a1.body != kGround && m.bodies[a1.body].flexible) {
    P = m.bodies[a1.body].r0;
  } else {
    j.fail("needs \"at\" (a global point) or a node of a flexible body");
  }
  a1.point = a2.point = P;
}

namespace {

// {"type": "coupler", "joint1", "joint2", "ratio"}: joint1's coordinate changes by ratio times
// joint2's (revolute: the angle, prismatic: the displacement, cylindrical: the angle).
void parse_coupler(const Field& j, Model& m, std::set<std::string>& names) {
  j.allow_only({"name", "type", "joint1", "joint2", "ratio"});
  Coupler c;
  c.name = j.at("name").string();
  if (c.name.empty()) j.at("name").fail("must not be empty");
  if (!names.insert(c.name).second) j.at("name").fail("duplicate joint name '" + c.name + "'");
  JointCoordinate* coord[2] = {&c.c1, &c.c2};
  int* joint[2] = {&c.joint1, &c.joint2};
  for (int k = 0; k < 2; ++k) {
    const Field f = j.at(k == 0 ? "joint1" : "joint2");
    const std::string n = f.string();
    const int idx = m.find_joint(n);
    if (idx < 0) f.fail("unknown joint '" + n + "' (a coupler names revolute, prismatic or cylindrical joints)");
    const JointType t = m.joints[idx].type;
    if (t != JointType::Revolute && t != JointType::Prismatic && t != JointType::Cylindrical)
      f.fail(std::string("a coupler needs a revolute, prismatic or cylindrical joint; '") + n + "' is " + to_string(t));
    *joint[k] = idx;
    *coord[k] = t == JointType::Prismatic ? JointCoordinate::Displacement : JointCoordinate::Angle;
  }
  if (c.joint1 == c.joint2) j.at("joint2").fail("must differ from joint1");
  const Field rf = j.at("ratio");
  c.ratio = rf.number();
  if (!(c.ratio != 0)) rf.fail("must not be zero (the joints would not be coupled)");
  // The row touches both joints' bodies (up to four: two shafts each in its own housing, the
  // housings on one carrier); each coordinate is measured in its own joint.
  m.couplers.push_back(c);
}

}  // namespace

void parse_joints(const Field& root, ParseContext& ctx) {
  if (!root.has("joints")) return;
  const Field list = root.at("joints");
  std::set<std::string> names;
  Model& m = ctx.model;
  std::vector<std::size_t> couplers;  // parsed after the joints they name
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Field j = list.at(i);
    if (j.is_object() && j.has("type") && j.at("type").is_string() && j.at("type").string() == "coupler") {
      couplers.push_back(i);
      continue;
    }
    j.allow_only({"name", "type", "body1", "body2", "at", "node1", "node2", "offset1", "offset2", "axis", "axis1", "axis2"});
    Joint jt;
    jt.name = j.at("name").string();
    if (jt.name.empty()) j.at("name").fail("must not be empty");
    if (!names.insert(jt.name).second) j.at("name").fail("duplicate joint name '" + jt.name + "'");
    jt.type = joint_type(j.at("type"));
    Attachment a1, a2;
    connection_points(j, m, a1, a2);
    Matrix3d E1 = Matrix3d::Identity(), E2 = Matrix3d::Identity();
    switch (jt.type) {
      case JointType::Revolute:
      case JointType::Prismatic:
      case JointType::Cylindrical:
        E1 = E2 = triad(unit_axis(j.at("axis")));
        break;
      case JointType::Fixed:
        if (auto a = j.find("axis")) E1 = E2 = triad(unit_axis(*a));
        break;
      case JointType::Universal: {
        const Vector3d x1 = unit_axis(j.at("axis1")), x2 = unit_axis(j.at("axis2"));
        if (std::abs(x1.dot(x2)) > 1e-9) j.at("axis2").fail("must be perpendicular to axis1");
        E1 = triad(x1);
        E2 = triad(x2);
        break;
      }
      case JointType::Spherical:
        break;
    }
    if (jt.type == JointType::Universal) {
      if (j.has("axis")) j.at("axis").fail("a universal joint takes axis1 and axis2");
    } else if (j.has("axis1") || j.has("axis2")) {
      j.at(j.has("axis1") ? "axis1" : "axis2").fail("only a universal joint takes axis1/axis2");
    }
    if (jt.type == JointType::Spherical && j.has("axis")) j.at("axis").fail("a spherical joint has no axis");
    jt.m1 = add_marker(m, a1, E1);
    jt.m2 = add_marker(m, a2, E2);
    m.joints.push_back(jt);
  }
  for (std::size_t i : couplers) parse_coupler(list.at(i), m, names);
}

}  // namespace ffr::runtime::detail
