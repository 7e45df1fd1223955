// Constraint rows of rigid-body conditions, joints and motions (FORMULATION.md section 5).
#include "ffr/runtime/constraints.hpp"

#include "rows.hpp"
#include "weighted_gram.hpp"
#include "../integrator/dense_products.hpp"
#include "../integrator/tangent_blocks.hpp"

#include <cmath>

namespace ffr::runtime {
namespace {

using detail::axis;
using detail::dot;
using detail::dot_jacobian;
using detail::expr;
using detail::point;
using detail::VecExpr;

// One block's rows: values, and its Jacobian written straight into data.Phiq, J1 (J2) being the
// columns of body 1 (2). For a ground side the block has no columns and is never written; a
// joint between two markers of one body gets the same columns twice, and the rows add into them.
struct Rows {
  Eigen::Ref<VectorXd> Phi, Phit, gamma;
  detail::JacobianBlock J1, J2;
  bool jacobian = true;  ///< false: values and biases only, J1 and J2 untouched
  int first = 0;         ///< the block holds the joint's rows [first, first + Phi.size())
  /// The block's own index of the joint's row `row`, or -1 when another block holds it.
  int local(int row) const { return row >= first && row < first + Phi.size() ? row - first : -1; }
};

// A plate's edge supports after its twelve frame rows: scale dir . y[index..] = 0, linear
// (FORMULATION.md 16); a gradient's row is scaled by the model length to be a length.
void plate_support_rows(const Model& model, const Data& data, int body, const AncfPlate& plate, Rows& r) {
  const int y0 = model.bodies[static_cast<std::size_t>(body)].offset + 12;
  for (std::size_t i = 0; i < plate.supports.size(); ++i) {
    const PlateSupportRow& s = plate.supports[i];
    const double scale = s.slope ? model.length : 1.0;
    const int row = 12 + static_cast<int>(i);
    r.Phi(row) = scale * s.dir.dot(data.state.q.segment<3>(y0 + s.index));
    if (r.jacobian) r.J1.block<1, 3>(row, 12 + s.index) = scale * s.dir.transpose();
  }
}

// The six conditions on a body's frame vectors: L/2 (u.u - 1), ..., L u.v, ... (each a length).
void rigid_body_rows(const Model& model, const Data& data, int body, Rows& r) {
  const double L = model.length;
  const BodyData& bd = data.bodies[body];
  if (model.bodies[static_cast<std::size_t>(body)].held_frame()) {
    // A beam's frame is the global frame (its nodal coordinates carry every motion): r0 = 0,
    // L (A - I) = 0, twelve linear rows (FORMULATION.md 15). A beam is never driven.
    r.Phi.head<3>() = data.state.q.segment<3>(model.bodies[static_cast<std::size_t>(body)].offset);
    for (int a = 0; a < 3; ++a) r.Phi.segment<3>(3 + 3 * a) = L * (bd.A.col(a) - Matrix3d::Identity().col(a));
    r.gamma.setZero();
    r.Phit.setZero();
    if (const auto& plate = model.bodies[static_cast<std::size_t>(body)].plate) plate_support_rows(model, data, body, *plate, r);
    if (!r.jacobian) return;
    r.J1.block<3, 3>(0, 0).diagonal().setConstant(1.0);
    for (int k = 3; k < 12; ++k) r.J1(k, k) = L;
    return;
  }
  const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
  for (int i = 0; i < 6; ++i) {
    const int a = pairs[i][0], b = pairs[i][1];
    const bool diag = a == b;
    const double s = diag ? 0.5 * L : L;
    r.Phi(i) = s * (bd.A.col(a).dot(bd.A.col(b)) - (diag ? 1.0 : 0.0));
    r.gamma(i) = 2 * s * bd.Ad.col(a).dot(bd.Ad.col(b));
    if (!integrated(data, body)) {
      // A driven body's frame: no unknowns, so its rate is all Phi_t and its acceleration all gamma.
      r.Phit(i) = s * (bd.Ad.col(a).dot(bd.A.col(b)) + bd.A.col(a).dot(bd.Ad.col(b)));
      r.gamma(i) += s * (bd.Add.col(a).dot(bd.A.col(b)) + bd.A.col(a).dot(bd.Add.col(b)));
      continue;
    }
    if (!r.jacobian) continue;
    r.J1.block<1, 3>(i, 3 + 3 * a) += s * bd.A.col(b).transpose();
    r.J1.block<1, 3>(i, 3 + 3 * b) += s * bd.A.col(a).transpose();
  }
}

struct JointSides {
  const MarkerData* m1;
  const MarkerData* m2;
  bool g1, g2;
};

// A side is fixed when its body has no unknowns: the ground, or a driven body (whose markers'
// rates then enter Phi_t and whose accelerations are in their biases, kinematics.hpp).
JointSides sides(const Model& model, const Data& data, const Joint& j) {
  return {&data.markers[j.m1], &data.markers[j.m2], !integrated(data, model.markers[j.m1].body),
          !integrated(data, model.markers[j.m2].body)};
}

void dot_row(const VecExpr& a, const VecExpr& b, double scale, Rows& r, int joint_row) {
  const int row = r.local(joint_row);
  if (row < 0) return;
  const auto v = dot(a, b);
  r.Phi(row) = scale * v.value;
  r.Phit(row) = scale * v.given;
  r.gamma(row) = scale * v.bias;
  if (r.jacobian) dot_jacobian(a, b, scale, r.J1, r.J2, row);
}

void coincident_points(const JointSides& s, Rows& r, int row) {
  eigen_assert(r.first == 0);  // only prismatic joints are split
  r.Phi.segment<3>(row) = s.m2->p - s.m1->p;
  r.gamma.segment<3>(row) = s.m2->pb - s.m1->pb;
  if (s.g2) r.Phit.segment<3>(row) += s.m2->pd;
  if (s.g1) r.Phit.segment<3>(row) -= s.m1->pd;
  if (!r.jacobian) return;
  if (!s.g1) r.J1.middleRows(row, 3) -= s.m1->Jp;
  if (!s.g2) r.J2.middleRows(row, 3) += s.m2->Jp;
}

void joint_rows(const Model& model, const Data& data, const Joint& j, Rows& r) {
  const double L = model.length;
  const JointSides s = sides(model, data, j);
  auto e1 = [&](int k) { return expr(axis(*s.m1, k, 1, s.g1)); };
  auto e2 = [&](int k) { return expr(axis(*s.m2, k, 2, s.g2)); };
  const VecExpr d = expr(point(*s.m2, 2, s.g2), point(*s.m1, 1, s.g1, -1.0));
  switch (j.type) {
    case JointType::Spherical:
      coincident_points(s, r, 0);
      break;
    case JointType::Revolute:
      coincident_points(s, r, 0);
      dot_row(e1(0), e2(1), L, r, 3);
      dot_row(e1(0), e2(2), L, r, 4);
      break;
    case JointType::Universal:
      coincident_points(s, r, 0);
      dot_row(e1(0), e2(0), L, r, 3);
      break;
    case JointType::Fixed:
      coincident_points(s, r, 0);
      dot_row(e1(0), e2(1), L, r, 3);
      dot_row(e1(0), e2(2), L, r, 4);
      dot_row(e1(1), e2(2), L, r, 5);
      break;
    case JointType::Cylindrical:
    case JointType::Prismatic:
      // The translational rows first (a block may hold them alone, see ConstraintBlock::first).
      dot_row(d, e1(1), 1.0, r, 0);
      dot_row(d, e1(2), 1.0, r, 1);
      dot_row(e1(0), e2(1), L, r, 2);
      dot_row(e1(0), e2(2), L, r, 3);
      if (j.type == JointType::Prismatic) dot_row(e1(1), e2(2), L, r, 4);
      break;
  }
}

double unwrap(double raw, double ref) { return raw + 2 * M_PI * std::round((ref - raw) / (2 * M_PI)); }

// Coordinate value, rate and bias; with jac, adds scale * gradient to row `row`. The joint's
// markers 1 and 2 add to the block's columns of sides side1 and side2 (a coupler's block holds
// two joints, whose bodies need not be its body1 and body2 in that order).
detail::DotValue coordinate(const Model& model, const Data& data, int joint, JointCoordinate c, Rows* r, int row,
                            double scale, int side1 = 1, int side2 = 2) {
  const Joint& j = model.joints[joint];
  const JointSides s = sides(model, data, j);
  if (c == JointCoordinate::Displacement) {
    const VecExpr d = expr(point(*s.m2, side2, s.g2), point(*s.m1, side1, s.g1, -1.0));
    const VecExpr e = expr(axis(*s.m1, 0, side1, s.g1));
    if (r) dot_jacobian(d, e, scale, r->J1, r->J2, row);
    auto v = dot(d, e);
    v.value -= j.d0;
    return v;
  }
  // theta = atan2(g1.f2, f1.f2): the rotation of marker 2's f axis about marker 1's e axis.
  const VecExpr f2 = expr(axis(*s.m2, 1, side2, s.g2));
  const VecExpr f1 = expr(axis(*s.m1, 1, side1, s.g1)), g1 = expr(axis(*s.m1, 2, side1, s.g1));
  const auto x = dot(f1, f2), y = dot(g1, f2);
  const double rho2 = x.value * x.value + y.value * y.value;
  if (r) {
    dot_jacobian(g1, f2, scale * x.value / rho2, r->J1, r->J2, row);
    dot_jacobian(f1, f2, -scale * y.value / rho2, r->J1, r->J2, row);
  }
  const double th = unwrap(std::atan2(y.value, x.value), data.state.angle_ref[joint]);
  const double thd = (x.value * y.rate - y.value * x.rate) / rho2;
  const double bias = (x.value * y.bias - y.value * x.bias) / rho2 - 2 * thd * (x.value * x.rate + y.value * y.rate) / rho2;
  return {th, thd, bias, (x.value * y.given - y.value * x.given) / rho2};
}

void motion_row(const Model& model, const Data& data, int m, double t, Rows& r) {
  const Motion& mo = model.motions[m];
  const double scale = mo.coordinate == JointCoordinate::Angle ? model.length : 1.0;
  const auto v = coordinate(model, data, mo.joint, mo.coordinate, r.jacobian ? &r : nullptr, 0, scale);
  const Vector3d target = motion_target(model, data, m, t);
  r.Phi(0) = scale * (v.value - target(0));
  r.Phit(0) = scale * (v.given - target(1));
  r.gamma(0) = scale * (v.bias - target(2));
}

detail::JacobianBlock block_columns(const Model& model, Data& data, const ConstraintBlock& b, int body);

// A coupler's row w (theta1 - ratio theta2): the two coordinates' rows added, each joint's
// gradient into its own two bodies' columns (the block may touch four bodies: two shafts in a
// moving carrier, or each in its own housing).
void coupler_row(const Model& model, Data& data, const ConstraintBlock& b, Rows& r) {
  const Coupler& c = model.couplers[b.index];
  const double w = c.c1 == JointCoordinate::Angle ? model.length : 1.0;
  r.Phi(0) = r.Phit(0) = r.gamma(0) = 0;
  const int joints[2] = {c.joint1, c.joint2};
  const JointCoordinate coords[2] = {c.c1, c.c2};
  const double scales[2] = {w, -w * c.ratio};
  for (int k = 0; k < 2; ++k) {
    const Joint& j = model.joints[joints[k]];
    Rows rk{r.Phi, r.Phit, r.gamma, block_columns(model, data, b, model.markers[j.m1].body),
            block_columns(model, data, b, model.markers[j.m2].body), r.jacobian, 0};
    const auto v = coordinate(model, data, joints[k], coords[k], r.jacobian ? &rk : nullptr, 0, scales[k], 1, 2);
    r.Phi(0) += scales[k] * v.value;
    r.Phit(0) += scales[k] * v.given;
    r.gamma(0) += scales[k] * v.bias;
  }
}

// The body's columns of a block's rows in data.Phiq (none for the ground or a driven body).
detail::JacobianBlock block_columns(const Model& model, Data& data, const ConstraintBlock& b, int body) {
  if (!integrated(data, body)) return data.Phiq.block(b.row0, 0, b.rows, 0);
  const Body& B = model.bodies[body];
  return data.Phiq.block(b.row0, B.offset, b.rows, B.ncoord());
}

}  // namespace

Vector3d motion_target(const Model& model, const Data& data, int m, double t) {
  if (data.motion_external[m]) return data.motion_value[m];
  Vector3d v;
  const Motion& mo = model.motions[m];
  if (mo.speed) {
    double d2;
    mo.table.eval(t, 0, v(1), v(2), d2);
    v(0) = mo.table.integral(t, 0) - mo.table.integral(mo.start, 0);
    return v;
  }
  mo.table.eval(t, 0, v(0), v(1), v(2));
  return v;
}

namespace {

// The column ranges [first, first + count) of a block's distinct integrated bodies (a joint
// within one body counts it once: its rows are in Phiq once, see Rows). Phiq is zero outside
// the blocks' rows and these columns.
struct BlockColumns {
  int ranges = 0;
  int first[4], count[4];
};

BlockColumns block_column_ranges(const Model& model, const Data& data, const ConstraintBlock& b) {
  BlockColumns c;
  for (int body : {b.body1, b.body2, b.body3, b.body4}) {  // (a coupler may join four)
    if (!integrated(data, body)) continue;
    const Body& B = model.bodies[static_cast<std::size_t>(body)];
    bool seen = false;
    for (int k = 0; k < c.ranges; ++k) seen = seen || c.first[k] == B.offset;
    if (seen) continue;
    c.first[c.ranges] = B.offset;
    c.count[c.ranges] = B.ncoord();
    ++c.ranges;
  }
  return c;
}

void evaluate_rows(const Model& model, Data& data, double t, bool jacobian, bool all_blocks) {
  // The Jacobian is stored dense, the blocks adding into it, and zero outside the blocks' rows
  // and their bodies' columns (block_column_ranges; set_unknowns clears it whole when the
  // bodies in use change): only those are cleared, each block's just before it is written. (A system of many bodies, such as a
  // geometrically exact beam's node bodies, touches a few percent of the dense matrix.)
  // With all_blocks, every block's values: those among driven bodies hold by construction,
  // and their values check that (step(), once a step); only the blocks of the unknowns have
  // Jacobian columns. Otherwise the blocks of the unknowns alone: the projections' biases
  // (nothing reads the others' rates) and the later iterates of a step (the others' values do
  // not change within it).
  const bool by_block = data.block_columns_pay;
  if (jacobian && !by_block) data.Phiq.setZero();
  const std::size_t nb = all_blocks ? model.blocks.size() : static_cast<std::size_t>(data.nblocks);
  if (all_blocks)
    data.Phit.setZero();
  else
    data.Phit.head(data.na).setZero();
  for (std::size_t bi = 0; bi < nb; ++bi) {
    const ConstraintBlock& b = model.blocks[bi];
    const bool active = static_cast<int>(bi) < data.nblocks;
    if (jacobian && active && by_block) {
      const BlockColumns c = block_column_ranges(model, data, b);
      for (int k = 0; k < c.ranges; ++k) data.Phiq.block(b.row0, c.first[k], b.rows, c.count[k]).setZero();
    }
    Rows r{data.Phi.segment(b.row0, b.rows), data.Phit.segment(b.row0, b.rows), data.gamma.segment(b.row0, b.rows),
           block_columns(model, data, b, b.body1), block_columns(model, data, b, b.body2), jacobian && active, b.first};
    switch (b.kind) {
      case BlockKind::RigidBody: rigid_body_rows(model, data, b.index, r); break;
      case BlockKind::Joint: joint_rows(model, data, model.joints[b.index], r); break;
      case BlockKind::Motion: motion_row(model, data, b.index, t, r); break;
      case BlockKind::Coupler: coupler_row(model, data, b, r); break;
    }
  }
}

}  // namespace

// The blocks' rows times their bodies' columns against the whole na x nf Jacobian: below half,
// the passes block by block are cheaper than the dense ones (not so on a model of a few large
// bodies, whose blocks span most of it).
bool detail::decide_block_columns_pay(const Model& model, const Data& data) {
  long area = 0;
  for (int bi = 0; bi < data.nblocks; ++bi) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
    const BlockColumns c = block_column_ranges(model, data, b);
    for (int k = 0; k < c.ranges; ++k) area += static_cast<long>(b.rows) * c.count[k];
  }
  return 2 * area < static_cast<long>(data.na) * data.nf;
}

