// Second derivatives of the constraints, sum_i lambda_i d2Phi_i/dq2: the "geometric stiffness" of
// the constraint forces Phi_q^T lambda in the Newton tangent. Without it Newton converges only
// linearly once the multipliers are large (fast rotation: the frame vectors' normalisation rows
// carry the centrifugal load), with it quadratically.
//   a . b:         J_a^T J_b + J_b^T J_a + H_a(b) + H_b(a)     (H_x(f) = d(J_x^T f)/dz)
//   e_i . (p2-p1): H_p2(e_i) - H_p1(e_i)
//   atan2(y, x):   (x H_y - y H_x + g_x^T g_y - g_y^T g_x) / r^2 - 2 (x g_x + y g_y)^T N / r^4,
//                  N = x g_y - y g_x
#include "ffr/runtime/constraints.hpp"

#include "../bodies/plate_triad.hpp"
#include "../forces/force_helpers.hpp"
#include "weighted_gram.hpp"

namespace ffr::runtime {
namespace {

// A marker quantity (point or axis) with its Jacobian and mode slice (null when rigid on its frame).
struct Quantity {
  const Vector3d* v = nullptr;
  const Matrix3N* J = nullptr;
  const Matrix3Xd* S = nullptr;
  int side = 0;
  double sign = 1;
  /// An axis of a plate node's exact triad (Marker::triad): its second derivatives are the
  /// triad's, not a constant slice's.
  const Marker* triad = nullptr;
  int axis = 0;
  const Matrix3d* A = nullptr;
  const double* y = nullptr;
};

struct Expr {
  Quantity t[2];
  int n = 0;
  Vector3d value() const {
    Vector3d s = Vector3d::Zero();
    for (int i = 0; i < n; ++i) s += t[i].sign * *t[i].v;
    return s;
  }
};

// Where the two sides' coordinates sit in the target matrix, and work space for the products
// (3 x a body's coordinates doubles).
struct Target {
  MatrixXd* M;
  int off[3] = {0, 0, 0};
  int nb[3] = {0, 0, 0};
  double* buf = nullptr;
};

Quantity quantity(const Model& model, const Data& data, int marker, int k, int side, double sign = 1) {
  const Marker& mk = model.markers[marker];
  const MarkerData& md = data.markers[marker];
  Quantity q;
  q.side = side;
  q.sign = sign;
  q.v = k < 0 ? &md.p : &md.e[k];
  if (!integrated(data, mk.body)) return q;  // the ground or a driven body: no unknowns
  q.J = k < 0 ? &md.Jp : &md.Je[k];
  if (detail::on_node(model, mk) && k >= 0 && mk.triad >= 0) {
    q.triad = &mk;
    q.axis = k;
    q.A = &data.bodies[mk.body].A;
    q.y = data.state.q.data() + model.bodies[mk.body].offset + 12;
    return q;
  }
  if (detail::on_node(model, mk)) q.S = &detail::slice(mk, k);
  return q;
}

// c * d(J^T f)/dz of a triad axis e = A ebar(y), ebar = T(r_x, r_y) R_k: the frame-y products
// (the y columns are A G, G = d ebar / d(r_x, r_y), as add_jt_f_derivative's A S) and the y-y
// block f . A D2ebar (plate_triad.hpp).
void add_triad(Target& T, const Quantity& q, const Vector3d& f, double c) {
  const Marker& mk = *q.triad;
  detail::PlateTriad tr;
  detail::plate_triad(mk.triad_x0 + Eigen::Map<const Vector3d>(q.y + mk.triad),
                      mk.triad_y0 + Eigen::Map<const Vector3d>(q.y + mk.triad + 3), tr);
  detail::Matrix36 G;
  detail::triad_axis(tr, mk.triad_R.col(q.axis), &G);
  detail::Matrix66 H;
  detail::triad_axis_hessian(tr, mk.triad_R.col(q.axis), q.A->transpose() * f, H);
  const double s = c * q.sign;
  auto M = T.M->block(T.off[q.side], T.off[q.side], T.nb[q.side], T.nb[q.side]);
  const int y0 = 12 + mk.triad;
  for (int j = 0; j < 6; ++j)
    for (int a = 0; a < 3; ++a) {
      M.block<3, 1>(3 + 3 * a, y0 + j) += (s * G(a, j)) * f;
      M.block<1, 3>(y0 + j, 3 + 3 * a) += (s * G(a, j)) * f.transpose();
    }
  M.block<6, 6>(y0, y0) += s * H;
}

Expr one(Quantity a) {
  Expr e;
  e.t[0] = a;
  e.n = 1;
  return e;
}
Expr two(Quantity a, Quantity b) {
  Expr e;
  e.t[0] = a;
  e.t[1] = b;
  e.n = 2;
  return e;
}

void add_node(Target& T, const Quantity& q, const Vector3d& f, double c) {
  if (q.triad && c != 0) add_triad(T, q, f, c);
  if (!q.S || c == 0) return;
  detail::add_jt_f_derivative(*q.S, f, c * q.sign, T.M->block(T.off[q.side], T.off[q.side], T.nb[q.side], T.nb[q.side]));
}

void dot_hessian(Target& T, const Expr& a, const Expr& b, double c) {
  if (c == 0) return;
  for (int i = 0; i < a.n; ++i)
    for (int j = 0; j < b.n; ++j) {
      const Quantity &x = a.t[i], &y = b.t[j];
      if (!x.J || !y.J) continue;
      // J_x^T J_y and its transpose, rank-3 updates by the kernel of the penalty tangent
      // (Eigen's GEMM packed these small operands: 4 % of a step).
      const double s = c * x.sign * y.sign, w[3] = {s, s, s};
      const int nx = T.nb[x.side], ny = T.nb[y.side];
      const Eigen::Index ld = T.M->rows();
      detail::add_weighted_gram(x.J->data(), y.J->data(), 3, 3, nx, ny, w, T.buf, &(*T.M)(T.off[x.side], T.off[y.side]), ld);
      detail::add_weighted_gram(y.J->data(), x.J->data(), 3, 3, ny, nx, w, T.buf, &(*T.M)(T.off[y.side], T.off[x.side]), ld);
    }
  const Vector3d av = a.value(), bv = b.value();
  for (int i = 0; i < a.n; ++i) add_node(T, a.t[i], bv, c);
  for (int j = 0; j < b.n; ++j) add_node(T, b.t[j], av, c);
}

// Gradient row of a . b over [side 1, side 2] columns (for the angle row's products).
void dot_gradient(const Target& T, const Expr& a, const Expr& b, Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> g) {
  const Vector3d av = a.value(), bv = b.value();
  for (int i = 0; i < a.n; ++i)
    if (a.t[i].J) g.segment(T.off[a.t[i].side], T.nb[a.t[i].side]).noalias() += a.t[i].sign * bv.transpose() * *a.t[i].J;
  for (int j = 0; j < b.n; ++j)
    if (b.t[j].J) g.segment(T.off[b.t[j].side], T.nb[b.t[j].side]).noalias() += b.t[j].sign * av.transpose() * *b.t[j].J;
}

void joint_hessian(const Model& model, const Data& data, const Joint& j, const Eigen::Ref<const VectorXd>& l, Target& T) {
  const double L = model.length;
  auto e1 = [&](int k) { return one(quantity(model, data, j.m1, k, 1)); };
  auto e2 = [&](int k) { return one(quantity(model, data, j.m2, k, 2)); };
  const Expr d = two(quantity(model, data, j.m2, -1, 2), quantity(model, data, j.m1, -1, 1, -1.0));
  auto points = [&](int row) {
    const Vector3d lv = l.segment<3>(row);
    add_node(T, quantity(model, data, j.m2, -1, 2), lv, 1.0);
    add_node(T, quantity(model, data, j.m1, -1, 1), lv, -1.0);
  };
  switch (j.type) {
    case JointType::Spherical:
      points(0);
      break;
    case JointType::Revolute:
      points(0);
      dot_hessian(T, e1(0), e2(1), L * l(3));
      dot_hessian(T, e1(0), e2(2), L * l(4));
      break;
    case JointType::Universal:
      points(0);
      dot_hessian(T, e1(0), e2(0), L * l(3));
      break;
    case JointType::Fixed:
      points(0);
      dot_hessian(T, e1(0), e2(1), L * l(3));
      dot_hessian(T, e1(0), e2(2), L * l(4));
      dot_hessian(T, e1(1), e2(2), L * l(5));
      break;
    case JointType::Cylindrical:
    case JointType::Prismatic:
      // Rows as in constraints.cpp; a block holding some of them has zeros for the others.
      if (l(0) != 0.0) dot_hessian(T, d, e1(1), l(0));
      if (l(1) != 0.0) dot_hessian(T, d, e1(2), l(1));
      if (l(2) != 0.0) dot_hessian(T, e1(0), e2(1), L * l(2));
      if (l(3) != 0.0) dot_hessian(T, e1(0), e2(2), L * l(3));
      if (j.type == JointType::Prismatic && l(4) != 0.0) dot_hessian(T, e1(1), e2(2), L * l(4));
      break;
  }
}

// lam times the second derivative of a joint coordinate (scaled by the model length for an
// angle), its markers 1 and 2 on the target's sides s1 and s2.
void coordinate_hessian(const Model& model, Data& data, int joint, JointCoordinate coord, double lam, Target& T, int s1,
                        int s2) {
  const Joint& j = model.joints[joint];
  if (coord == JointCoordinate::Displacement) {
    const Expr d = two(quantity(model, data, j.m2, -1, s2), quantity(model, data, j.m1, -1, s1, -1.0));
    dot_hessian(T, d, one(quantity(model, data, j.m1, 0, s1)), lam);
    return;
  }
  // Angle row L (theta - target): build g_x, g_y, H_x, H_y over [z1, z2] in the work buffers.
  const int n = T.nb[1] + T.nb[2];
  Target local{&data.cH, {0, 0, T.nb[1]}, {0, T.nb[1], T.nb[2]}, T.buf};
  const Expr f2 = one(quantity(model, data, j.m2, 1, s2));
  const Expr f1 = one(quantity(model, data, j.m1, 1, s1)), g1 = one(quantity(model, data, j.m1, 2, s1));
  const double x = f1.value().dot(f2.value()), y = g1.value().dot(f2.value()), r2 = x * x + y * y;
  auto gx = data.cg.row(0).head(n);
  auto gy = data.cg.row(1).head(n);
  gx.setZero();
  gy.setZero();
  dot_gradient(local, f1, f2, gx);
  dot_gradient(local, g1, f2, gy);
  auto H = data.cH.topLeftCorner(n, n);
  H.setZero();
  dot_hessian(local, g1, f2, x / r2);   // x H_y / r^2
  dot_hessian(local, f1, f2, -y / r2);  // -y H_x / r^2
  H.noalias() += (1.0 / r2) * gx.transpose() * gy;
  H.noalias() -= (1.0 / r2) * gy.transpose() * gx;
  auto N = data.cg.row(2).head(n);
  auto w = data.cg.row(3).head(n);
  N = x * gy - y * gx;
  w = x * gx + y * gy;
  H.noalias() -= (2.0 / (r2 * r2)) * w.transpose() * N;
  const double c = lam * model.length;
  for (int a = 1; a <= 2; ++a)
    for (int b = 1; b <= 2; ++b)
      if (T.nb[a] && T.nb[b]) T.M->block(T.off[a], T.off[b], T.nb[a], T.nb[b]) += c * H.block(local.off[a], local.off[b], T.nb[a], T.nb[b]);
}

void motion_hessian(const Model& model, Data& data, const Motion& mo, double lam, Target& T) {
  coordinate_hessian(model, data, mo.joint, mo.coordinate, lam, T, 1, 2);
}

// A coupler's row w (theta1 - ratio theta2): the two coordinates' Hessians (an angle's carries
// the model length itself, coordinate_hessian), each over its own joint's two bodies (the
// coupler may touch four: two shafts in a moving carrier, or each in its own housing).
void coupler_hessian(const Model& model, Data& data, const ConstraintBlock& b, double lam, Target& T) {
  const Coupler& c = model.couplers[b.index];
  const double w = c.c1 == JointCoordinate::Angle ? 1.0 : 1.0 / model.length;  // the row's w over the length
  const int joints[2] = {c.joint1, c.joint2};
  const JointCoordinate coords[2] = {c.c1, c.c2};
  const double scales[2] = {w, -w * c.ratio};
  for (int k = 0; k < 2; ++k) {
    const Joint& j = model.joints[joints[k]];
    Target Tk = T;
    const int bs[3] = {kGround, model.markers[j.m1].body, model.markers[j.m2].body};
    for (int side = 1; side <= 2; ++side) {
      const bool h = integrated(data, bs[side]);
      Tk.off[side] = h ? model.bodies[bs[side]].offset : 0;
      Tk.nb[side] = h ? unknown_columns(model, data, bs[side]) : 0;
    }
    // coordinate_hessian scales an angle by the length and leaves a displacement as it is.
    const double s = coords[k] == JointCoordinate::Angle ? scales[k] : scales[k] * model.length;
    coordinate_hessian(model, data, joints[k], coords[k], lam * s, Tk, 1, 2);
  }
}

}  // namespace

void add_constraint_hessian(const Model& model, Data& data, const VectorXd& lam, double factor, MatrixXd& M) {
  for (int bi = 0; bi < data.nblocks; ++bi) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
    const auto l = lam.segment(b.row0, b.rows);
    if (b.kind == BlockKind::RigidBody && model.bodies[b.body1].held_frame()) continue;  // linear rows
    if (b.kind == BlockKind::RigidBody) {
      const int o = model.bodies[b.body1].offset + 3;
      const double L = model.length;
      const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
      for (int i = 0; i < 6; ++i) {
        const int a = pairs[i][0], c = pairs[i][1];
        const double s = factor * l(i) * L;  // (L/2) d2(u.u) = L I;  L d2(u.v) = L I off-diagonal
        M.block<3, 3>(o + 3 * a, o + 3 * c).diagonal().array() += s;
        if (a != c) M.block<3, 3>(o + 3 * c, o + 3 * a).diagonal().array() += s;
      }
      continue;
    }
    Target T{&M};
    T.buf = data.Jw.data();  // rows_max (>= 6) x (a body's coordinates) doubles
    const bool h1 = integrated(data, b.body1), h2 = integrated(data, b.body2);
    T.off[1] = h1 ? model.bodies[b.body1].offset : 0;
    T.off[2] = h2 ? model.bodies[b.body2].offset : 0;
    T.nb[1] = h1 ? unknown_columns(model, data, b.body1) : 0;
    T.nb[2] = h2 ? unknown_columns(model, data, b.body2) : 0;
    if (b.kind == BlockKind::Joint) {
      // The joint's rows, those of other blocks (a split joint, ConstraintBlock::first) zero.
      const Joint& j = model.joints[b.index];
      const int n = joint_rows(j.type);
      data.cl.head(n).setZero();
      data.cl.segment(b.first, b.rows) = factor * l;
      joint_hessian(model, data, j, data.cl.head(n), T);
    } else if (b.kind == BlockKind::Coupler) {
      coupler_hessian(model, data, b, factor * l(0), T);
    } else {
      motion_hessian(model, data, model.motions[b.index], factor * l(0), T);
    }
  }
}

}  // namespace ffr::runtime
