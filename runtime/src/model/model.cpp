// Model bookkeeping: coordinate offsets, constraint blocks, scales and derived offsets.
#include "ffr/runtime/model.hpp"
#include "ffr/runtime/relative.hpp"

#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "known_frame.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace ffr::runtime {

const char* to_string(JointType t) {
  switch (t) {
    case JointType::Revolute: return "revolute";
    case JointType::Spherical: return "spherical";
    case JointType::Fixed: return "fixed";
    case JointType::Prismatic: return "prismatic";
    case JointType::Cylindrical: return "cylindrical";
    case JointType::Universal: return "universal";
  }
  return "?";
}

int joint_rows(JointType t) {
  switch (t) {
    case JointType::Spherical: return 3;
    case JointType::Revolute: return 5;
    case JointType::Universal: return 4;
    case JointType::Fixed: return 6;
    case JointType::Cylindrical: return 4;
    case JointType::Prismatic: return 5;
  }
  return 0;
}

int Model::find_body(const std::string& n) const {
  if (n == "ground") return kGround;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == n) return static_cast<int>(i);
  return -2;
}

int Model::find_joint(const std::string& n) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == n) return static_cast<int>(i);
  return -1;
}

int Model::find_output(const std::string& n) const {
  for (std::size_t i = 0; i < outputs.size(); ++i)
    if (outputs[i].name == n) return static_cast<int>(i);
  return -1;
}

namespace {

// Mode slices of a node marker's axes: (psi y) x E_k = -skew(E_k) psi y.
void set_axis_slices(Marker& mk) {
  if (mk.body == kGround || mk.node < 0) return;
  for (int k = 0; k < 3; ++k) {
    const Vector3d e = mk.E.col(k);
    mk.phiE[k].resize(3, mk.psi.cols());
    for (Eigen::Index j = 0; j < mk.psi.cols(); ++j) mk.phiE[k].col(j) = Vector3d(mk.psi.col(j)).cross(e);
  }
}

Marker slot_marker(const Body& b, int node) {
  Marker m;
  m.E = Matrix3d::Identity();
  if (node < 0) return m;
  const NodeSlice& n = b.nodes[node];
  m.node = node;
  m.c = n.origin;
  m.phi = n.phi;
  m.psi = n.psi;
  return m;
}

// The drive of each rigid body held, or moved by a motion, through a joint to the ground alone
// (Drive). The first such joint of a body drives it; any other joint or motion between it and
// the ground is then a condition among driven bodies, checked while the model runs.
// A rigid body on a prismatic joint to the ground without a motion is frame-locked instead
// (Body::frame_locked), unless another joint drives it. Why: such a body only slides, and its
// nine frame coordinates with the six rows of its frame made a slider-crank's step work on 34
// unknowns and 27 rows where 25 and 21 describe it (measured: 27 us a step instead of 33; with
// its guide's rotational rows split off as well, in finalize, 18 rows).
void find_drives(Model& m) {
  for (auto& b : m.bodies) {
    b.drive = Drive{};
    b.frame_locked = false;
  }
  if (!m.settings.eliminate_driven) return;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const Joint& jt = m.joints[j];
    const int b1 = m.markers[jt.m1].body, b2 = m.markers[jt.m2].body;
    if ((b1 == kGround) == (b2 == kGround)) continue;  // not between a body and the ground
    const int side = b1 == kGround ? 2 : 1;
    Body& b = m.bodies[side == 1 ? b1 : b2];
    if (b.nq > 0 || b.driven()) continue;
    Drive d;
    d.joint = static_cast<int>(j);
    d.side = side;
    if (jt.type == JointType::Fixed) {
      d.kind = DriveKind::Fixed;
    } else if (jt.type == JointType::Revolute || jt.type == JointType::Prismatic) {
      for (std::size_t i = 0; i < m.motions.size(); ++i)
        if (m.motions[i].joint == static_cast<int>(j)) d.motion = static_cast<int>(i);
      if (d.motion < 0) {
        b.frame_locked = b.frame_locked || jt.type == JointType::Prismatic;
        continue;
      }
      d.kind = jt.type == JointType::Revolute ? DriveKind::Revolute : DriveKind::Prismatic;
    } else {
      continue;
    }
    b.drive = d;
  }
  for (auto& b : m.bodies)
    if (b.driven()) b.frame_locked = false;  // a later joint drove it: it is known whole
  // A joint whose reaction is an output needs its multipliers, which only the rows of the
  // unknowns have: its bodies stay integrated when neither would be (and a frame-locked slider
  // keeps its frame among the unknowns, whose rows carry the guide's reaction torque).
  for (const Output& o : m.outputs) {
    if (o.type != OutputType::JointReaction) continue;
    const Joint& jt = m.joints[static_cast<std::size_t>(o.joint)];
    const int bs[2] = {m.markers[jt.m1].body, m.markers[jt.m2].body};
    const auto fixed = [&](int b) { return b == kGround || m.bodies[b].driven(); };
    const bool neither = fixed(bs[0]) && fixed(bs[1]);
    for (int b : bs) {
      if (b == kGround) continue;
      if (neither) m.bodies[b].drive = Drive{};
      m.bodies[b].frame_locked = false;
    }
  }
}

