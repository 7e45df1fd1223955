// Stress resultants of a linear shell solution and the geometric stiffness of its membrane
// forces (for the stiffening terms of formats/SPEC.md section 10). The membrane forces are those
// of the element's own strain field (incompatible modes condensed, OPT's higher-order strains
// included), at the element's in-plane integration points.

#include "ffr/preproc/elements/shell.hpp"

#include "local_shell.hpp"
#include "material_check.hpp"
#include "shape2d.hpp"

#include <Eigen/Dense>

namespace ffr::preproc {

ShellResultants shell_resultants(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section,
                                 const Eigen::VectorXd& d_e) {
  shell::check_input(type, xe, section);
  if (d_e.size() != 6 * xe.rows())
    structural::fail(shell::who(type), "displacement vector has " + std::to_string(d_e.size()) + " entries, expected " +
                                       std::to_string(6 * xe.rows()));
  const shell::LocalShell l = shell::local_shell(type, xe, section);
  const Eigen::VectorXd dl = l.T * d_e;
  const Eigen::VectorXd dm = shell::gather(dl, shell::kMembraneDof);
  const Eigen::VectorXd dp = shell::gather(dl, shell::kPlateDof);

  const double t = section.thickness;
  const Eigen::Matrix3d Dm = shell::plane_stress(section.material.E, section.material.nu) * t;
  const Eigen::Matrix3d Db = Dm * (t * t / 12);
  const double Ds = 5.0 / 6.0 * section.material.E / (2 * (1 + section.material.nu)) * t;

  ShellResultants r;
  r.R = l.frame.R;
  r.xi = l.membrane.xi;
  r.area = l.membrane.area;
  for (std::size_t g = 0; g < r.xi.size(); ++g) {
    r.N.push_back(Dm * l.membrane.B[g] * dm);
    r.M.push_back(Db * l.plate.B[g] * dp);
    r.Q.push_back(l.plate.Bs.empty() ? Eigen::Vector2d::Zero() : Eigen::Vector2d(Ds * l.plate.Bs[g] * dp));
  }
  return r;
}

Eigen::MatrixXd shell_geometric_stiffness(ElementType type, const Eigen::MatrixX3d& xe, const ShellResultants& r) {
  const std::string w = shell::who(type);
  if (type != ElementType::Tri3 && type != ElementType::Quad4)
    structural::fail(w, "geometric stiffness needs a TRI3 or QUAD4 element");
  if (xe.rows() != num_nodes(type)) structural::fail(w, "wrong number of node rows");
  if (r.N.size() != r.xi.size() || r.area.size() != r.xi.size())
    structural::fail(w, "inconsistent resultants (points, areas and forces differ in number)");
  const shell::ShellFrame f = shell::make_frame(type, xe, w);
  const int n = static_cast<int>(xe.rows());

  Eigen::MatrixXd G(n, n);  // int N_ab N_i,a N_j,b dA, the same for every displacement component
  G.setZero();
  for (std::size_t g = 0; g < r.xi.size(); ++g) {
    Eigen::MatrixXd dN = type == ElementType::Quad4 ? Eigen::MatrixXd(shell::quad4_dN(r.xi[g].x(), r.xi[g].y()))
                                                    : Eigen::MatrixXd(shell::tri3_dN());
    const Eigen::Matrix2d J = dN * f.xy;
    const Eigen::MatrixXd dNx = J.inverse() * dN;  // 2 x n
    Eigen::Matrix2d S;
    S << r.N[g](0), r.N[g](2), r.N[g](2), r.N[g](1);
    G += r.area[g] * dNx.transpose() * S * dNx;
  }
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) K.block<3, 3>(6 * i, 6 * j) = G(i, j) * Eigen::Matrix3d::Identity();
  return K;
}

Eigen::MatrixXd shell_geometric_stiffness(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section,
                                          const Eigen::VectorXd& d_e) {
  return shell_geometric_stiffness(type, xe, shell_resultants(type, xe, section, d_e));
}

}  // namespace ffr::preproc
