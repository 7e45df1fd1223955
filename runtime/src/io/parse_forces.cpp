// "forces": spring-dampers, friction dampers, bushings, tyres, and point forces and torques from tables.
#include "ffr/runtime/kinematics.hpp"
#include "parse.hpp"

#include <cmath>

namespace ffr::runtime::detail {
namespace {

// One end of a spring: body, and node or global point (`at1`/`node1` style keys).
Attachment end_point(const Field& f, const Model& m, const char* body_key, const char* at_key, const char* node_key,
                     const char* offset_key) {
  Attachment a;
  a.body = body_ref(f.at(body_key), m);
  if (auto n = f.find(node_key)) {
    a.node = node_ref(*n, m, a.body);
    a.point = node_position(m, a.body, a.node);
    if (f.has(at_key)) f.at(at_key).fail(std::string("give either ") + at_key + " or " + node_key);
    node_offset(f, offset_key, m, a);
  } else if (f.has(offset_key)) {
    f.at(offset_key).fail(std::string("is an offset from a node: give ") + node_key + " too");
  } else if (auto at = f.find(at_key)) {
    a.point = at->vec3();
  } else if (a.body != kGround) {
    a.point = m.bodies[a.body].r0;  // the frame origin
  } else {
    f.fail(std::string("needs ") + at_key + " on the ground");
  }
  return a;
}

// A characteristic {"x": [...], "value": [...], "interpolation": ...}: a force against a
// deflection or a rate, linear between its points by default (it never overshoots them) and
// continued with its end slopes beyond them.
Table parse_characteristic(const Field& f) {
  f.allow_only({"x", "value", "interpolation"});
  const Field xf = f.at("x"), vf = f.at("value");
  const Eigen::VectorXd x = xf.vector(), v = vf.vector();
  if (x.size() < 2) xf.fail("needs at least two points");
  if (v.size() != x.size()) vf.fail("has " + std::to_string(v.size()) + " entries but x has " + std::to_string(x.size()));
  for (Eigen::Index i = 1; i < x.size(); ++i)
    if (!(x(i) > x(i - 1))) xf.fail("must be strictly increasing (entry " + std::to_string(i) + ")");
  const Interpolation kind = f.has("interpolation") ? interpolation(f.at("interpolation")) : Interpolation::Linear;
  return Table(x, v, kind);
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
      f.allow_only({"name", "type", "body1", "at1", "node1", "body2", "at2", "node2", "offset1", "offset2", "k", "c", "length0", "force_table",
                    "damping_table", "preload"});
      SpringDamper s;
      s.name = element_name(f, i);
      const Attachment a1 = end_point(f, m, "body1", "at1", "node1", "offset1");
      const Attachment a2 = end_point(f, m, "body2", "at2", "node2", "offset2");
      // Two points of one flexible body (a tendon, a strut) load its modes; on a rigid body it
      // would exert nothing.
      if (a1.body == a2.body && (a1.body == kGround || !m.bodies[a1.body].flexible))
        f.at("body2").fail("a spring needs two different bodies, or two points of one flexible body");
      // k or force_table (one of them), c or damping_table (at most one).
      if (auto t = f.find("force_table")) {
        if (f.has("k")) f.at("k").fail("give either k or force_table");
        s.force_table = parse_characteristic(*t);
      } else {
        s.k = f.at("k").non_negative();
      }
      if (auto t = f.find("damping_table")) {
        if (f.has("c")) f.at("c").fail("give either c or damping_table");
        s.damping_table = parse_characteristic(*t);
      }
      s.c = f.has("c") ? f.at("c").non_negative() : 0.0;
      if (auto p = f.find("preload")) s.preload = p->number();
      s.m1 = add_marker(m, a1, Matrix3d::Identity());
      s.m2 = add_marker(m, a2, Matrix3d::Identity());
      const double l = (a2.point - a1.point).norm();
      s.length0 = f.has("length0") ? f.at("length0").non_negative() : l;
      if (l == 0 && s.length0 > 0) f.fail("the two ends coincide initially, so the spring has no direction there");
      m.springs.push_back(s);
    } else if (type == "friction_damper") {
      f.allow_only({"name", "type", "body1", "at1", "node1", "body2", "at2", "node2", "offset1", "offset2", "force", "series_stiffness",
                    "velocity_tolerance"});
      FrictionDamper fd;
      fd.name = element_name(f, i);
      const Attachment a1 = end_point(f, m, "body1", "at1", "node1", "offset1");
      const Attachment a2 = end_point(f, m, "body2", "at2", "node2", "offset2");
      if (a1.body == a2.body && (a1.body == kGround || !m.bodies[a1.body].flexible))
        f.at("body2").fail("a friction damper needs two different bodies, or two points of one flexible body");
      fd.force = f.at("force").positive();
      if (auto k = f.find("series_stiffness")) {
        fd.series_stiffness = k->positive();
        // Its stick and slip are exact (return mapping): a tolerance would be silently unused.
        if (auto v = f.find("velocity_tolerance"))
          v->fail("applies only without series_stiffness (with a series spring stick and slip are exact)");
      } else {
        fd.velocity_tolerance = f.has("velocity_tolerance") ? f.at("velocity_tolerance").positive() : 1e-3;
      }
      fd.length0 = (a2.point - a1.point).norm();
      if (fd.length0 == 0) f.fail("the two ends coincide initially, so the damper has no direction there");
      fd.m1 = add_marker(m, a1, Matrix3d::Identity());
      fd.m2 = add_marker(m, a2, Matrix3d::Identity());
      m.friction_dampers.push_back(fd);
    } else if (type == "bushing") {
      f.allow_only({"name", "type", "body1", "body2", "at", "node1", "node2", "offset1", "offset2", "axes", "stiffness", "damping", "tables", "preload"});
      Bushing bu;
      bu.name = element_name(f, i);
      Attachment a1, a2;
      connection_points(f, m, a1, a2, true);
      Matrix3d E = Matrix3d::Identity();
      if (auto ax = f.find("axes")) {
        // Rows as written are the bushing's x, y, z axes (global).
        E = ax->mat3().transpose();
        if ((E.transpose() * E - Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 || E.determinant() < 0)
          ax->fail("must be three orthonormal right-handed axes");
      }
      // Per axis a characteristic (tables.x ... tables.rz) or a stiffness; without tables the
      // six stiffnesses are required.
      bu.k = f.has("stiffness") || !f.has("tables") ? VectorXd(f.at("stiffness").vector(6)) : VectorXd::Zero(6);
      bu.c = f.has("damping") ? VectorXd(f.at("damping").vector(6)) : VectorXd::Zero(6);
      if (bu.k.minCoeff() < 0) f.at("stiffness").fail("must not be negative");
      if (auto tf = f.find("tables")) {
        static const char* kAxes[6] = {"x", "y", "z", "rx", "ry", "rz"};
        tf->allow_only({"x", "y", "z", "rx", "ry", "rz"});
        for (int a = 0; a < 6; ++a)
          if (auto t = tf->find(kAxes[a])) {
            if (bu.k(a) != 0) f.at("stiffness").fail(std::string("is not zero on axis ") + kAxes[a] + ", which tables." + kAxes[a] + " gives");
            bu.tables[a] = parse_characteristic(*t);
          }
      }
      if (auto pf = f.find("preload")) {
        pf->allow_only({"force", "torque"});
        if (auto v = pf->find("force")) bu.preload.head<3>() = v->vec3();
        if (auto v = pf->find("torque")) bu.preload.tail<3>() = v->vec3();
      }
      if (bu.c.minCoeff() < 0) f.at("damping").fail("must not be negative");
      bu.m1 = add_marker(m, a1, E);
      bu.m2 = add_marker(m, a2, E);
      m.bushings.push_back(bu);
    } else if (type == "tire") {
      f.allow_only({"name", "type", "body", "center", "node", "axis", "radius", "vertical_stiffness", "vertical_damping",
                    "longitudinal_stiffness", "cornering_stiffness", "friction", "velocity_tolerance", "road"});
      Tire ty;
      ty.name = element_name(f, i);
      Attachment a;
      a.body = body_ref(f.at("body"), m);
      if (a.body == kGround) f.at("body").fail("a tire needs a moving body (its wheel)");
      if (auto n = f.find("node")) {
        if (f.has("center")) f.at("center").fail("give either center or node");
        a.node = node_ref(*n, m, a.body);
        a.point = node_position(m, a.body, a.node);
      } else {
        a.point = f.has("center") ? f.at("center").vec3() : m.bodies[a.body].r0;
      }
      const Field rf = f.at("road");
      const std::string road = rf.string();
      for (std::size_t k = 0; k < m.roads.size() && ty.road < 0; ++k)
        if (m.roads[k].name == road) ty.road = static_cast<int>(k);
      if (ty.road < 0) {
        std::string known;
        for (const Road& r : m.roads) known += (known.empty() ? "" : ", ") + r.name;
        rf.fail("unknown road '" + road + "' (" + (known.empty() ? "the model has no \"roads\"" : "roads: " + known) + ")");
      }
      const Vector3d axis = unit_axis(f.at("axis"));
      // The wheel must be able to roll on the road: a spin axis along its normal would lie flat.
      if (std::abs(axis.dot(m.roads[static_cast<std::size_t>(ty.road)].up)) > 0.99)
        f.at("axis").fail("is (nearly) vertical: a wheel spinning about it lies flat on the road");
      ty.radius = f.at("radius").positive();
      ty.vertical_stiffness = f.at("vertical_stiffness").positive();
      if (auto c = f.find("vertical_damping")) ty.vertical_damping = c->non_negative();
      if (auto k = f.find("longitudinal_stiffness")) ty.longitudinal_stiffness = k->non_negative();
      if (auto k = f.find("cornering_stiffness")) ty.cornering_stiffness = k->non_negative();
      // Friction and the speed regularisation act on the slip forces alone: without them they
      // would be silently unused.
      if (ty.longitudinal_stiffness > 0 || ty.cornering_stiffness > 0) {
        ty.friction = f.at("friction").positive();
        if (auto v = f.find("velocity_tolerance")) ty.velocity_tolerance = v->positive();
      } else {
        for (const char* k : {"friction", "velocity_tolerance"})
          if (auto v = f.find(k)) v->fail("applies only with a longitudinal_stiffness or cornering_stiffness");
      }
      // A centre at or below the road is a misplaced wheel (a sign or a unit), not a deflection.
      const Road& rd = m.roads[static_cast<std::size_t>(ty.road)];
      const double above = a.point.dot(rd.up) - rd.profile.value(a.point.dot(rd.direction), 0);
      if (!(above > 0)) {
        const std::string what = "the wheel centre is " + std::to_string(-above) + " m below the road '" + rd.name + "' at set-up";
        if (f.has("node")) f.at("node").fail(what);
        if (f.has("center")) f.at("center").fail(what);
        f.fail(what + " (the centre is the body's frame origin: give \"center\")");
      }
      ty.marker = add_marker(m, a, triad(axis));
      m.tires.push_back(ty);
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
      l.table = parse_table(f.at("table"), 3, Interpolation::Linear);
      l.marker = add_marker(m, a, Matrix3d::Identity());
      m.loads.push_back(std::move(l));
    } else {
      f.at("type").fail("unknown force type '" + type + "' (expected spring_damper, friction_damper, bushing, tire, point_force or point_torque)");
    }
  }
}

}  // namespace ffr::runtime::detail
