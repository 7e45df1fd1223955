// "motions" and "outputs".
#include "parse.hpp"

#include <set>

namespace ffr::runtime::detail {
namespace {

int joint_ref(const Field& f, const Model& m) {
  const std::string n = f.string();
  const int j = m.find_joint(n);
  if (j < 0) f.fail("unknown joint '" + n + "'");
  return j;
}

// The coordinates a joint reports: revolute angle, prismatic displacement, cylindrical both.
std::vector<JointCoordinate> joint_coordinates(const Field& f, const Joint& j) {
  switch (j.type) {
    case JointType::Revolute: return {JointCoordinate::Angle};
    case JointType::Prismatic: return {JointCoordinate::Displacement};
    case JointType::Cylindrical: return {JointCoordinate::Angle, JointCoordinate::Displacement};
    default: f.fail(std::string("a ") + to_string(j.type) + " joint has no joint coordinate");
  }
}

}  // namespace

void parse_motions(const Field& root, ParseContext& ctx) {
  if (!root.has("motions")) return;
  Model& m = ctx.model;
  const Field list = root.at("motions");
  std::set<int> driven;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Field f = list.at(i);
    f.allow_only({"joint", "table", "speed", "coordinate"});
    Motion mo;
    mo.joint = joint_ref(f.at("joint"), m);
    const Joint& j = m.joints[mo.joint];
    const auto coords = joint_coordinates(f.at("joint"), j);
    mo.coordinate = coords.front();
    if (auto c = f.find("coordinate")) {
      const std::string s = c->string();
      if (s == "angle") mo.coordinate = JointCoordinate::Angle;
      else if (s == "displacement") mo.coordinate = JointCoordinate::Displacement;
      else c->fail("expected angle or displacement");
      bool ok = false;
      for (auto k : coords) ok = ok || k == mo.coordinate;
      if (!ok) c->fail(std::string("a ") + to_string(j.type) + " joint has no " + s);
    }
    if (!driven.insert(mo.joint * 2 + static_cast<int>(mo.coordinate)).second)
      f.at("joint").fail("this joint coordinate is already prescribed");
    // The coordinate (`table`) or its rate (`speed`, integrated exactly), never both.
    if (auto sp = f.find("speed")) {
      if (f.has("table")) sp->fail("give either table (the coordinate) or speed (its rate), not both");
      mo.table = parse_table(*sp, 1, Interpolation::Pchip);
      mo.speed = true;
      mo.start = m.settings.start;
    } else {
      mo.table = parse_table(f.at("table"), 1, Interpolation::Pchip);
    }
    m.motions.push_back(std::move(mo));
  }
}

void parse_outputs(const Field& root, ParseContext& ctx) {
  if (!root.has("outputs")) return;
  Model& m = ctx.model;
  const Field list = root.at("outputs");
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Field f = list.at(i);
    f.allow_only({"name", "type", "body", "node", "at", "joint", "force"});
    Output o;
    o.name = f.at("name").string();
    if (o.name.empty() || o.name.find('/') != std::string::npos || o.name == "." || o.name == "..")
      f.at("name").fail("must be a non-empty name without '/'");
    if (!names.insert(o.name).second) f.at("name").fail("duplicate output name '" + o.name + "'");
    const std::string type = f.at("type").string();
    if (f.has("force") && type != "element_force") f.at("force").fail("is a key of element_force outputs");
    auto flexible_body = [&]() {
      o.body = body_ref(f.at("body"), m);
      if (o.body == kGround || !m.bodies[o.body].flexible) f.at("body").fail("must be a flexible body");
    };
    if (type == "node_deformation") {
      flexible_body();
      o.type = OutputType::NodeDeformation;
      o.node = node_ref(f.at("node"), m, o.body);
      o.size = 3;
    } else if (type == "node_position" || type == "node_velocity") {
      o.type = type == "node_position" ? OutputType::NodePosition : OutputType::NodeVelocity;
      o.body = body_ref(f.at("body"), m);
      if (o.body == kGround) f.at("body").fail("the ground does not move");
      o.size = 3;
      const Body& b = m.bodies[o.body];
      if (auto n = f.find("node")) {
        o.node = node_ref(*n, m, o.body);
      } else if (b.flexible && !f.has("at")) {
        f.fail("needs \"node\" (or \"at\", a point rigidly on the body's frame)");
      } else {
        // A point fixed in the body frame, given globally in the initial configuration.
        o.point = f.has("at") ? Vector3d(b.A0.transpose() * (f.at("at").vec3() - b.r0)) : Vector3d::Zero();
      }
    } else if (type == "modal_coordinates") {
      flexible_body();
      o.type = OutputType::ModalCoordinates;
      o.size = m.bodies[o.body].nq;
    } else if (type == "joint_coordinate") {
      o.type = OutputType::JointCoordinate;
      o.joint = joint_ref(f.at("joint"), m);
      o.coords = joint_coordinates(f.at("joint"), m.joints[o.joint]);
      o.size = static_cast<int>(o.coords.size());
    } else if (type == "joint_rate") {
      o.type = OutputType::JointRate;
      o.joint = joint_ref(f.at("joint"), m);
      o.coords = joint_coordinates(f.at("joint"), m.joints[o.joint]);
      o.size = static_cast<int>(o.coords.size());
    } else if (type == "joint_reaction") {
      o.type = OutputType::JointReaction;
      o.joint = joint_ref(f.at("joint"), m);
      o.size = 6;
    } else if (type == "body_angular_velocity") {
      o.type = OutputType::BodyAngularVelocity;
      o.body = body_ref(f.at("body"), m);
      if (o.body == kGround) f.at("body").fail("the ground does not move");
      o.size = 3;
    } else if (type == "element_force") {
      o.type = OutputType::ElementForce;
      const Field ef = f.at("force");
      const std::string n = ef.string();
      for (std::size_t k = 0; k < m.springs.size() && o.element < 0; ++k)
        if (m.springs[k].name == n) {
          o.element_kind = ForceElementKind::SpringDamper;
          o.element = static_cast<int>(k);
          o.size = 1;
        }
      for (std::size_t k = 0; k < m.bushings.size() && o.element < 0; ++k)
        if (m.bushings[k].name == n) {
          o.element_kind = ForceElementKind::Bushing;
          o.element = static_cast<int>(k);
          o.size = 6;
        }
      for (std::size_t k = 0; k < m.friction_dampers.size() && o.element < 0; ++k)
        if (m.friction_dampers[k].name == n) {
          o.element_kind = ForceElementKind::FrictionDamper;
          o.element = static_cast<int>(k);
          o.size = 1;
        }
      for (std::size_t k = 0; k < m.tires.size() && o.element < 0; ++k)
        if (m.tires[k].name == n) {
          o.element_kind = ForceElementKind::Tire;
          o.element = static_cast<int>(k);
          o.size = 6;
        }
      if (o.element < 0) {
        for (const PointLoad& l : m.loads)
          if (l.name == n) ef.fail("'" + n + "' is a point load: its force is its table");
        ef.fail("no spring_damper, bushing, friction_damper or tire named '" + n + "'");
      }
    } else if (type == "energy") {
      o.type = OutputType::Energy;
      // With friction dampers a fourth value: the energy they have dissipated.
      o.size = m.friction_dampers.empty() ? 3 : 4;
    } else {
      f.at("type").fail("unknown output type '" + type +
                        "' (expected node_deformation, node_position, node_velocity, modal_coordinates, joint_coordinate, joint_rate, "
                        "joint_reaction, body_angular_velocity, element_force or energy)");
    }
    m.outputs.push_back(o);
  }
}

}  // namespace ffr::runtime::detail