// Active blocks (touching an integrated body, other than a frame-locked body's own frame)
// first, in their order, then the others; rows numbered in that order, and the joints' and
// motions' block indices with them.
void order_blocks(Model& m) {
  const auto integrated = [&](int body) { return body != kGround && !m.bodies[body].driven(); };
  const auto active = [&](const ConstraintBlock& b) {
    // holds: the frame's rows see known coordinates only (a locked or known frame)
    if (b.kind == BlockKind::RigidBody && detail::first_known_frame_coord(m, m.bodies[b.body1]) < 12) return false;
    if (b.held_by_lock) return false;  // a locked body's prismatic rotational rows: both frames known
    return integrated(b.body1) || integrated(b.body2) || integrated(b.body3) || integrated(b.body4);
  };
  std::stable_partition(m.blocks.begin(), m.blocks.end(), active);
  int row = 0;
  m.active_blocks = 0;
  m.nactive = 0;
  for (std::size_t i = 0; i < m.blocks.size(); ++i) {
    ConstraintBlock& b = m.blocks[i];
    b.row0 = row;
    row += b.rows;
    if (b.kind == BlockKind::Joint) m.joints[b.index].block = static_cast<int>(i);
    if (b.kind == BlockKind::Motion) m.motions[b.index].block = static_cast<int>(i);
    if (b.kind == BlockKind::Coupler) m.couplers[b.index].block = static_cast<int>(i);
    if (active(b)) {
      m.active_blocks = static_cast<int>(i) + 1;
      m.nactive = row;
    }
  }
  m.nconstraints = row;
}

// Which axes of each marker anything reads (Marker::axes). Why: a marker on a node computes each
// axis, its rate and its Jacobian from the node's mode slices every evaluation, and most joints
// leave one of them unread (a revolute joint's second marker its e axis; a spherical joint's
// markers all three). Every joint coordinate stays readable at any time (joint_coordinate is
// public, and update_angle_references tracks every revolute and cylindrical angle), so the axes
// of each joint's own coordinates count as read.
void mark_read_axes(Model& m) {
  for (auto& mk : m.markers) mk.axes = {false, false, false};
  const auto use = [&](int marker, std::initializer_list<int> ks) {
    for (int k : ks) m.markers[static_cast<std::size_t>(marker)].axes[static_cast<std::size_t>(k)] = true;
  };
  for (const auto& j : m.joints) {
    switch (j.type) {  // the rows of constraints.cpp's joint_rows
      case JointType::Spherical: break;
      case JointType::Revolute: use(j.m1, {0}); use(j.m2, {1, 2}); break;
      case JointType::Universal: use(j.m1, {0}); use(j.m2, {0}); break;
      case JointType::Fixed: use(j.m1, {0, 1}); use(j.m2, {1, 2}); break;
      case JointType::Cylindrical:
      case JointType::Prismatic: use(j.m1, {0, 1, 2}); use(j.m2, {1, 2}); break;
    }
  }
  // Joint coordinates (constraints.cpp's coordinate): the angle reads f1, g1 and f2, the
  // displacement e1.
  for (const auto& j : m.joints) {
    if (j.type == JointType::Revolute || j.type == JointType::Cylindrical) {
      use(j.m1, {1, 2});
      use(j.m2, {1});
    }
    if (j.type == JointType::Prismatic || j.type == JointType::Cylindrical) use(j.m1, {0});
  }
  for (const auto& bu : m.bushings) {
    use(bu.m1, {0, 1, 2});
    use(bu.m2, {0, 1, 2});
  }
  for (const auto& ty : m.tires) use(ty.marker, {0, 1, 2});  // the spin axis and the wheel's angular velocity
}

}  // namespace

