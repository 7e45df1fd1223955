#pragma once
// The local frame of a flat-facet shell element and the map from body-axis nodal DOFs to the
// local DOFs of the flat (projected) element.
//
// QUAD4: normal e3 along the cross product of the diagonals, the mean plane through the
// centroid; the four corners sit at heights h, -h, h, -h above it (warping). e1 follows the
// mean xi-direction (x2 + x3 - x1 - x4) projected on the plane, so the frame does not depend on
// which diagonal is "first" and the projected quad keeps gmsh's counter-clockwise order.
// TRI3: e1 along edge 1-2, e3 along (x2 - x1) x (x3 - x1).
//
// Rigid links join each node to its projection x_i - h_i e3 (the warping correction):
//   u_proj = u_i + theta_i x (-h_i e3),
// exact for rigid-body motion, so a warped element keeps its six rigid-body modes.

#include "ffr/preproc/mesh/mesh.hpp"

#include <Eigen/Core>

#include <string>

namespace ffr::preproc::shell {

struct ShellFrame {
  Eigen::Matrix3d R;     ///< rows e1, e2, e3 in body axes (v_local = R v_body)
  Eigen::Vector3d origin;
  Eigen::MatrixX2d xy;   ///< in-plane local coordinates of the projected nodes (n x 2)
  Eigen::VectorXd h;     ///< height of each node above the mean plane (along e3)
  double length = 0;     ///< characteristic size: longest edge
};

/// Largest |h| / sqrt(projected area) a QUAD4 may have before it is refused as excessively
/// warped (0.2 on a unit square is a fold of about 60 degrees between its two triangles).
inline constexpr double kMaxWarp = 0.2;

/// Builds and checks the frame; throws ElementError (prefixed with `who`) for degenerate,
/// non-convex or excessively warped elements.
ShellFrame make_frame(ElementType type, const Eigen::MatrixX3d& xe, const std::string& who);

/// T (6n x 6n) with d_local = T d_body: rotation to local axes, then the rigid links to the
/// projected nodes. Local DOFs per node: (u, v, w, rx, ry, rz).
Eigen::MatrixXd local_transform(const ShellFrame& f);

}  // namespace ffr::preproc::shell