void evaluate_constraints(const Model& model, Data& data, double t, Scope scope) {
  evaluate_rows(model, data, t, true, scope == Scope::All);
}

void evaluate_constraint_biases(const Model& model, Data& data, double t) { evaluate_rows(model, data, t, false, false); }

double joint_coordinate(const Model& model, const Data& data, int joint, JointCoordinate c) {
  return coordinate(model, data, joint, c, nullptr, 0, 1.0).value;
}

double joint_coordinate_rate(const Model& model, const Data& data, int joint, JointCoordinate c) {
  return coordinate(model, data, joint, c, nullptr, 0, 1.0).rate;
}

void update_angle_references(const Model& model, Data& data) {
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const JointType t = model.joints[j].type;
    if (t == JointType::Revolute || t == JointType::Cylindrical)
      data.state.angle_ref[j] = joint_coordinate(model, data, static_cast<int>(j), JointCoordinate::Angle);
  }
}

// The products go block by block over the blocks' bodies' columns (block_column_ranges): a
// row touches the coordinates of its bodies alone, so the dense m x n products did mostly
// multiplications by zero on models of many bodies.
void add_constraint_forces(const Model& model, const Data& data, const VectorXd& lam, VectorXd& out) {
  if (!data.block_columns_pay) {
    detail::add_transpose_times(data.Phiq, data.na, data.nf, lam, out);
    return;
  }
  const Eigen::Index ld = data.Phiq.rows();
  for (int bi = 0; bi < data.nblocks; ++bi) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
    const BlockColumns c = block_column_ranges(model, data, b);
    const double* l = lam.data() + b.row0;
    for (int k = 0; k < c.ranges; ++k) {
      const double* J = data.Phiq.data() + c.first[k] * ld + b.row0;
      double* y = out.data() + c.first[k];
      for (int j = 0; j < c.count[k]; ++j) {  // one short dot product a column
        double s = 0.0;
        for (int i = 0; i < b.rows; ++i) s += J[j * ld + i] * l[i];
        y[j] += s;
      }
    }
  }
}

