#pragma once
// Input checks and the local (flat, projected) pieces of a shell element, shared by the
// stiffness/mass kernel and the resultant/geometric-stiffness functions.

#include "local_part.hpp"
#include "shell_frame.hpp"

#include "ffr/preproc/elements/shell.hpp"

#include <string>

namespace ffr::preproc::shell {

/// Where each part's three DOFs sit among a node's six local DOFs (u, v, w, rx, ry, rz).
inline constexpr int kMembraneDof[3] = {0, 1, 5};
inline constexpr int kPlateDof[3] = {2, 3, 4};

struct LocalShell {
  ShellFrame frame;
  Eigen::MatrixXd T;  ///< d_local = T d_body (6n x 6n)
  LocalPart membrane, plate;
};

/// "shell QUAD4" etc., the prefix of every message.
std::string who(ElementType type);

/// Validates type, node count, thickness, material and coordinates; throws ElementError.
void check_input(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& s);

/// Builds frame, transform and both parts (after check_input).
LocalShell local_shell(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& s);

/// Scatters a part's matrix (3n x 3n) into the 6n local DOFs.
void scatter(const Eigen::MatrixXd& part, const int (&dofs)[3], Eigen::MatrixXd& K);

/// Gathers a part's DOFs (3n) from the 6n local DOFs.
Eigen::VectorXd gather(const Eigen::VectorXd& d_local, const int (&dofs)[3]);

}  // namespace ffr::preproc::shell
