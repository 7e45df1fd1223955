// "bodies" of type "plate": large-deformation thin plates (plate.hpp, FORMULATION.md section 16),
// and the checks that what attaches to a plate reads only what its nodes carry.
#include "ffr/runtime/plate.hpp"
#include "parse.hpp"
#include "../bodies/plate_triad.hpp"

#include <cmath>

namespace ffr::runtime::detail {

namespace {

// The plate's shape integrals are dense nq x nq matrices (the general flexible body's, 18 of
// them with their stacked copy): 11 x 11 nodes (1452 coordinates) take about 300 MB.
constexpr int kMaxNodes = 121;

PlateSupport support(const Field& f) {
  const std::string s = f.string();
  if (s == "free") return PlateSupport::Free;
  if (s == "simply_supported") return PlateSupport::SimplySupported;
  if (s == "clamped") return PlateSupport::Clamped;
  f.fail("unknown support '" + s + "' (expected clamped, simply_supported or free)");
}

}  // namespace

Body parse_plate(const Field& b, const std::string& name, ParseContext& ctx) {
  b.allow_only({"name", "type", "formulation", "corners", "elements", "thickness", "E", "nu", "rho", "damping", "supports"});
  if (auto form = b.find("formulation"))
    if (form->string() != "ancf") form->fail("unknown plate formulation '" + form->string() + "' (expected ancf)");
  const Field corners = b.at("corners");
  if (!corners.is_array() || corners.size() != 4)
    corners.fail("must be four corner points [[x, y, z], ...] in order round the plate");
  Eigen::Vector3d c[4];
  for (std::size_t i = 0; i < 4; ++i) c[i] = corners.at(i).vec3();
  const Field el = b.at("elements");
  if (!el.is_array() || el.size() != 2) el.fail("must be [nx, ny]: elements along corner 0-1 and along corner 0-3");
  const int nx = el.at(std::size_t{0}).small_integer(), ny = el.at(std::size_t{1}).small_integer();
  if (nx >= 1 && ny >= 1 && (nx + 1) * (ny + 1) > kMaxNodes)
    el.fail("gives " + std::to_string((nx + 1) * (ny + 1)) + " nodes; at most " + std::to_string(kMaxNodes) +
            " are allowed (the plate's mass is held as the dense shape integrals of a flexible body)");
  const double h = b.at("thickness").positive();
  const double E = b.at("E").positive();
  const Field fnu = b.at("nu");
  const double nu = fnu.number();
  if (!(nu > -1 && nu < 0.5)) fnu.fail("must be in (-1, 0.5) (found " + std::to_string(nu) + ")");
  const double rho = b.at("rho").positive();
  double tau = 0;
  if (auto d = b.find("damping")) {
    d->allow_only({"strain_rate"});
    tau = d->at("strain_rate").non_negative();
  }
  PlateSupport edges[4] = {PlateSupport::Free, PlateSupport::Free, PlateSupport::Free, PlateSupport::Free};
  if (auto s = b.find("supports")) {
    s->allow_only({"x0", "x1", "y0", "y1"});
    const char* names[4] = {"x0", "x1", "y0", "y1"};
    for (int e = 0; e < 4; ++e)
      if (auto f = s->find(names[e])) edges[e] = support(*f);
  }
  Body body = make_plate_body(name, c, nx, ny, h, E, nu, rho, tau, edges, ctx.file, b.path());
  body.source = "plate";
  return body;
}

namespace {

bool on_plate(const Model& m, int marker) {
  const Marker& mk = m.markers[static_cast<std::size_t>(marker)];
  return mk.body != kGround && m.bodies[static_cast<std::size_t>(mk.body)].plate != nullptr;
}

// A weld's marker on a plate node reads the node's exact triad (Marker::triad): the
// Gram-Schmidt frame of its gradients r_x, r_y, and its axes E in that frame as it is at the
// start (the weld's constant relative orientation).
void use_node_triad(Marker& mk, const Body& b) {
  const int k = 12 * mk.node;
  mk.triad = k + 3;
  mk.triad_x0 = b.plate->q0.segment<3>(k + 3);
  mk.triad_y0 = b.plate->q0.segment<3>(k + 6);
  detail::PlateTriad T;
  detail::plate_triad(mk.triad_x0 + b.y0.segment<3>(k + 3), mk.triad_y0 + b.y0.segment<3>(k + 6), T);
  Matrix3d T0;
  for (int i = 0; i < 3; ++i) T0.col(i) = T.t[i];
  mk.triad_R = T0.transpose() * mk.E;
}

}  // namespace

void check_plate_attachments(const Field& root, ParseContext& ctx) {
  const Model& m = ctx.model;
  // A plate's frame is held at the global frame: a marker on it that is not at a node would be
  // attached to nothing that moves.
  const auto node_only = [&](const Field& where, int marker) {
    const Marker& mk = m.markers[static_cast<std::size_t>(marker)];
    if (on_plate(m, marker) && mk.node < 0)
      where.fail("attaches to plate '" + m.bodies[static_cast<std::size_t>(mk.body)].name +
                 "' away from its nodes: give node1/node2 (n<i>_<j>)");
  };
  const auto joint = [&](const Field& f, const Joint& jt) {
    node_only(f, jt.m1);
    node_only(f, jt.m2);
    if (!on_plate(m, jt.m1) && !on_plate(m, jt.m2)) return;
    // A node's linearised axes are exact only for rows that hold them against the ground (a
    // point clamp, linear rows). A weld to a moving body reads the node's exact triad instead
    // (FORMULATION.md 16, "Welds"): its rows are exact at any rotation.
    const bool to_ground = m.markers[static_cast<std::size_t>(jt.m1)].body == kGround ||
                           m.markers[static_cast<std::size_t>(jt.m2)].body == kGround;
    if (jt.type == JointType::Spherical || (jt.type == JointType::Fixed && to_ground)) return;
    if (jt.type == JointType::Fixed) {
      std::string where;
      for (int mi : {jt.m1, jt.m2}) {
        if (!on_plate(m, mi)) continue;
        Marker& mk = ctx.model.markers[static_cast<std::size_t>(mi)];
        const Body& b = m.bodies[static_cast<std::size_t>(mk.body)];
        use_node_triad(mk, b);
        where += std::string(where.empty() ? "" : " and ") + "node '" + b.nodes[static_cast<std::size_t>(mk.node)].name +
                 "' of plate '" + b.name + "'";
      }
      ctx.model.notes.push_back("joint '" + jt.name + "' (fixed) at " + where +
                                ": its rotation rows hold the node's exact triad (the Gram-Schmidt frame of r_x, r_y) and "
                                "stay constraint rows (not assembled)");
      return;
    }
    f.at("type").fail(std::string("a ") + to_string(jt.type) +
                      " joint at a plate node is not supported: the node's rotation is its gradients' linearised turn "
                      "(spherical and fixed joints are; an edge is held by the plate's supports)");
  };
  const auto force = [&](const AttachedElement& a) {
    if (a.kind == AttachmentKind::Bushing) {
      if (on_plate(m, a.m1) || on_plate(m, a.m2))
        a.where.at("type").fail("a bushing at a plate node is not supported: the node's rotation is its gradients' linearised turn");
      return;
    }
    node_only(a.where, a.m1);
    if (a.m2 >= 0) node_only(a.where, a.m2);
    if (a.kind == AttachmentKind::Torque && on_plate(m, a.m1))
      a.where.at("type").fail("a point torque at a plate node is not supported: the node's rotation is its gradients' linearised turn");
  };
  visit_attachments(root, m, joint, force);
}

}  // namespace ffr::runtime::detail
