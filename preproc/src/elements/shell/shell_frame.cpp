#include "shell_frame.hpp"

#include "material_check.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace ffr::preproc::shell {

using structural::fail;
using structural::num;

namespace {

double longest_edge(const Eigen::MatrixX3d& xe) {
  const int n = static_cast<int>(xe.rows());
  double l = 0;
  for (int i = 0; i < n; ++i) l = std::max(l, (xe.row((i + 1) % n) - xe.row(i)).norm());
  return l;
}

}  // namespace

ShellFrame make_frame(ElementType type, const Eigen::MatrixX3d& xe, const std::string& who) {
  const int n = static_cast<int>(xe.rows());
  ShellFrame f;
  f.length = longest_edge(xe);
  if (!(f.length > 0)) fail(who, "degenerate element: all nodes coincide");
  const double tol = 1e-10 * f.length * f.length;

  Eigen::Vector3d e1, e3;
  double area2 = 0;  // twice the projected area
  if (type == ElementType::Tri3) {
    const Eigen::Vector3d a = xe.row(1) - xe.row(0), b = xe.row(2) - xe.row(0);
    e3 = a.cross(b);
    if (e3.norm() <= tol) fail(who, "degenerate TRI3: zero area (collinear or coincident nodes)");
    e1 = a;
  } else {
    const Eigen::Vector3d d1 = xe.row(2) - xe.row(0), d2 = xe.row(3) - xe.row(1);
    e3 = d1.cross(d2);
    if (e3.norm() <= tol) fail(who, "degenerate QUAD4: zero area (collinear or coincident nodes)");
    e1 = (xe.row(1) + xe.row(2) - xe.row(0) - xe.row(3)).transpose();
  }
  area2 = e3.norm();
  e3.normalize();
  e1 -= e1.dot(e3) * e3;
  if (e1.norm() <= 1e-10 * f.length) fail(who, "degenerate element: no in-plane direction");
  e1.normalize();
  const Eigen::Vector3d e2 = e3.cross(e1);
  f.R.row(0) = e1.transpose();
  f.R.row(1) = e2.transpose();
  f.R.row(2) = e3.transpose();

  f.origin = xe.colwise().mean().transpose();
  f.xy.resize(n, 2);
  f.h.resize(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = f.R * (xe.row(i).transpose() - f.origin);
    f.xy.row(i) << p.x(), p.y();
    f.h(i) = p.z();
  }

  // Convexity and orientation: every corner of the projected polygon turns left.
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d a = f.xy.row((i + 1) % n) - f.xy.row(i);
    const Eigen::Vector2d b = f.xy.row((i + n - 1) % n) - f.xy.row(i);
    const double c = a.x() * b.y() - a.y() * b.x();
    if (c <= tol)
      fail(who, std::string("degenerate or non-convex ") + name(type) + " at corner " + std::to_string(i + 1) +
                    " (coincident nodes, a straight or re-entrant angle)");
  }
  const double warp = f.h.cwiseAbs().maxCoeff() / std::sqrt(0.5 * area2);
  if (warp > kMaxWarp)
    fail(who, "QUAD4 too warped: corner height / sqrt(area) = " + num(warp) + " > " + num(kMaxWarp));
  return f;
}

Eigen::MatrixXd local_transform(const ShellFrame& f) {
  const int n = static_cast<int>(f.xy.rows());
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int i = 0; i < n; ++i) {
    // u_proj = u - h (theta x e3) = u + h (-theta_y, theta_x, 0) in local axes.
    Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
    W(0, 1) = -f.h(i);
    W(1, 0) = f.h(i);
    T.block<3, 3>(6 * i, 6 * i) = f.R;
    T.block<3, 3>(6 * i, 6 * i + 3) = W * f.R;
    T.block<3, 3>(6 * i + 3, 6 * i + 3) = f.R;
  }
  return T;
}

}  // namespace ffr::preproc::shell
