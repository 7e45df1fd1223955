#include "local_shell.hpp"

#include "material_check.hpp"

namespace ffr::preproc::shell {

std::string who(ElementType type) { return std::string("shell ") + name(type); }

void check_input(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& s) {
  const std::string w = who(type);
  if (type == ElementType::Tri6 || type == ElementType::Quad8 || type == ElementType::Quad9)
    structural::fail(w, "second-order shell elements are not supported; mesh shell groups with order 1 (TRI3/QUAD4)");
  if (type != ElementType::Tri3 && type != ElementType::Quad4)
    structural::fail(w, "not a shell element type (expected TRI3 or QUAD4)");
  if (xe.rows() != num_nodes(type))
    structural::fail(w, "expected " + std::to_string(num_nodes(type)) + " node rows, got " + std::to_string(xe.rows()));
  structural::check_finite(w, xe, "node coordinates");
  structural::check_positive(w, "thickness", s.thickness);
  structural::check_material(w, s.material);
}

LocalShell local_shell(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& s) {
  LocalShell l;
  l.frame = make_frame(type, xe, who(type));
  l.T = local_transform(l.frame);
  const double t = s.thickness;
  if (type == ElementType::Quad4) {
    const Eigen::Matrix<double, 4, 2> xy = l.frame.xy;
    l.membrane = quad4_membrane(xy, s.material, t);
    l.plate = mitc4_plate(xy, s.material, t);
  } else {
    const Eigen::Matrix<double, 3, 2> xy = l.frame.xy;
    l.membrane = opt_membrane(xy, s.material, t);
    l.plate = dkt_plate(xy, s.material, t);
  }
  return l;
}

void scatter(const Eigen::MatrixXd& part, const int (&dofs)[3], Eigen::MatrixXd& K) {
  const int n = static_cast<int>(part.rows()) / 3;
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      for (int j = 0; j < n; ++j)
        for (int b = 0; b < 3; ++b) K(6 * i + dofs[a], 6 * j + dofs[b]) += part(3 * i + a, 3 * j + b);
}

Eigen::VectorXd gather(const Eigen::VectorXd& d_local, const int (&dofs)[3]) {
  const int n = static_cast<int>(d_local.size()) / 6;
  Eigen::VectorXd d(3 * n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) d(3 * i + a) = d_local(6 * i + dofs[a]);
  return d;
}

}  // namespace ffr::preproc::shell
