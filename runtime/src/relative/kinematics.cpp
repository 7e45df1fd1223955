// The recursion q(s), q_dot = R s_dot, q_ddot = R s_ddot + R_dot s_dot (relative.hpp).
//
// A tree body c on parent p (frame r_p, A_p; the ground: 0, I) through a joint whose parent
// marker is at c_p with triad E_p (body frame of p; global for the ground), with angle th about
// the marker's axis e and slide x along it:
//   A_c = A_p N,  N = E_p Rx(th) rel_A
//   r_c = r_p + A_p k,  k = c_p + E_p (Rx(th) rel_p + x e_x)
// Natural coordinates make this linear in the parent's (A_p, r_p): its derivatives with respect
// to the parent's coordinates are the same map applied to their changes, and the rates and
// accelerations follow by the product rule (FORMULATION.md 18).
#include "ffr/runtime/relative.hpp"

#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/kinematics.hpp"

#include <cmath>

namespace ffr::runtime {
namespace {

Matrix3d rot_x(double th, int derivative) {
  const double c = std::cos(th), s = std::sin(th);
  Matrix3d r = Matrix3d::Zero();
  switch (derivative) {
    case 0: r << 1, 0, 0, 0, c, -s, 0, s, c; break;
    case 1: r << 0, 0, 0, 0, -s, -c, 0, c, -s; break;
    default: r << 0, 0, 0, 0, -c, s, 0, -s, -c; break;
  }
  return r;
}

// The frame of coordinates q at offset o: r0 and A = [u v w].
Vector3d pos(const VectorXd& q, int o) { return q.segment<3>(o); }
Matrix3d frame(const VectorXd& q, int o) { return Eigen::Map<const Matrix3d>(q.data() + o + 3); }
void set(VectorXd& q, int o, const Vector3d& r, const Matrix3d& A) {
  q.segment<3>(o) = r;
  Eigen::Map<Matrix3d>(q.data() + o + 3) = A;
}

// S y for a marker's 3 x nq mode slice (column by column: no temporary).
Vector3d slice_times(const Matrix3Xd& S, const double* y) {
  Vector3d v = Vector3d::Zero();
  for (Eigen::Index k = 0; k < S.cols(); ++k) v += S.col(k) * y[k];
  return v;
}

// A body placed at a point (RelativeBody::point): the parent's marker point P, at a node
// x_p = c_p + phi_p y_p (markers.cpp's point), and the body's own marker point at x_c likewise:
//   r_c = P - A_c x_c,  P = r_p + A_p x_p,
// with A_c and y_c the body's own relative coordinates. Both are linear in each body's
// coordinates, so the Jacobian columns of the parent's coordinates are P's (the parent's columns
// of R mapped), and the rates and accelerations follow by the product rule.
void place_at_point(const Model& model, const RelativeTree& t, RelativeWork& w, const RelativeBody& rb, const Body& b,
                    VectorXd& q, VectorXd& qd, VectorXd& qdd, bool jacobian, bool rates) {
  const int o = b.offset, sf = rb.s_first, nq = b.nq;
  const Marker& mp = model.markers[static_cast<std::size_t>(rb.parent_marker)];
  const Marker& mc = model.markers[static_cast<std::size_t>(rb.child_marker)];
  Vector3d P = mp.c, Pd = Vector3d::Zero(), Pdd = Vector3d::Zero(), xp = mp.c;
  Matrix3d Ap = Matrix3d::Identity(), Apd = Matrix3d::Zero(), Apdd = Matrix3d::Zero();
  Vector3d pyd = Vector3d::Zero(), pydd = Vector3d::Zero();
  int op = -1;
  bool pnode = false;
  if (rb.parent != kGround) {
    const Body& pb = model.bodies[static_cast<std::size_t>(rb.parent)];
    op = pb.offset;
    pnode = mp.node >= 0 && pb.nq > 0;
    Vector3d py = Vector3d::Zero();
    if (pnode) {
      py = slice_times(mp.phi, q.data() + op + 12);
      pyd = slice_times(mp.phi, qd.data() + op + 12);
      pydd = slice_times(mp.phi, qdd.data() + op + 12);
    }
    xp += py;
    Ap = frame(q, op);
    Apd = frame(qd, op);
    Apdd = frame(qdd, op);
    P = pos(q, op) + Ap * xp;
    Pd = pos(qd, op) + Apd * xp + Ap * pyd;
    Pdd = pos(qdd, op) + Apdd * xp + 2 * Apd * pyd + Ap * pydd;
  }
  q.segment<9>(o + 3) = w.s.segment<9>(sf);
  qd.segment<9>(o + 3) = w.sd.segment<9>(sf);
  qdd.segment<9>(o + 3) = w.sdd.segment<9>(sf);
  if (nq > 0) {
    q.segment(o + 12, nq) = w.s.segment(sf + 9, nq);
    qd.segment(o + 12, nq) = w.sd.segment(sf + 9, nq);
    qdd.segment(o + 12, nq) = w.sdd.segment(sf + 9, nq);
  }
  const bool cnode = mc.node >= 0 && nq > 0;
  Vector3d cy = Vector3d::Zero(), cyd = Vector3d::Zero(), cydd = Vector3d::Zero();
  if (cnode) {
    cy = slice_times(mc.phi, q.data() + o + 12);
    cyd = slice_times(mc.phi, qd.data() + o + 12);
    cydd = slice_times(mc.phi, qdd.data() + o + 12);
  }
  const Vector3d xc = mc.c + cy;
  const Matrix3d Ac = frame(q, o), Acd = frame(qd, o), Acdd = frame(qdd, o);
  q.segment<3>(o) = P - Ac * xc;
  qd.segment<3>(o) = Pd - Acd * xc - Ac * cyd;
  qdd.segment<3>(o) = Pdd - Acdd * xc - 2 * Acd * cyd - Ac * cydd;
  if (!jacobian) return;
  if (op >= 0) {
    const RelativeBody& pr = t.bodies[static_cast<std::size_t>(rb.parent)];
    for (int col = pr.col0; col < pr.col0 + pr.ncols; ++col) {
      const double* c = w.R.col(col).data();
      const Eigen::Map<const Matrix3d> dA(c + op + 3);
      Vector3d dP = w.R.col(col).segment<3>(op) + dA * xp;
      if (pnode) dP += Ap * slice_times(mp.phi, c + op + 12);
      w.R.col(col).segment<3>(o) = dP;
      if (!rates) continue;
      // Its rate (R_dot): the product rule on the same map.
      const double* cd = w.Rd.col(col).data();
      const Eigen::Map<const Matrix3d> dAd(cd + op + 3);
      Vector3d dPd = w.Rd.col(col).segment<3>(op) + dAd * xp + dA * pyd;
      if (pnode) dPd += Apd * slice_times(mp.phi, c + op + 12) + Ap * slice_times(mp.phi, cd + op + 12);
      w.Rd.col(col).segment<3>(o) = dPd;
      // dP_ddot/ds at fixed rates (the modal rows of R_dot and Ra are zero: y's rates are s's).
      const Eigen::Map<const Matrix3d> dAa(w.Ra.col(col).data() + op + 3);
      Vector3d dPa = w.Ra.col(col).segment<3>(op) + dAa * xp + 2 * (dAd * pyd) + dA * pydd;
      if (pnode) dPa += Apdd * slice_times(mp.phi, c + op + 12);
      w.Ra.col(col).segment<3>(o) = dPa;
    }
  }
  for (int a = 0; a < 3; ++a) w.R.block<3, 3>(o, sf + 3 * a).diagonal().setConstant(-xc(a));
  if (rates)
    for (int a = 0; a < 3; ++a) {
      w.Rd.block<3, 3>(o, sf + 3 * a).diagonal().setConstant(-cyd(a));
      w.Ra.block<3, 3>(o, sf + 3 * a).diagonal().setConstant(-cydd(a));
    }
  w.R.block<9, 9>(o + 3, sf).setIdentity();
  if (nq > 0) {
    w.R.block(o + 12, sf + 9, nq, nq).setIdentity();
    if (cnode)
      for (int k = 0; k < nq; ++k) {
        w.R.col(sf + 9 + k).segment<3>(o) = -(Ac * mc.phi.col(k));
        if (!rates) continue;
        w.Rd.col(sf + 9 + k).segment<3>(o) = -(Acd * mc.phi.col(k));
        w.Ra.col(sf + 9 + k).segment<3>(o) = -(Acdd * mc.phi.col(k));
      }
  }
}

}  // namespace

void relative_kinematics(const Model& model, Data& data, bool jacobian, bool rates) {
  const RelativeTree& t = *model.relative;
  RelativeWork& w = *data.relative;
  VectorXd &q = data.state.q, &qd = data.state.qd, &qdd = data.state.qdd;
  // R and its rates are zero outside each body's rows over its range of columns (written below
  // only there): zeroed there, not whole (n x ns each).
  if (jacobian)
    for (int bi : t.order) {
      const RelativeBody& rb = t.bodies[static_cast<std::size_t>(bi)];
      const Body& b = model.bodies[static_cast<std::size_t>(bi)];
      w.R.block(b.offset, rb.col0, b.ncoord(), rb.ncols).setZero();
      if (rates)
        for (MatrixXd* m : {&w.Rd, &w.Ra}) m->block(b.offset, rb.col0, b.ncoord(), rb.ncols).setZero();
    }
  for (int bi : t.order) {
    const RelativeBody& rb = t.bodies[static_cast<std::size_t>(bi)];
    const Body& b = model.bodies[static_cast<std::size_t>(bi)];
    const int o = b.offset, nc = b.ncoord();
    if (rb.free) {
      q.segment(o, nc) = w.s.segment(rb.s_first, nc);
      qd.segment(o, nc) = w.sd.segment(rb.s_first, nc);
      qdd.segment(o, nc) = w.sdd.segment(rb.s_first, nc);
      if (jacobian) w.R.block(o, rb.s_first, nc, nc).setIdentity();  // (R_dot's block: zero)
      continue;
    }
    if (rb.point) {
      place_at_point(model, t, w, rb, b, q, qd, qdd, jacobian, rates);
      continue;
    }
    const Marker& mk = model.markers[static_cast<std::size_t>(rb.parent_marker)];
    Vector3d rp = Vector3d::Zero(), rpd = Vector3d::Zero(), rpdd = Vector3d::Zero();
    Matrix3d Ap = Matrix3d::Identity(), Apd = Matrix3d::Zero(), Apdd = Matrix3d::Zero();
    int op = -1;
    if (rb.parent != kGround) {
      op = model.bodies[static_cast<std::size_t>(rb.parent)].offset;
      rp = pos(q, op), rpd = pos(qd, op), rpdd = pos(qdd, op);
      Ap = frame(q, op), Apd = frame(qd, op), Apdd = frame(qdd, op);
    }
    const double th = rb.s_angle >= 0 ? w.s(rb.s_angle) : 0.0;
    const double thd = rb.s_angle >= 0 ? w.sd(rb.s_angle) : 0.0;
    const double thdd = rb.s_angle >= 0 ? w.sdd(rb.s_angle) : 0.0;
    const double x = rb.s_slide >= 0 ? w.s(rb.s_slide) : 0.0;
    const double xd = rb.s_slide >= 0 ? w.sd(rb.s_slide) : 0.0;
    const double xdd = rb.s_slide >= 0 ? w.sdd(rb.s_slide) : 0.0;
    const Matrix3d& relA = w.rel_A[static_cast<std::size_t>(bi)];
    const Vector3d& relp = w.rel_p[static_cast<std::size_t>(bi)];
    const Matrix3d& E = mk.E;
    const Matrix3d R0 = rot_x(th, 0), R1 = rot_x(th, 1), R2 = rot_x(th, 2);
    const Matrix3d N = E * R0 * relA, N1 = E * R1 * relA, N2 = E * R2 * relA;
    const Vector3d ks = E.col(0);
    const Vector3d k = mk.c + E * (R0 * relp) + x * ks, k1 = E * (R1 * relp), k2 = E * (R2 * relp);
    const Vector3d kd = k1 * thd + ks * xd;  // rate of k
    set(q, o, rp + Ap * k, Ap * N);
    set(qd, o, rpd + Apd * k + Ap * kd, Apd * N + Ap * N1 * thd);
    const Vector3d kdd = k2 * (thd * thd) + k1 * thdd + ks * xdd;  // k's acceleration, A_p fixed
    const Matrix3d Ndd = N2 * (thd * thd) + N1 * thdd;
    set(qdd, o, rpdd + Apdd * k + 2 * Apd * kd + Ap * kdd, Apdd * N + 2 * thd * Apd * N1 + Ap * Ndd);
    if (b.nq > 0) {
      q.segment(o + 12, b.nq) = w.s.segment(rb.s_first, b.nq);
      qd.segment(o + 12, b.nq) = w.sd.segment(rb.s_first, b.nq);
      qdd.segment(o + 12, b.nq) = w.sdd.segment(rb.s_first, b.nq);
    }
    if (!jacobian) continue;
    // Columns of the parent's coordinates: the same linear map (the parent's rows of R are zero
    // outside the columns its coordinates depend on, so all columns can be mapped).
    if (op >= 0) {
      const RelativeBody& pb = t.bodies[static_cast<std::size_t>(rb.parent)];
      for (int col = pb.col0; col < pb.col0 + pb.ncols; ++col) {
        const Eigen::Map<const Matrix3d> dA(w.R.col(col).data() + op + 3), dAd(w.Rd.col(col).data() + op + 3);
        const Eigen::Map<const Matrix3d> dAa(w.Ra.col(col).data() + op + 3);
        if (dA.isZero(0.0) && w.R.col(col).segment<3>(op).isZero(0.0) &&
            (!rates || (dAd.isZero(0.0) && w.Rd.col(col).segment<3>(op).isZero(0.0) && dAa.isZero(0.0) &&
                        w.Ra.col(col).segment<3>(op).isZero(0.0))))
          continue;
        w.R.col(col).segment<3>(o) = w.R.col(col).segment<3>(op) + dA * k;
        Eigen::Map<Matrix3d>(w.R.col(col).data() + o + 3) = dA * N;
        if (!rates) continue;
        // R_dot = dR/dt, the product rule on the same map (k and N turn with the angle).
        w.Rd.col(col).segment<3>(o) = w.Rd.col(col).segment<3>(op) + dAd * k + dA * kd;
        Eigen::Map<Matrix3d>(w.Rd.col(col).data() + o + 3) = dAd * N + thd * (dA * N1);
        // dq_ddot/ds at fixed rates: q_ddot's recursion with the parent's q, q_dot, q_ddot
        // replaced by their derivatives R, R_dot, Ra.
        w.Ra.col(col).segment<3>(o) = w.Ra.col(col).segment<3>(op) + dAa * k + 2 * (dAd * kd) + dA * kdd;
        Eigen::Map<Matrix3d>(w.Ra.col(col).data() + o + 3) = dAa * N + (2 * thd) * (dAd * N1) + dA * Ndd;
      }
    }
    if (rb.s_angle >= 0) {
      // (d/dth: k -> k1 -> k2 -> -k1, N likewise: rot_x''' = -rot_x'.)
      w.R.col(rb.s_angle).segment<3>(o) = Ap * k1;
      Eigen::Map<Matrix3d>(w.R.col(rb.s_angle).data() + o + 3) = Ap * N1;
    }
    if (rb.s_angle >= 0 && rates) {
      w.Rd.col(rb.s_angle).segment<3>(o) = Apd * k1 + thd * (Ap * k2);
      Eigen::Map<Matrix3d>(w.Rd.col(rb.s_angle).data() + o + 3) = Apd * N1 + thd * (Ap * N2);
      w.Ra.col(rb.s_angle).segment<3>(o) = Apdd * k1 + (2 * thd) * (Apd * k2) + Ap * (k2 * thdd - k1 * (thd * thd));
      Eigen::Map<Matrix3d>(w.Ra.col(rb.s_angle).data() + o + 3) = Apdd * N1 + (2 * thd) * (Apd * N2) + Ap * (N2 * thdd - N1 * (thd * thd));
    }
    if (rb.s_slide >= 0) {
      w.R.col(rb.s_slide).segment<3>(o) = Ap * ks;
      if (rates) {
        w.Rd.col(rb.s_slide).segment<3>(o) = Apd * ks;
        w.Ra.col(rb.s_slide).segment<3>(o) = Apdd * ks;
      }
    }
    if (b.nq > 0) w.R.block(o + 12, rb.s_first, b.nq, b.nq).setIdentity();
  }
}

void relative_curvature(const Model& model, Data& data, double factor, MatrixXd& Ts) {
  const RelativeTree& t = *model.relative;
  RelativeWork& w = *data.relative;
  const VectorXd& q = data.state.q;
  const VectorXd& F = w.force;
  for (int bi : t.order) {
    const Body& b = model.bodies[static_cast<std::size_t>(bi)];
    w.frame_force[static_cast<std::size_t>(bi)] << F.segment<3>(b.offset), Eigen::Map<const Matrix3d>(F.data() + b.offset + 3);
  }
  const auto frobenius = [](const Matrix3d& X, const double* y) { return X.cwiseProduct(Eigen::Map<const Matrix3d>(y)).sum(); };
  // Children before parents: a body's frame force then holds its descendants' (mapped by the
  // transposed placements), which see its coordinates only through its frame.
  for (auto it = t.order.rbegin(); it != t.order.rend(); ++it) {
    const int bi = *it;
    const RelativeBody& rb = t.bodies[static_cast<std::size_t>(bi)];
    if (rb.free) continue;
    const Body& b = model.bodies[static_cast<std::size_t>(bi)];
    const Eigen::Matrix<double, 3, 4>& ff = w.frame_force[static_cast<std::size_t>(bi)];
    const Vector3d Fr = ff.col(0);
    const Matrix3d FA = ff.rightCols<3>();
    const Marker& mp = model.markers[static_cast<std::size_t>(rb.parent_marker)];
    int op = -1;
    Matrix3d Ap = Matrix3d::Identity();
    const RelativeBody* pr = nullptr;
    const Body* pb = nullptr;
    if (rb.parent != kGround) {
      pr = &t.bodies[static_cast<std::size_t>(rb.parent)];
      pb = &model.bodies[static_cast<std::size_t>(rb.parent)];
      op = pb->offset;
      Ap = frame(q, op);
    }
    if (rb.point) {
      // r = P - A x_c: bilinear in the body's own frame A and modes y (x_c = c + phi y), and
      // P = r_p + A_p (c_p + phi_p y_p) in the parent's frame and modes.
      const Marker& mc = model.markers[static_cast<std::size_t>(rb.child_marker)];
      const int sf = rb.s_first;
      if (mc.node >= 0 && b.nq > 0)
        for (int k = 0; k < b.nq; ++k)
          for (int a = 0; a < 9; ++a) {
            const double v = -factor * Fr(a % 3) * mc.phi(a / 3, k);
            Ts(sf + a, sf + 9 + k) += v;
            Ts(sf + 9 + k, sf + a) += v;
          }
      if (op < 0) continue;
      Vector3d xp = mp.c;
      if (mp.node >= 0 && pb->nq > 0) {
        const int ym = pr->free ? pr->s_first + 12 : (pr->point ? pr->s_first + 9 : pr->s_first);
        for (int k = 0; k < pb->nq; ++k) {
          xp += mp.phi.col(k) * q(op + 12 + k);
          const Matrix3d B = Fr * mp.phi.col(k).transpose();
          for (int col = pr->col0; col < pr->col0 + pr->ncols; ++col) {
            const double v = factor * frobenius(B, w.R.col(col).data() + op + 3);
            Ts(col, ym + k) += v;
            Ts(ym + k, col) += v;
          }
        }
      }
      Eigen::Matrix<double, 3, 4>& fp = w.frame_force[static_cast<std::size_t>(rb.parent)];
      fp.col(0) += Fr;
      fp.rightCols<3>() += Fr * xp.transpose();
      continue;
    }
    // Wholly placed: r = r_p + A_p k(th, x), A = A_p N(th).
    const Matrix3d& relA = w.rel_A[static_cast<std::size_t>(bi)];
    const Vector3d& relp = w.rel_p[static_cast<std::size_t>(bi)];
    const double th = rb.s_angle >= 0 ? w.s(rb.s_angle) : 0.0, x = rb.s_slide >= 0 ? w.s(rb.s_slide) : 0.0;
    const Matrix3d& E = mp.E;
    const Matrix3d R0 = rot_x(th, 0), R1 = rot_x(th, 1), R2 = rot_x(th, 2);
    const Vector3d ks = E.col(0), k = mp.c + E * (R0 * relp) + x * ks, k1 = E * (R1 * relp), k2 = E * (R2 * relp);
    const Matrix3d N = E * R0 * relA, N1 = E * R1 * relA, N2 = E * R2 * relA;
    if (rb.s_angle >= 0) {
      Ts(rb.s_angle, rb.s_angle) += factor * (Fr.dot(Ap * k2) + FA.cwiseProduct(Ap * N2).sum());
      if (op >= 0) {
        const Matrix3d B = Fr * k1.transpose() + FA * N1.transpose();
        for (int col = pr->col0; col < pr->col0 + pr->ncols; ++col) {
          const double v = factor * frobenius(B, w.R.col(col).data() + op + 3);
          Ts(col, rb.s_angle) += v;
          Ts(rb.s_angle, col) += v;
        }
      }
    }
    if (rb.s_slide >= 0 && op >= 0) {
      const Matrix3d B = Fr * ks.transpose();
      for (int col = pr->col0; col < pr->col0 + pr->ncols; ++col) {
        const double v = factor * frobenius(B, w.R.col(col).data() + op + 3);
        Ts(col, rb.s_slide) += v;
        Ts(rb.s_slide, col) += v;
      }
    }
    if (op < 0) continue;
    Eigen::Matrix<double, 3, 4>& fp = w.frame_force[static_cast<std::size_t>(rb.parent)];
    fp.col(0) += Fr;
    fp.rightCols<3>() += Fr * k.transpose() + FA * N.transpose();
  }
}

void relative_sync(const Model& model, Data& data) {
  const RelativeTree& t = *model.relative;
  RelativeWork& w = *data.relative;
  const State& st = data.state;
  // Each tree body's pose in its parent marker's triad, its joint coordinates zero there.
  for (int bi : t.order) {
    const RelativeBody& rb = t.bodies[static_cast<std::size_t>(bi)];
    const Body& b = model.bodies[static_cast<std::size_t>(bi)];
    if (rb.free) {
      w.s.segment(rb.s_first, b.ncoord()) = st.q.segment(b.offset, b.ncoord());
      continue;
    }
    if (rb.point) {
      w.s.segment<9>(rb.s_first) = st.q.segment<9>(b.offset + 3);
      if (b.nq > 0) w.s.segment(rb.s_first + 9, b.nq) = st.q.segment(b.offset + 12, b.nq);
      continue;
    }
    const Marker& mk = model.markers[static_cast<std::size_t>(rb.parent_marker)];
    Vector3d rp = Vector3d::Zero();
    Matrix3d Ap = Matrix3d::Identity();
    if (rb.parent != kGround) {
      const int op = model.bodies[static_cast<std::size_t>(rb.parent)].offset;
      rp = pos(st.q, op);
      Ap = frame(st.q, op);
    }
    const Matrix3d Tp = Ap * mk.E;
    const Vector3d P = rp + Ap * mk.c;
    w.rel_A[static_cast<std::size_t>(bi)] = Tp.transpose() * frame(st.q, b.offset);
    w.rel_p[static_cast<std::size_t>(bi)] = Tp.transpose() * (pos(st.q, b.offset) - P);
    if (rb.s_angle >= 0) w.s(rb.s_angle) = 0;
    if (rb.s_slide >= 0) w.s(rb.s_slide) = 0;
    if (b.nq > 0) w.s.segment(rb.s_first, b.nq) = st.q.segment(b.offset + 12, b.nq);
  }
  // Rates and accelerations: the least-squares solutions of R s_dot = q_dot and
  // R s_ddot = q_ddot - R_dot s_dot (exact for a state that satisfies the tree's joints).
  w.qsave = data.state.qd;
  w.g = data.state.qdd;
  w.sd.setZero();
  w.sdd.setZero();
  relative_kinematics(model, data, true);
  w.Ts.noalias() = w.R.transpose() * w.R;
  w.lu.compute(w.Ts);
  w.sd.noalias() = w.R.transpose() * w.qsave;
  w.lu.solve_in_place(w.sd);
  relative_kinematics(model, data, false);  // q_ddot = R_dot s_dot with s_ddot = 0
  w.bias = w.g - data.state.qdd;
  w.sdd.noalias() = w.R.transpose() * w.bias;
  w.lu.solve_in_place(w.sdd);
  relative_kinematics(model, data, false);
  // The scaled size of each coordinate's increment: the largest weighted displacement it causes.
  for (int k = 0; k < t.ns; ++k) w.weight(k) = std::max(1e-12, w.R.col(k).cwiseAbs().cwiseProduct(model.increment_weight).maxCoeff());
  w.have_previous = false;
}

}  // namespace ffr::runtime
