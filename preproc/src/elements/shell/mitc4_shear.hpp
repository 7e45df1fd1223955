#pragma once
// MITC4 assumed transverse shear (Dvorkin & Bathe, Eng. Comput. 1 (1984) 77–88; Bathe &
// Dvorkin, IJNME 21 (1985) 367–383). The covariant shear strains
//     g_xi  = w,xi  + beta . x,xi ,   g_eta = w,eta + beta . x,eta ,   beta = (ry, -rx)
// are sampled at the edge midpoints (tying points) and interpolated linearly across the
// element: g_xi from (0, -1) and (0, +1), g_eta from (-1, 0) and (+1, 0). Along a straight edge
// the bilinear w gives the exact chord slope, so a Kirchhoff (zero-shear) state of the nodal
// values is seen as zero shear: no shear locking, and the constant-curvature patch test holds.
// Cartesian (gxz, gyz) = J^-1 (g_xi, g_eta).
//
// Plate DOFs per node (w, rx, ry); rotations are components of the rotation vector, so a fibre
// at height z moves by z (ry, -rx) in-plane.

#include <Eigen/Core>

namespace ffr::preproc::shell {

/// 2 x 12 map from the plate DOFs to the assumed Cartesian shear strains at (xi, eta).
Eigen::Matrix<double, 2, 12> mitc4_shear_B(const Eigen::Matrix<double, 4, 2>& xy, double xi, double eta);

}  // namespace ffr::preproc::shell
