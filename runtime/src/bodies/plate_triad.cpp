// The exact triad of a plate node and its derivatives (plate_triad.hpp, FORMULATION.md 16).
#include "plate_triad.hpp"

#include <Eigen/Geometry>

namespace ffr::runtime::detail {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d skew(const Vector3d& x) {
  Matrix3d s;
  s << 0, -x(2), x(1), x(2), 0, -x(0), -x(1), x(0), 0;
  return s;
}

}  // namespace

void plate_triad(const Vector3d& a, const Vector3d& b, PlateTriad& T) {
  T.a = a;
  T.b = b;
  const Matrix3d I = Matrix3d::Identity();
  const double aa = a.dot(a), ab = a.dot(b);
  // v1 = a
  T.v[0] = a;
  T.Jv[0].leftCols<3>() = I;
  T.Jv[0].rightCols<3>().setZero();
  // v2 = (a.a) b - (a.b) a: dv2 = (2 b a^T - a b^T - (a.b) I) da + ((a.a) I - a a^T) db
  T.v[1] = aa * b - ab * a;
  T.Jv[1].leftCols<3>() = 2 * b * a.transpose() - a * b.transpose() - ab * I;
  T.Jv[1].rightCols<3>() = aa * I - a * a.transpose();
  // v3 = a x b: dv3 = -[b]x da + [a]x db
  T.v[2] = a.cross(b);
  T.Jv[2].leftCols<3>() = -skew(b);
  T.Jv[2].rightCols<3>() = skew(a);
  for (int i = 0; i < 3; ++i) {
    T.r[i] = T.v[i].norm();
    T.t[i] = T.v[i] / T.r[i];
    T.J[i].noalias() = (I - T.t[i] * T.t[i].transpose()) * T.Jv[i] / T.r[i];
  }
}

Vector3d triad_axis(const PlateTriad& T, const Vector3d& w, Matrix36* G) {
  Vector3d e = Vector3d::Zero();
  if (G) G->setZero();
  for (int i = 0; i < 3; ++i) {
    if (w(i) == 0) continue;
    e += w(i) * T.t[i];
    if (G) *G += w(i) * T.J[i];
  }
  return e;
}

Vector3d triad_axis_second(const PlateTriad& T, const Vector3d& w, const Vector6& z) {
  const auto za = z.head<3>(), zb = z.tail<3>();
  Vector3d out = Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (w(i) == 0) continue;
    const Vector3d& t = T.t[i];
    const double r = T.r[i];
    const Vector3d p = T.Jv[i] * z;
    // D2v[z, z]: zero for v1, 2 da x db for v3, and for v2 the second variation of the cubic.
    Vector3d s = Vector3d::Zero();
    if (i == 2) s = 2 * za.cross(zb);
    if (i == 1)
      s = 2 * za.dot(za) * T.b + 4 * T.a.dot(za) * zb - 2 * za.dot(zb) * T.a - 2 * (za.dot(T.b) + T.a.dot(zb)) * za;
    const double tp = t.dot(p);
    const Vector3d Pp = p - tp * t;
    out += w(i) * ((-2 * tp * Pp - p.dot(Pp) * t) / (r * r) + (s - t.dot(s) * t) / r);
  }
  return out;
}

void triad_axis_hessian(const PlateTriad& T, const Vector3d& w, const Vector3d& f, Matrix66& H) {
  H.setZero();
  const Matrix3d I = Matrix3d::Identity();
  for (int i = 0; i < 3; ++i) {
    if (w(i) == 0) continue;
    const Vector3d fi = w(i) * f;
    const Vector3d& t = T.t[i];
    const double r = T.r[i], tf = t.dot(fi);
    const Vector3d Pf = fi - tf * t;
    // f . D2n[Dv z, Dv z']
    const Matrix3d Hn = -(Pf * t.transpose() + t * Pf.transpose() + tf * (I - t * t.transpose())) / (r * r);
    H.noalias() += T.Jv[i].transpose() * Hn * T.Jv[i];
    // (Dn^T f) . D2v[z, z'], g = P f / r
    const Vector3d g = Pf / r;
    if (i == 2) {
      // g . (da x db' + da' x db): the (a, b) block -[g]x
      H.block<3, 3>(0, 3) -= skew(g);
      H.block<3, 3>(3, 0) += skew(g);
    } else if (i == 1) {
      const Vector3d &a = T.a, &b = T.b;
      H.block<3, 3>(0, 0) += 2 * g.dot(b) * I - b * g.transpose() - g * b.transpose();
      const Matrix3d AB = 2 * a * g.transpose() - g.dot(a) * I - g * a.transpose();
      H.block<3, 3>(0, 3) += AB;
      H.block<3, 3>(3, 0) += AB.transpose();
    }
  }
}

}  // namespace ffr::runtime::detail
