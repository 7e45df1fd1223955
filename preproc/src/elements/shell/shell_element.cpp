// The public shell kernel: membrane and plate parts assembled on the local six DOFs of the
// projected facet, transformed back to body axes through the rigid links and the rotation
// (K = T^T K_local T), plus the mass samples of shell_mass.cpp.

#include "ffr/preproc/elements/shell.hpp"

#include "local_shell.hpp"
#include "shell_mass.hpp"

namespace ffr::preproc {

ElementMatrices shell_element(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section) {
  shell::check_input(type, xe, section);
  const shell::LocalShell l = shell::local_shell(type, xe, section);
  const int ndof = 6 * static_cast<int>(xe.rows());

  Eigen::MatrixXd Kl = Eigen::MatrixXd::Zero(ndof, ndof);
  shell::scatter(l.membrane.K, shell::kMembraneDof, Kl);
  shell::scatter(l.plate.K, shell::kPlateDof, Kl);

  ElementMatrices out;
  out.dofs_per_node = 6;
  out.K = l.T.transpose() * Kl * l.T;
  out.K = 0.5 * (out.K + out.K.transpose()).eval();
  shell::shell_mass(type, xe, l.frame, section, out);
  return out;
}

}  // namespace ffr::preproc
