// The relative formulation's spanning tree (relative.hpp): which joints place their child
// body, which bodies stay free, which constraint rows stay; and the Auto rule.
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/relative.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

namespace ffr::runtime {
namespace {

// How a joint can place the body on its side `child` (the other side the parent): 1 wholly (the
// kinds with a rotation about and a slide along the first marker axis, or neither, between two
// markers rigidly on body frames with orthonormal triads: a marker on a flexible node has a
// first-order triad, and a child placed by it would not be rigid); 2 at its point only (a
// spherical joint anywhere; a revolute, universal or fixed joint the first way cannot place:
// the child's position follows the parent's point, exactly as the point rows evaluate it, and
// the joint's rotation rows stay); 0 not. A beam or plate (frame held at the global frame by its
// own rows) is never placed.
int placement(const Model& m, const Joint& j, int child) {
  const int b1 = m.markers[static_cast<std::size_t>(j.m1)].body, b2 = m.markers[static_cast<std::size_t>(j.m2)].body;
  if (b1 == b2 || child == kGround || m.bodies[static_cast<std::size_t>(child)].held_frame()) return 0;
  bool whole = j.type == JointType::Revolute || j.type == JointType::Prismatic || j.type == JointType::Cylindrical ||
               j.type == JointType::Fixed;
  for (int mk : {j.m1, j.m2}) {
    const Marker& k = m.markers[static_cast<std::size_t>(mk)];
    // (A geometrically exact beam's node is a rigid body: a marker there is on its frame.)
    if (k.node >= 0 && k.body != kGround && m.bodies[static_cast<std::size_t>(k.body)].nq > 0) whole = false;
    if (k.body != kGround && m.bodies[static_cast<std::size_t>(k.body)].held_frame()) whole = false;
    if (!(k.E.transpose() * k.E - Matrix3d::Identity()).isZero(1e-9)) whole = false;
  }
  if (whole) return 1;
  const bool point = j.type == JointType::Spherical || j.type == JointType::Revolute || j.type == JointType::Universal ||
                     j.type == JointType::Fixed;
  return point ? 2 : 0;
}

// The spanning tree and the relative coordinates (everything but the kept rows).
void span(const Model& m, RelativeTree& t, int& ntree, int& nfree) {
  const int nb = static_cast<int>(m.bodies.size());
  t.bodies.assign(static_cast<std::size_t>(nb), RelativeBody{});
  t.tree_joint.assign(m.joints.size(), 0);
  std::vector<char> placed(static_cast<std::size_t>(nb), 0);
  // Breadth first from the ground, then from each body left over (a free base): every body is
  // reached by the fewest joints, which keeps the recursion short and the tree shallow.
  std::deque<int> queue{kGround};
  nfree = ntree = 0;
  for (;;) {
    while (!queue.empty()) {
      const int p = queue.front();
      queue.pop_front();
      for (std::size_t ji = 0; ji < m.joints.size(); ++ji) {
        const Joint& j = m.joints[ji];
        if (t.tree_joint[ji]) continue;
        const int b1 = m.markers[static_cast<std::size_t>(j.m1)].body, b2 = m.markers[static_cast<std::size_t>(j.m2)].body;
        int child = -1, pm = -1, cm = -1;
        if (b1 == p && b2 != kGround && !placed[static_cast<std::size_t>(b2)]) child = b2, pm = j.m1, cm = j.m2;
        else if (b2 == p && b1 != kGround && !placed[static_cast<std::size_t>(b1)]) child = b1, pm = j.m2, cm = j.m1;
        if (child < 0) continue;
        const int how = placement(m, j, child);
        if (how == 0) continue;
        RelativeBody& rb = t.bodies[static_cast<std::size_t>(child)];
        rb.free = false;
        rb.point = how == 2;
        rb.parent = p;
        rb.joint = static_cast<int>(ji);
        rb.parent_marker = pm;
        rb.child_marker = cm;
        placed[static_cast<std::size_t>(child)] = 1;
        t.tree_joint[ji] = static_cast<char>(how);
        t.order.push_back(child);
        queue.push_back(child);
        ++ntree;
      }
    }
    // A beam or plate first: it can carry other bodies but never be placed itself.
    int root = -1;
    for (int b = 0; b < nb && root < 0; ++b)
      if (!placed[static_cast<std::size_t>(b)] && m.bodies[static_cast<std::size_t>(b)].held_frame()) root = b;
    for (int b = 0; b < nb && root < 0; ++b)
      if (!placed[static_cast<std::size_t>(b)]) root = b;
    if (root < 0) break;
    placed[static_cast<std::size_t>(root)] = 1;
    t.order.push_back(root);
    queue.push_back(root);
    ++nfree;
  }
  // Coordinates in the order of the recursion.
  int ns = 0;
  for (int b : t.order) {
    RelativeBody& rb = t.bodies[static_cast<std::size_t>(b)];
    const Body& body = m.bodies[static_cast<std::size_t>(b)];
    if (rb.free) {
      rb.s_first = ns;
      ns += body.ncoord();
      continue;
    }
    if (rb.point) {
      rb.s_first = ns;
      ns += 9 + body.nq;
      continue;
    }
    const JointType jt = m.joints[static_cast<std::size_t>(rb.joint)].type;
    if (jt == JointType::Revolute || jt == JointType::Cylindrical) rb.s_angle = ns++;
    if (jt == JointType::Prismatic || jt == JointType::Cylindrical) rb.s_slide = ns++;
    if (body.nq > 0) {
      rb.s_first = ns;
      ns += body.nq;
    }
  }
  t.ns = ns;
  // Column ranges, parents first (a free body's: its own).
  for (int b : t.order) {
    RelativeBody& rb = t.bodies[static_cast<std::size_t>(b)];
    int lo = ns, hi = 0;
    const auto add = [&](int c0, int n) {
      if (n <= 0 || c0 < 0) return;
      lo = std::min(lo, c0);
      hi = std::max(hi, c0 + n);
    };
    if (rb.free) {
      add(rb.s_first, m.bodies[static_cast<std::size_t>(b)].ncoord());
    } else {
      if (rb.parent != kGround) {
        const RelativeBody& pb = t.bodies[static_cast<std::size_t>(rb.parent)];
        add(pb.col0, pb.ncols);
      }
      add(rb.s_angle, 1);
      add(rb.s_slide, 1);
      add(rb.s_first, (rb.point ? 9 : 0) + m.bodies[static_cast<std::size_t>(b)].nq);
    }
    rb.col0 = lo < hi ? lo : 0;
    rb.ncols = lo < hi ? hi - lo : 0;
    // Its own columns follow its ancestors' (parents first above).
    int own = rb.col0 + rb.ncols;
    for (int c : {rb.s_angle, rb.s_slide, rb.s_first})
      if (c >= 0) own = std::min(own, c);
    rb.own0 = rb.free ? rb.col0 : own;
    rb.top = rb.free ? 0 : rb.point ? 3 : 12;
  }
  for (const Body& b : m.bodies) t.flexible = t.flexible || b.nq > 0;
}

}  // namespace

void build_relative_tree(Model& m) {
  const std::string& file = m.source;
  const SolverSettings& st = m.settings;
  if (st.adaptive)
    throw ModelError(file, "solver.formulation",
                     "\"relative\" takes fixed steps only; give solver.step a number or use \"absolute\"");
  auto tree = std::make_shared<RelativeTree>();
  RelativeTree& t = *tree;
  int ntree = 0, nfree = 0;
  span(m, t, ntree, nfree);
  const int ns = t.ns;
  // The rows that stay: all but the tree joints' and the tree bodies' frames.
  for (std::size_t i = 0; i < m.blocks.size(); ++i) {
    const ConstraintBlock& b = m.blocks[i];
    if (b.kind == BlockKind::Joint && t.tree_joint[static_cast<std::size_t>(b.index)] == 1) continue;
    if (b.kind == BlockKind::Joint && t.tree_joint[static_cast<std::size_t>(b.index)] == 2 && b.first == 0 && b.rows == 3) continue;
    const RelativeBody* own = b.kind == BlockKind::RigidBody ? &t.bodies[static_cast<std::size_t>(b.index)] : nullptr;
    if (own && !own->free && !own->point) continue;
    t.kept_blocks.push_back(static_cast<int>(i));
    // (A joint placed at its point keeps its rotation rows; its three point rows come first.)
    const bool point_rows = b.kind == BlockKind::Joint && t.tree_joint[static_cast<std::size_t>(b.index)] == 2 && b.first == 0;
    t.kept_rows += b.rows - (point_rows ? 3 : 0);
  }
  const auto hessian_pair = [&](int a, int b) {
    if (a == kGround || b == kGround) return;
    if (a > b) std::swap(a, b);
    if (std::find(t.hessian_pairs.begin(), t.hessian_pairs.end(), std::pair{a, b}) == t.hessian_pairs.end()) t.hessian_pairs.emplace_back(a, b);
  };
  for (int bi : t.kept_blocks) {
    const ConstraintBlock& b = m.blocks[static_cast<std::size_t>(bi)];
    for (int x : {b.body1, b.body2, b.body3, b.body4})
      for (int y : {b.body1, b.body2, b.body3, b.body4}) hessian_pair(x, y);
  }
  for (int b = 0; b < static_cast<int>(m.bodies.size()); ++b)
    if (m.bodies[static_cast<std::size_t>(b)].nq > 0) hessian_pair(b, b);
  t.hessian_self.assign(m.bodies.size(), 0);
  for (const auto& [a, b] : t.hessian_pairs)
    if (a == b) t.hessian_self[static_cast<std::size_t>(a)] = 1;
  // Force elements between two bodies couple their blocks of K and C.
  const auto pair = [&](int mk1, int mk2) {
    int a = m.markers[static_cast<std::size_t>(mk1)].body, b = m.markers[static_cast<std::size_t>(mk2)].body;
    if (a == kGround || b == kGround || a == b) return;
    if (a > b) std::swap(a, b);
    if (std::find(t.pairs.begin(), t.pairs.end(), std::pair{a, b}) == t.pairs.end()) t.pairs.emplace_back(a, b);
  };
  for (const auto& s : m.springs) pair(s.m1, s.m2);
  for (const auto& s : m.bushings) pair(s.m1, s.m2);
  for (const auto& s : m.friction_dampers) pair(s.m1, s.m2);
  // A geometrically exact beam's elements join consecutive node bodies (FORMULATION.md 17).
  for (const GeBeam& gb : m.ge_beams)
    for (std::size_t k = 0; k + 1 < gb.node_bodies.size(); ++k) {
      int a = gb.node_bodies[k], b = gb.node_bodies[k + 1];
      if (a > b) std::swap(a, b);
      if (std::find(t.pairs.begin(), t.pairs.end(), std::pair{a, b}) == t.pairs.end()) t.pairs.emplace_back(a, b);
    }
  // What the tree cannot give: the reaction of a joint it satisfies by construction has no
  // multiplier.
  for (std::size_t i = 0; i < m.outputs.size(); ++i) {
    const Output& o = m.outputs[i];
    if (o.type == OutputType::JointReaction && o.joint >= 0 && t.tree_joint[static_cast<std::size_t>(o.joint)] != 0)
      throw ModelError(file, "outputs[" + std::to_string(i) + "] ('" + o.name + "')",
                       "a joint_reaction of joint '" + m.joints[static_cast<std::size_t>(o.joint)].name +
                           "', which the relative formulation satisfies by its coordinates (no multiplier); use \"formulation\": \"absolute\"");
  }
  // What was assembled, joint by joint.
  const auto at_node = [&](int mk) {
    const Marker& k = m.markers[static_cast<std::size_t>(mk)];
    return k.body != kGround && k.node >= 0 && m.bodies[static_cast<std::size_t>(k.body)].nq > 0 &&
           k.node < static_cast<int>(m.bodies[static_cast<std::size_t>(k.body)].nodes.size());
  };
  const auto where = [&](int mk) {
    const Marker& k = m.markers[static_cast<std::size_t>(mk)];
    if (k.body == kGround) return std::string("the ground");
    const Body& b = m.bodies[static_cast<std::size_t>(k.body)];
    if (at_node(mk))
      return "node '" + b.nodes[static_cast<std::size_t>(k.node)].name + "' of '" + b.name + "'";
    return "'" + b.name + "'";
  };
  for (int b : t.order) {
    const RelativeBody& rb = t.bodies[static_cast<std::size_t>(b)];
    if (rb.free) continue;
    const Joint& j = m.joints[static_cast<std::size_t>(rb.joint)];
    std::string line = "joint '" + j.name + "' assembled (" + to_string(j.type) + ", body '" + m.bodies[static_cast<std::size_t>(b)].name + "' placed ";
    if (!rb.point) {
      line += "on " + where(rb.parent_marker) + " by " + std::to_string((rb.s_angle >= 0) + (rb.s_slide >= 0)) + " joint coordinate(s))";
    } else {
      line += "at " + (at_node(rb.parent_marker) ? where(rb.parent_marker) : "its point on " + where(rb.parent_marker));
      line += j.type == JointType::Spherical ? ")" : "; its rotation rows stay constraints)";
    }
    t.assembled.push_back(std::move(line));
  }
  t.description = "relative formulation: " + std::to_string(ns) + " coordinates (absolute: " + std::to_string(m.ncoord) + "), " +
                  std::to_string(ntree) + " bodies placed by their joints, " + std::to_string(nfree) + " free, " +
                  std::to_string(t.kept_rows) + " constraint rows kept (absolute: " + std::to_string(m.nconstraints) + ")";
  m.relative = std::move(tree);
}

RelativeWork::RelativeWork(const Model& model) {
  const RelativeTree& t = *model.relative;
  const int ns = t.ns, n = model.ncoord, m = model.nconstraints;
  s = sd = sdd = s0 = sd0 = sdd0 = sdd_prev = sd_hat = sdd_hat = VectorXd::Zero(ns);
  a = start_s = start_sd = start_sdd = VectorXd::Zero(ns);
  f = ds = y = scale = VectorXd::Zero(ns);
  rel_A.assign(model.bodies.size(), Matrix3d::Identity());
  rel_p.assign(model.bodies.size(), Vector3d::Zero());
  R = Rd = Ra = Z = MatrixXd::Zero(n, ns);
  force = VectorXd::Zero(n);
  frame_force.assign(model.bodies.size(), Eigen::Matrix<double, 3, 4>::Zero());
  weight = VectorXd::Ones(ns);
  keep = VectorXd::Zero(m);
  for (int bi : t.kept_blocks) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
    keep.segment(b.row0, b.rows).setOnes();
    // A joint placed at its point: its three point rows hold by construction.
    if (b.kind == BlockKind::Joint && t.tree_joint[static_cast<std::size_t>(b.index)] == 2 && b.first == 0) keep.segment(b.row0, 3).setZero();
  }
  for (int i = 0; i < m; ++i)
    if (keep(i) != 0) kept.push_back(i);
  const int k = static_cast<int>(kept.size());
  projY = MatrixXd::Zero(ns, k);
  projS = MatrixXd::Zero(k, k);
  proj_order.assign(static_cast<std::size_t>(k), 0);
  proj_own = proj_w = proj_mu = proj_c = VectorXd::Zero(k);
  Phis = MatrixXd::Zero(m, ns);
  span_lo.assign(t.kept_blocks.size(), 0);
  span_hi.assign(t.kept_blocks.size(), 0);
  Ts = Tm = MatrixXd::Zero(ns, ns);
  scale_m = VectorXd::Ones(ns);
  lu_m.resize(std::max(ns, 1));
  int nb_max = 12;
  for (const Body& b : model.bodies) nb_max = std::max(nb_max, b.ncoord());
  Wb = MatrixXd::Zero(nb_max, nb_max);
  WR = MatrixXd::Zero(nb_max, ns);
  PA = MatrixXd::Zero(m, ns);
  lu.resize(std::max(ns, 1));
  r = sigma = c = VectorXd::Zero(m);
  g = bias = qsave = q_last = qd_last = VectorXd::Zero(n);
}

