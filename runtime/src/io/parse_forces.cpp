// "forces": spring-dampers, bushings, and point forces and torques from tables.
#include "ffr/runtime/kinematics.hpp"
#include "parse.hpp"

namespace ffr::runtime::detail {
namespace {

// One end of a spring: body, and node or global point (`at1`/`node1` style keys).
Attachment end_point(const Field& f, const Model& m, const char* body_key, const char* at_key, const char* node_key) {
  Attachment a;
  a.body = body_ref(f.at(body_key), m);
  if (auto n = f.find(node_key)) {
    a.node = node_ref(*n, m, a.body);
    a.point = node_position(m, a.body, a.node);
    if (f.has(at_key)) f.at(at_key).fail(std::string("give either ") + at_key + " or " + node_key);
  } else if (auto at = f.find(at_key)) {
    a.point = at->vec3();
  } else if (a.body != kGround) {
    a.point = m.bodies[a.body].r0;  // the frame origin
  } else {
    f.fail(std::string("needs ") + at_key + " on the ground");
  }
  return a;
}

std::string element_name(const Field& f, std::size_t i) {
  return f.has("name") ? f.at("name").string() : "forces[" + std::to_string(i) + "]";
}

}  // namespace

void parse_forces(const Field& root, ParseContext& ctx) {
  if (!root.has("forces")) return;
  Model& m = ctx.model;
  const Field list = root.at("forces");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Field f = list.at(i);
    if (!f.is_object()) f.fail("expected an object");
    const std::string type = f.at("type").string();
    if (type == "spring_damper") {
      f.allow_only({"name", "type", "body1", "at1", "node1", "body2", "at2", "node2", "k", "c", "length0"});
      SpringDamper s;
      s.name = element_name(f, i);
      const Attachment a1 = end_point(f, m, "body1", "at1", "node1");
      const Attachment a2 = end_point(f, m, "body2", "at2", "node2");
      if (a1.body == a2.body) f.at("body2").fail("a spring needs two different bodies");
      s.k = f.at("k").non_negative();
      s.c = f.has("c") ? f.at("c").non_negative() : 0.0;
      s.m1 = add_marker(m, a1, Matrix3d::Identity());
      s.m2 = add_marker(m, a2, Matrix3d::Identity());
      const double l = (a2.point - a1.point).norm();
      s.length0 = f.has("length0") ? f.at("length0").non_negative() : l;
      if (l == 0 && s.length0 > 0) f.fail("the two ends coincide initially, so the spring has no direction there");
      m.springs.push_back(s);
    } else if (type == "bushing") {
      f.allow_only({"name", "type", "body1", "body2", "at", "node1", "node2", "axes", "stiffness", "damping"});
      Bushing bu;
      bu.name = element_name(f, i);
      Attachment a1, a2;
      connection_points(f, m, a1, a2);
      Matrix3d E = Matrix3d::Identity();
      if (auto ax = f.find("axes")) {
        // Rows as written are the bushing's x, y, z axes (global).
        E = ax->mat3().transpose();
        if ((E.transpose() * E - Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 || E.determinant() < 0)
          ax->fail("must be three orthonormal right-handed axes");
      }
      bu.k = f.at("stiffness").vector(6);
      bu.c = f.has("damping") ? VectorXd(f.at("damping").vector(6)) : VectorXd::Zero(6);
      if (bu.k.minCoeff() < 0) f.at("stiffness").fail("must not be negative");
      if (bu.c.minCoeff() < 0) f.at("damping").fail("must not be negative");
      bu.m1 = add_marker(m, a1, E);
      bu.m2 = add_marker(m, a2, E);
      m.bushings.push_back(bu);
    } else if (type == "point_force" || type == "point_torque") {
      f.allow_only({"name", "type", "body", "node", "at", "table"});
      PointLoad l;
      l.name = element_name(f, i);
      l.torque = type == "point_torque";
      Attachment a;
      a.body = body_ref(f.at("body"), m);
      if (a.body == kGround) f.at("body").fail("a load on the ground does nothing");
      if (auto n = f.find("node")) {
        a.node = node_ref(*n, m, a.body);
        a.point = node_position(m, a.body, a.node);
      } else {
        a.point = f.has("at") ? f.at("at").vec3() : m.bodies[a.body].r0;
      }
      l.table = parse_table(f.at("table"), 3);
      l.marker = add_marker(m, a, Matrix3d::Identity());
      m.loads.push_back(std::move(l));
    } else {
      f.at("type").fail("unknown force type '" + type + "' (expected spring_damper, bushing, point_force or point_torque)");
    }
  }
}

}  // namespace ffr::runtime::detail
