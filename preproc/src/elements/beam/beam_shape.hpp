#pragma once
// The displacement interpolation of the Timoshenko beam (local axes, local DOFs per node
// (u, v, w, rx, ry, rz)): the interdependent ("shear-corrected") functions of Friedman &
// Kosmatka (Comput. Struct. 47 (1993) 473–481), which solve the homogeneous Timoshenko
// equations exactly, so the element is exact for end loads and its stiffness equals
// Przemieniecki's closed form.
//
//   v  = N1 v1 + N2 rz1 + N3 v2 + N4 rz2,       rz = G1 v1 + G2 rz1 + G3 v2 + G4 rz2   (Phi_y)
//   w  = N1 w1 - N2 ry1 + N3 w2 - N4 ry2,       ry = -(G1 w1 - G2 ry1 + G3 w2 - G4 ry2) (Phi_z)
//   u, rx linear,
// with Phi = 12 E I / (k G A L^2) (0 when shear-rigid, giving the cubic Hermite functions).

#include <Eigen/Core>

namespace ffr::preproc::beam {

struct ShapeParams {
  double L = 0;
  double phi_y = 0;  ///< bending in the x-y plane (v, rz; uses Iz and ky)
  double phi_z = 0;  ///< bending in the x-z plane (w, ry; uses Iy and kz)
};

/// 6 x 12: rows (u, v, w, rx, ry, rz) of the section at s = xi L, xi in [0, 1].
Eigen::Matrix<double, 6, 12> interpolation(const ShapeParams& p, double xi);

/// 6 x 12: d/ds of interpolation().
Eigen::Matrix<double, 6, 12> interpolation_ds(const ShapeParams& p, double xi);

/// 4-point Gauss on [0, 1] (exact to degree 7).
inline constexpr double kGauss4X[4] = {0.0694318442029737124, 0.330009478207571868, 0.669990521792428132,
                                       0.930568155797026288};
inline constexpr double kGauss4W[4] = {0.173927422568726929, 0.326072577431273071, 0.326072577431273071,
                                       0.173927422568726929};

}  // namespace ffr::preproc::beam