void finalize(Model& m) {
  // Without a body there is no coordinate: the step's vectors and matrices would be empty, and
  // the norms of the start's projections undefined (it ended in a segmentation fault).
  if (m.bodies.empty())
    throw ModelError(m.source, "bodies", "no body: the model has nothing to integrate (give at least one rigid, flexible, beam or plate body)");
  // The relative formulation (relative.hpp) reconstructs every body's natural coordinates from
  // its own: no body is driven out of the unknowns.
  m.relative.reset();
  std::string formulation_why;
  const bool relative = m.settings.formulation == Formulation::Relative ||
                        (m.settings.formulation == Formulation::Auto && choose_formulation(m, formulation_why) == Formulation::Relative);
  if (relative) m.settings.eliminate_driven = false;
  // Coordinates: the integrated bodies first, the driven ones after them.
  find_drives(m);
  int off = 0;
  double size = 0, mass_sum = 0;
  m.nfree = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (auto& b : m.bodies)
      if (b.driven() == (pass == 1)) {
        b.offset = off;
        off += b.ncoord();
        if (pass == 0) m.nfree = off;
      }
  // The model length: the largest of the bodies' sizes, each the larger of its radius of
  // gyration and the distance of its farthest marker from its centre of mass. Why both: the
  // radius of gyration alone makes a point mass on an arm (the IFToMM pendulum's bob, 1e-9 kg m^2
  // of its own) a body 5e-5 m large, and the tolerances, relative to it, then ask for violations
  // below round-off of its 1 m arm; the arm's length is where its markers are.
  for (auto& b : m.bodies) {
    const Matrix3d Jg = b.J0 - b.rdm * b.rdm.transpose() / b.mass;
    size = std::max(size, std::sqrt(std::max(0.0, Jg.trace() / b.mass)));
    mass_sum += b.mass;
  }
  for (const Marker& mk : m.markers)
    if (mk.body != kGround) {
      const Body& b = m.bodies[static_cast<std::size_t>(mk.body)];
      size = std::max(size, (mk.c - b.rdm / b.mass).norm());
    }
  if (off > kMaxModelCoordinates) {
    const auto most = std::max_element(m.bodies.begin(), m.bodies.end(),
                                       [](const Body& a, const Body& b) { return a.ncoord() < b.ncoord(); });
    throw ModelError(m.source, "bodies",
                     "the model has " + std::to_string(off) + " coordinates in " + std::to_string(m.bodies.size()) +
                         " bodies (the most, " + std::to_string(most->ncoord()) + ", in body '" + most->name +
                         "'); at most " + std::to_string(kMaxModelCoordinates) +
                         " are allowed: the step's matrices are dense in them");
  }
  m.ncoord = off;
  m.nunknown = m.nfree;
  for (const auto& b : m.bodies) m.nunknown -= 12 - detail::first_known_frame_coord(m, b);
  m.length = size > 0 ? size : 1.0;
  m.mass = m.bodies.empty() ? 1.0 : mass_sum / static_cast<double>(m.bodies.size());
  for (auto& b : m.bodies) {
    b.PPdm_stack.resize(9 * b.nq, b.nq);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) b.PPdm_stack.middleRows((3 * a + c) * b.nq, b.nq) = b.PPdm[a][c];
    b.y_scale.resize(b.nq);
    for (int k = 0; k < b.nq; ++k)
      b.y_scale(k) = b.Myy(k, k) > 0 ? m.length * std::sqrt(b.mass / b.Myy(k, k)) : m.length;
  }
  // Increment weights (FORMULATION.md 9). A frame vector's diagonal mass is J0_aa, the body's
  // mass spread along axis a: sqrt(J0_aa / m) is how far its mass moves when the vector does.
  // Why not one weight for all frame vectors: a point mass's or a slender bar's frame vectors
  // across it carry no mass, and their round-off-sized increments (the penalty forces' rounding
  // over a mass of 1e-9) would then stall convergence tests that nothing physical depends on.
  m.increment_weight.resize(m.ncoord);
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const Body& b = m.bodies[i];
    Vector3d extent = (b.J0.diagonal() / b.mass).cwiseMax(0.0).cwiseSqrt();
    for (const Marker& mk : m.markers)
      if (mk.body == static_cast<int>(i)) extent = extent.cwiseMax(mk.c.cwiseAbs());
    m.increment_weight.segment<3>(b.offset).setConstant(1.0 / m.length);
    for (int a = 0; a < 3; ++a) m.increment_weight.segment<3>(b.offset + 3 + 3 * a).setConstant(extent(a) / m.length);
    for (int k = 0; k < b.nq; ++k) m.increment_weight(b.offset + 12 + k) = 1.0 / b.y_scale(k);
  }

  // Markers on a node need their axes' mode slices.
  for (auto& mk : m.markers) set_axis_slices(mk);

  // Constraint blocks: rigid-body conditions, joints, motions (their rows and the joints' and
  // motions' block indices are numbered by order_blocks).
  m.blocks.clear();
  for (std::size_t i = 0; i < m.bodies.size(); ++i)
    m.blocks.push_back({BlockKind::RigidBody, static_cast<int>(i), 0, m.bodies[i].frame_rows(), static_cast<int>(i), kGround});
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    Joint& jt = m.joints[j];
    const int b1 = m.markers[jt.m1].body, b2 = m.markers[jt.m2].body;
    const auto locked = [&](int body) { return body != kGround && m.bodies[body].frame_locked; };
    if (jt.type == JointType::Prismatic && ((b1 == kGround && locked(b2)) || (b2 == kGround && locked(b1)))) {
      // Why split: the three rotational rows are zero over the unknowns (a locked body's frame
      // is known); kept among the active rows they cost work in every product with the
      // Jacobian (the benchmark's slider-crank: 18 active rows instead of 21).
      m.blocks.push_back({BlockKind::Joint, static_cast<int>(j), 0, 2, b1, b2, 0, false});
      m.blocks.push_back({BlockKind::Joint, static_cast<int>(j), 0, 3, b1, b2, 2, true});
    } else {
      m.blocks.push_back({BlockKind::Joint, static_cast<int>(j), 0, joint_rows(jt.type), b1, b2});
    }
    // Zero of the displacement coordinate: the initial offset along the axis.
    jt.d0 = (initial_marker_position(m, m.markers[jt.m2]) - initial_marker_position(m, m.markers[jt.m1]))
                .dot(initial_marker_axis(m, m.markers[jt.m1], 0));
  }
  for (std::size_t i = 0; i < m.motions.size(); ++i) {
    const Motion& mo = m.motions[i];
    const Joint& jt = m.joints[mo.joint];
    const bool angle_ok = jt.type == JointType::Revolute || jt.type == JointType::Cylindrical;
    const bool disp_ok = jt.type == JointType::Prismatic || jt.type == JointType::Cylindrical;
    if ((mo.coordinate == JointCoordinate::Angle && !angle_ok) || (mo.coordinate == JointCoordinate::Displacement && !disp_ok))
      throw ModelError(m.source, "motions[" + std::to_string(i) + "]",
                       std::string("a ") + to_string(jt.type) + " joint has no " +
                           (mo.coordinate == JointCoordinate::Angle ? "angle" : "displacement") + " to prescribe");
    m.blocks.push_back({BlockKind::Motion, static_cast<int>(i), 0, 1, m.markers[jt.m1].body, m.markers[jt.m2].body});
  }
  for (std::size_t i = 0; i < m.couplers.size(); ++i) {
    // Its row touches the bodies of both joints: at most four besides the ground, body1 to body4
    // of the block in the order met.
    const Coupler& c = m.couplers[i];
    int b[4] = {kGround, kGround, kGround, kGround}, n = 0;
    for (int j : {c.joint1, c.joint2})
      for (int mk : {m.joints[j].m1, m.joints[j].m2}) {
        const int body = m.markers[mk].body;
        if (body == kGround || body == b[0] || body == b[1] || body == b[2] || body == b[3]) continue;
        b[n++] = body;
      }
    ConstraintBlock blk{BlockKind::Coupler, static_cast<int>(i), 0, 1, b[0], b[1]};
    blk.body3 = b[2];
    blk.body4 = b[3];
    m.blocks.push_back(blk);
  }
  order_blocks(m);
  mark_read_axes(m);

  // Load slots for external inputs: the frame origin and every node of every body.
  m.load_slots.assign(m.bodies.size(), {});
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const Body& b = m.bodies[i];
    m.load_slots[i].push_back(slot_marker(b, -1));
    for (std::size_t p = 0; p < b.nodes.size(); ++p) m.load_slots[i].push_back(slot_marker(b, static_cast<int>(p)));
    for (auto& mk : m.load_slots[i]) {
      mk.body = static_cast<int>(i);
      set_axis_slices(mk);
    }
  }

  // Bushings are unloaded in the initial configuration.
  for (auto& bu : m.bushings) {
    const Marker& a = m.markers[bu.m1];
    const Marker& b = m.markers[bu.m2];
    const Vector3d d = initial_marker_position(m, b) - initial_marker_position(m, a);
    Vector3d e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = initial_marker_axis(m, a, k);
      e2[k] = initial_marker_axis(m, b, k);
    }
    bu.s0 << e1[0].dot(d), e1[1].dot(d), e1[2].dot(d), 0.5 * (e1[2].dot(e2[1]) - e1[1].dot(e2[2])),
        0.5 * (e1[0].dot(e2[2]) - e1[2].dot(e2[0])), 0.5 * (e1[1].dot(e2[0]) - e1[0].dot(e2[1]));
  }
  if (relative) {
    build_relative_tree(m);
    m.notes.insert(m.notes.end(), m.relative->assembled.begin(), m.relative->assembled.end());
    m.notes.push_back((formulation_why.empty() ? std::string() : "formulation: " + formulation_why + "; ") + m.relative->description);
  } else if (!formulation_why.empty()) {
    m.notes.push_back("formulation: " + formulation_why);
  }
}

}  // namespace ffr::runtime
