// "bodies" of type "beam": large-deformation beams (beam.hpp, FORMULATION.md section 15), and the
// checks that what attaches to a beam reads only what its nodes carry.
#include "ffr/runtime/beam.hpp"
#include "parse.hpp"

#include <cmath>

namespace ffr::runtime::detail {

namespace {

// A geometrically exact beam (FORMULATION.md 17): its node bodies and its element data.
void parse_ge_beam(const Field& b, const std::string& name, ParseContext& ctx) {
  const double E = b.at("E").positive();
  const Field nuf = b.at("nu");
  const double nu = nuf.number();
  if (!(nu > -1 && nu < 0.5)) nuf.fail("must lie in (-1, 0.5) (found " + std::to_string(nu) + ")");
  const double rho = b.at("rho").positive();
  const Field sec = b.at("section");
  sec.allow_only({"A", "Iy", "Iz", "J", "shear_factor"});
  const double A = sec.at("A").positive();
  const double Iy = sec.at("Iy").positive();
  const double Iz = sec.at("Iz").positive();
  const double J = sec.at("J").positive();
  // Shear correction: 5/6, a rectangle's (Reissner), unless the section says otherwise.
  const double kappa = sec.has("shear_factor") ? sec.at("shear_factor").positive() : 5.0 / 6.0;
  if (kappa > 1) sec.at("shear_factor").fail("must not exceed 1 (found " + std::to_string(kappa) + ")");
  const int elements = b.at("elements").small_integer();
  const Vector3d start = b.at("start").vec3(), end = b.at("end").vec3();
  Vector3d y_axis;
  if (auto f = b.find("y_axis")) {
    y_axis = f->vec3();
  } else {
    // Without a y_axis the section's orientation must not matter.
    if (std::abs(Iy - Iz) > 1e-9 * std::max(Iy, Iz))
      b.fail("needs \"y_axis\" (the section's local y direction): Iy and Iz differ");
    const Vector3d t = end - start;
    y_axis = triad(t.norm() > 0 ? Vector3d(t.normalized()) : Vector3d::UnitX()).col(1);
  }
  double tau = 0;
  if (auto d = b.find("damping")) {
    d->allow_only({"strain_rate"});
    tau = d->at("strain_rate").non_negative();
  }
  Model& m = ctx.model;
  std::vector<Body> nodes;
  GeBeam beam = make_ge_beam(nodes, name, start, end, y_axis, elements, E, E / (2 * (1 + nu)), rho, A, Iy, Iz, J, kappa,
                             tau, ctx.file, b.path());
  for (Body& n : nodes) {
    if (m.find_body(n.name) != -2) b.at("name").fail("its node body '" + n.name + "' clashes with a body of that name");
    n.source = "beam '" + name + "' node";
    beam.node_bodies.push_back(static_cast<int>(m.bodies.size()));
    m.bodies.push_back(std::move(n));
  }
  m.ge_beams.push_back(std::move(beam));
}

}  // namespace

int ge_beam_of(const Model& m, int body) {
  if (body < 0) return -1;
  for (std::size_t g = 0; g < m.ge_beams.size(); ++g)
    for (const int nb : m.ge_beams[g].node_bodies)
      if (nb == body) return static_cast<int>(g);
  return -1;
}

int ge_beam_node(const Field& f, const Model& m, int g, int& body) {
  const GeBeam& beam = m.ge_beams[static_cast<std::size_t>(g)];
  const std::string n = f.string();
  int k = -1;
  if (n == "start") k = 0;
  if (n == "end") k = beam.elements;
  for (int i = 0; i <= beam.elements && k < 0; ++i)
    if (n == "n" + std::to_string(i)) k = i;
  if (k < 0)
    f.fail("body '" + beam.name + "' has no node '" + n + "' (nodes: n0 ... n" + std::to_string(beam.elements) +
           ", start, end)");
  body = beam.node_bodies[static_cast<std::size_t>(k)];
  return 0;
}

void parse_beam(const Field& b, const std::string& name, ParseContext& ctx) {
  b.allow_only({"name", "type", "formulation", "start", "end", "elements", "E", "nu", "rho", "section", "y_axis", "damping"});
  const Field form = b.at("formulation");
  if (form.string() == "geometrically_exact") return parse_ge_beam(b, name, ctx);
  if (form.string() != "ancf")
    form.fail("unknown beam formulation '" + form.string() + "' (expected ancf or geometrically_exact)");
  // The gradient-deficient element has one bending stiffness, no torsion and no shear: what
  // would be ignored is refused rather than dropped (FORMULATION.md 15, limitations).
  if (auto f = b.find("nu")) f->fail("is not used by the ancf beam (no shear or torsion); remove it");
  if (auto f = b.find("y_axis"))
    f->fail("orients a section the ancf beam cannot: it has no torsion and needs Iy = Iz; remove it");
  const Field sec = b.at("section");
  sec.allow_only({"A", "Iy", "Iz", "J"});
  if (auto f = sec.find("J")) f->fail("is not used: the ancf beam has no torsion; remove it");
  const double A = sec.at("A").positive();
  const double Iy = sec.at("Iy").positive();
  const double Iz = sec.at("Iz").positive();
  if (std::abs(Iy - Iz) > 1e-9 * std::max(Iy, Iz))
    sec.at("Iz").fail("must equal Iy: the ancf beam's section bends alike about every axis (a round or square "
                      "section); it has no section orientation");
  const int elements = b.at("elements").small_integer();
  const double E = b.at("E").positive();
  const double rho = b.at("rho").positive();
  double tau = 0;
  if (auto d = b.find("damping")) {
    d->allow_only({"strain_rate"});
    tau = d->at("strain_rate").non_negative();
  }
  Body body = make_beam_body(name, b.at("start").vec3(), b.at("end").vec3(), elements, E, rho, A, Iy, tau, ctx.file, b.path());
  body.source = "beam";
  ctx.model.bodies.push_back(std::move(body));
}

namespace {

bool on_beam(const Model& m, int marker) {
  const Marker& mk = m.markers[static_cast<std::size_t>(marker)];
  return mk.body != kGround && m.bodies[static_cast<std::size_t>(mk.body)].beam != nullptr;
}

}  // namespace

void check_beam_attachments(const Field& root, ParseContext& ctx) {
  const Model& m = ctx.model;
  // A beam's frame is held at the global frame: a marker on it that is not at a node would be
  // attached to nothing that moves.
  const auto node_only = [&](const Field& where, int marker) {
    const Marker& mk = m.markers[static_cast<std::size_t>(marker)];
    if (on_beam(m, marker) && mk.node < 0)
      where.fail("attaches to beam '" + m.bodies[static_cast<std::size_t>(mk.body)].name +
                 "' away from its nodes: give node1/node2 (n0 ... nN, start, end)");
    // A geometrically exact beam named without a node resolves to its first node's body.
    if (const int g = ge_beam_of(m, mk.body); g >= 0 && mk.node < 0)
      where.fail("attaches to beam '" + m.ge_beams[static_cast<std::size_t>(g)].name +
                 "' without a node: give node1/node2 (n0 ... nN, start, end)");
  };
  const auto joint = [&](const Field& f, const Joint& jt) {
    node_only(f, jt.m1);
    node_only(f, jt.m2);
    if (!on_beam(m, jt.m1) && !on_beam(m, jt.m2)) return;
    // A node has a position and a slope; its axes are the slope's small rotation, exact only
    // for rows that hold the slope's direction against the ground (a clamp).
    const bool to_ground = m.markers[static_cast<std::size_t>(jt.m1)].body == kGround ||
                           m.markers[static_cast<std::size_t>(jt.m2)].body == kGround;
    if (jt.type == JointType::Spherical || (jt.type == JointType::Fixed && to_ground)) return;
    // A weld to a moving body would need the node's full triad: the element is gradient-deficient
    // (position and one slope per node, no cross-section gradients), so the body's turn about the
    // slope would follow nothing (FORMULATION.md 15).
    if (jt.type == JointType::Fixed)
      f.at("type").fail("a fixed joint between a body and an ancf beam node is not supported: the ancf beam is "
                        "gradient-deficient (a node carries its position and one slope, no cross-section axes), so "
                        "there is no triad for the body to follow; use \"formulation\": \"geometrically_exact\", "
                        "whose nodes carry a triad, or a spherical joint");
    f.at("type").fail(std::string("a ") + to_string(jt.type) +
                      " joint at a beam node is not supported: the ancf node has no rotation beyond its slope's "
                      "direction (spherical joints, and fixed joints to the ground, are)");
  };
  const auto force = [&](const AttachedElement& a) {
    if (a.kind == AttachmentKind::Bushing) {
      for (const int mk : {a.m1, a.m2})
        if (ge_beam_of(m, m.markers[static_cast<std::size_t>(mk)].body) >= 0) node_only(a.where, mk);
      if (on_beam(m, a.m1) || on_beam(m, a.m2))
        a.where.at("type").fail("a bushing at a beam node is not supported: the ancf node has no rotation beyond its slope's direction");
      return;
    }
    node_only(a.where, a.m1);
    if (a.m2 >= 0) node_only(a.where, a.m2);
    if (a.kind == AttachmentKind::Torque && on_beam(m, a.m1))
      a.where.at("type").fail("a point torque at a beam node is not supported: the ancf node has no rotation beyond its slope's direction");
  };
  visit_attachments(root, m, joint, force);
}

}  // namespace ffr::runtime::detail