void constraint_times(const Model& model, const Data& data, const VectorXd& v, VectorXd& out) {
  if (!data.block_columns_pay) {
    detail::times(data.Phiq, data.na, data.nf, v, out, false);
    out.tail(out.size() - data.na).setZero();  // the rows among driven bodies have no unknowns
    return;
  }
  const Eigen::Index ld = data.Phiq.rows();
  out.setZero();  // (the rows among driven bodies have no unknowns)
  for (int bi = 0; bi < data.nblocks; ++bi) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
    const BlockColumns c = block_column_ranges(model, data, b);
    for (int k = 0; k < c.ranges; ++k)
      detail::times(data.Phiq.data() + c.first[k] * ld + b.row0, ld, b.rows, c.count[k], v.data() + c.first[k],
                    out.data() + b.row0, true);
  }
}

namespace {

// The first and last of the n columns of the rows x n block J (leading dimension ld) that have a
// nonzero entry (lo > hi when none).
void nonzero_columns(const double* J, Eigen::Index ld, int rows, int n, int& lo, int& hi) {
  const auto zero = [&](int c) {
    for (int r = 0; r < rows; ++r)
      if (J[r + c * ld] != 0.0) return false;
    return true;
  };
  lo = 0;
  hi = n - 1;
  while (lo <= hi && zero(lo)) ++lo;
  while (hi >= lo && zero(hi)) --hi;
}

}  // namespace