// The Auto rule: see FORMULATION.md section 18 for the measurements behind it.
Formulation choose_formulation(const Model& m, std::string& why) {
  if (m.settings.adaptive) {
    why = "absolute (solver.formulation \"auto\": the relative formulation takes fixed steps only)";
    return Formulation::Absolute;
  }
  RelativeTree t;
  int ntree = 0, nfree = 0;
  span(m, t, ntree, nfree);
  int n = 0, flexible = 0, modes = 0;
  for (const Body& b : m.bodies) {
    n += b.ncoord();
    if (b.nq > 0) ++flexible, modes += b.nq;
  }
  // Loops: the joints the tree does not place stay constraints (cut joints).
  int cut = 0;
  for (const char c : t.tree_joint) cut += c == 0 ? 1 : 0;
  // Relative when its coordinates are at most a third of the absolute ones in a tree (no cut
  // joint), a fifth with loops. Measured (tools/bench/formulations/RESULTS.md, side by side in one
  // run, per-step CPU time): trees ran faster in relative coordinates at ratios 1/12 (rigid
  // chains) up to 0.26 (five rigid links and a flexible one, 1.4 times), slower from 0.40 (two
  // rigid links and a flexible one: 0.9 times; the vehicle, 0.61: 0.8; flexible links hinged at
  // their nodes, 0.83: 0.56 down to 0.02); with one cut joint (the slider-crank carrying a chain
  // of rigid links) faster at 0.17 (1.1 times) and below, slower from 0.22 (0.9, and 0.6 at 0.33;
  // the flexible slider-crank alone, 0.40: 0.35): the cut joint's rows, projected through R,
  // cost the relative step more. The thresholds lie between those measured ratios.
  const bool rel = n > 0 && (cut == 0 ? 3 * t.ns <= n : 5 * t.ns <= n);
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%d relative coordinates against %d absolute ones; %zu bodies (%d flexible, %d modes), %d placed by joints, %d free, "
                "%d cut joint(s)",
                t.ns, n, m.bodies.size(), flexible, modes, ntree, nfree, cut);
  why = std::string(rel ? "relative" : "absolute") + " (solver.formulation \"auto\": " + buf +
        "; relative when it has at most " + (cut == 0 ? "a third of the absolute coordinates without loops" : "a fifth of the absolute coordinates with loops") +
        ", the measured break-even of FORMULATION.md 18)";
  return rel ? Formulation::Relative : Formulation::Absolute;
}

}  // namespace ffr::runtime
