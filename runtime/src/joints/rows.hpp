#pragma once
// Building blocks of constraint rows: vector expressions made of marker quantities and the dot
// products between them, with value, Jacobian row, rate and acceleration bias.
//   a . b:   J = b^T J_a + a^T J_b,   bias = a_b . b + a . b_b + 2 a_dot . b_dot

#include "ffr/runtime/data.hpp"

namespace ffr::runtime::detail {

struct VecTerm {
  double sign = 1;
  const Vector3d* v = nullptr;
  const Vector3d* vd = nullptr;
  const Vector3d* vb = nullptr;  ///< acceleration bias; the whole acceleration where J is null
  const Matrix3N* J = nullptr;   ///< null on the ground and on driven bodies (no unknowns)
  int side = 0;                  ///< 1: block.body1 columns, 2: block.body2 columns
};

struct VecExpr {
  VecTerm t[2];
  int n = 0;
  Vector3d value() const { return sum([](const VecTerm& x) { return x.v; }); }
  Vector3d rate() const { return sum([](const VecTerm& x) { return x.vd; }); }
  Vector3d bias() const { return sum([](const VecTerm& x) { return x.vb; }); }
  /// The rate of the terms without unknowns (a driven body's, zero on the ground): what moves
  /// the expression at fixed coordinates, for Phi_t.
  Vector3d given_rate() const {
    Vector3d s = Vector3d::Zero();
    for (int i = 0; i < n; ++i)
      if (!t[i].J) s += t[i].sign * *t[i].vd;
    return s;
  }

 private:
  template <class F>
  Vector3d sum(F f) const {
    Vector3d s = Vector3d::Zero();
    for (int i = 0; i < n; ++i) s += t[i].sign * *f(t[i]);
    return s;
  }
};

/// `fixed`: the marker's body has no unknowns (the ground, or a driven body).
inline VecTerm point(const MarkerData& md, int side, bool fixed, double sign = 1) {
  return {sign, &md.p, &md.pd, &md.pb, fixed ? nullptr : &md.Jp, side};
}
inline VecTerm axis(const MarkerData& md, int k, int side, bool fixed, double sign = 1) {
  return {sign, &md.e[k], &md.ed[k], &md.eb[k], fixed ? nullptr : &md.Je[k], side};
}
inline VecExpr expr(VecTerm a) { VecExpr e; e.t[0] = a; e.n = 1; return e; }
inline VecExpr expr(VecTerm a, VecTerm b) { VecExpr e; e.t[0] = a; e.t[1] = b; e.n = 2; return e; }

/// A constraint block's columns of one body in the dense Jacobian data.Phiq.
using JacobianBlock = Eigen::Block<MatrixXd>;

/// Adds scale * d(a.b)/dz to row r of J1/J2. Returns nothing; value/bias are computed by dot().
inline void dot_jacobian(const VecExpr& a, const VecExpr& b, double scale, JacobianBlock& J1, JacobianBlock& J2, int r) {
  const Vector3d av = a.value(), bv = b.value();
  auto add = [&](const VecTerm& x, const Vector3d& other) {
    if (!x.J) return;
    JacobianBlock& J = x.side == 1 ? J1 : J2;
    J.row(r).noalias() += (scale * x.sign) * other.transpose() * *x.J;
  };
  for (int i = 0; i < a.n; ++i) add(a.t[i], bv);
  for (int i = 0; i < b.n; ++i) add(b.t[i], av);
}

/// A scalar row: value, rate, acceleration bias, and the part of the rate at fixed coordinates
/// (Phi_t: Phi_dot = Phi_q q_dot + given).
struct DotValue {
  double value, rate, bias, given;
};
inline DotValue dot(const VecExpr& a, const VecExpr& b) {
  const Vector3d av = a.value(), bv = b.value(), ad = a.rate(), bd = b.rate();
  return {av.dot(bv), ad.dot(bv) + av.dot(bd), a.bias().dot(bv) + av.dot(b.bias()) + 2 * ad.dot(bd),
          a.given_rate().dot(bv) + av.dot(b.given_rate())};
}

}  // namespace ffr::runtime::detail