void add_penalty_tangent(const Model& model, Data& data, const VectorXd& alpha, double f, MatrixXd& T) {
  const Eigen::Index ld = data.Phiq.rows();
  double* buf = data.Jw.data();  // rows_max x (a body's coordinates) doubles of work space
  for (int bi = 0; bi < data.nblocks; ++bi) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
    const auto J1 = block_columns(model, data, b, b.body1);
    double* w = data.penalty_rows.data();
    for (int r = 0; r < b.rows; ++r) w[r] = f * alpha(b.row0 + r);
    // Side a's rows weighted once (buf, from its column fa), then its products with each side's
    // columns from column fb: T(oa + fa.., ob + fb..) += Ja^T diag(w) Jb.
    const auto weigh = [&](const detail::JacobianBlock& Ja, int fa, int na) {
      detail::weight_rows(Ja.data() + fa * ld, ld, b.rows, na, w, buf);
    };
    const auto add = [&](const detail::JacobianBlock& Jb, int oa, int fa, int na, int ob, int fb, int nb) {
      detail::add_weighted_product(buf, b.rows, na, Jb.data() + fb * ld, ld, nb, &T(oa + fa, ob + fb), T.rows());
    };
    if (b.kind == BlockKind::RigidBody && model.bodies[b.body1].held_frame()) {
      // A beam's or plate's held frame: its twelve frame columns.
      const int o = model.bodies[b.body1].offset;
      weigh(J1, 0, 12);
      add(J1, o, 0, 12, o, 0, 12);
      // A plate's support rows, each a multiple of three of its coordinates (the products above
      // take the block's first twelve columns, where these rows are zero).
      if (const auto& plate = model.bodies[b.body1].plate)
        for (std::size_t i = 0; i < plate->supports.size(); ++i) {
          const PlateSupportRow& s = plate->supports[i];
          const double scale = s.slope ? model.length : 1.0;
          const int k = o + 12 + s.index;
          T.block<3, 3>(k, k).noalias() += (w[12 + i] * scale * scale) * s.dir * s.dir.transpose();
        }
      continue;
    }
    if (b.kind == BlockKind::RigidBody) {
      // Only the frame-vector columns are nonzero.
      const int o = model.bodies[b.body1].offset;
      weigh(J1, 3, 9);
      add(J1, o, 3, 9, o, 3, 9);
      continue;
    }
    // The block's distinct integrated bodies (a joint's two, a coupler's up to four): the
    // rows of a joint within one body are in Phiq once, so each body counts once. Each body's
    // columns from its first to its last nonzero one: a joint on a node of a beam or of a
    // flexible body reaches a few of the body's columns (on a 16-element ancf beam 18 of 114,
    // whose whole square product was a twentieth of its step).
    int bodies[4], lo[4], hi[4], nbod = 0;
    for (int body : {b.body1, b.body2, b.body3, b.body4}) {
      if (!integrated(data, body)) continue;
      bool seen = false;
      for (int k = 0; k < nbod; ++k) seen = seen || bodies[k] == body;
      if (seen) continue;
      const detail::JacobianBlock J = block_columns(model, data, b, body);
      nonzero_columns(J.data(), ld, b.rows, unknown_columns(model, data, body), lo[nbod], hi[nbod]);
      bodies[nbod++] = body;
    }
    for (int ia = 0; ia < nbod; ++ia) {
      if (hi[ia] < lo[ia]) continue;
      const int oa = model.bodies[bodies[ia]].offset, na = hi[ia] - lo[ia] + 1;
      weigh(block_columns(model, data, b, bodies[ia]), lo[ia], na);
      for (int ib = 0; ib < nbod; ++ib)
        if (hi[ib] >= lo[ib])
          add(block_columns(model, data, b, bodies[ib]), oa, lo[ia], na, model.bodies[bodies[ib]].offset, lo[ib],
              hi[ib] - lo[ib] + 1);
    }
  }
}

void penalty_weights(const Model& model, const Data& data, const MatrixXd& W, double factor, VectorXd& alpha) {
  // One penalty for all rows, relative to the mean body mass. (A per-row penalty scaled to the
  // tangent's stiffness along each row was tried: rows touching stiff modes then get penalties
  // so large that the augmented multipliers swing and Newton needs more iterations, not fewer.)
  (void)data;
  (void)W;
  alpha.setConstant(factor * model.mass);
}

}  // namespace ffr::runtime
