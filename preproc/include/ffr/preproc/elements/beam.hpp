#pragma once
// Two-node 3D Timoshenko beam, six DOFs per node (ux, uy, uz, rx, ry, rz) in body axes.
//
// Local axes: x from node 1 to node 2, y = the component of `y_axis` normal to x, z = x × y.
// Section (preproc/PART_FILE.md, beams[].section): Iy = int z^2 dA (bending about y, the x–z plane),
// Iz = int y^2 dA (bending about z, the x–y plane), J torsion constant; y and z are principal.
// Shear factors ky, kz give the shear areas ky A (shear along y) and kz A (along z); 0 means
// shear-rigid (Euler–Bernoulli limit).
//
// Stiffness: the shear-flexibility-corrected (interdependent interpolation) matrix of
// Przemieniecki (1968) / Friedman & Kosmatka (1993), with Phi = 12 E I / (k G A L^2); exact for
// end loads. The same interpolation describes the motion of every material point:
//   v(s) = cubic Hermite-type functions of (v1, rz1, v2, rz2) with Phi (Friedman–Kosmatka),
//   rz(s) = their quadratic section-rotation companions (rz = v' when Phi = 0),
//   w, ry alike with Phi_z, u and the twist rx linear,
//   u_P = u_c(s) + theta(s) x (y e_y + z e_z)       (plane sections rotate rigidly, no warping)
// Mass samples: 4 Gauss points along the element times 4 section points at (±sqrt(2 Iz/A), 0),
// (0, ±sqrt(2 Iy/A)) with A/4 each, which reproduce A, Iy, Iz and the zero first moments and
// product exactly, so M (translational + rotary + polar inertia rho (Iy+Iz)) is exact.

#include "ffr/preproc/elements/element.hpp"

#include <Eigen/Core>

namespace ffr::preproc {

struct BeamSection {
  double A = 0, Iy = 0, Iz = 0, J = 0;
  double ky = 0, kz = 0;  ///< shear area factors; 0 = shear-rigid
  Eigen::Vector3d y_axis = Eigen::Vector3d::Zero();
  Material material;
};

/// xe: 2 x 3 node coordinates. Throws ElementError for coincident nodes, y_axis zero or
/// parallel to the element, non-positive A, Iy, Iz, J, negative ky, kz, or bad material.
ElementMatrices beam_element(const Eigen::MatrixX3d& xe, const BeamSection& section);

/// Rows: local x, y, z axes in body axes (v_local = R v_body). Validates as beam_element.
Eigen::Matrix3d beam_frame(const Eigen::MatrixX3d& xe, const Eigen::Vector3d& y_axis);

/// Section resultants of a displacement d_e (12, body axes) in local axes, as the force and
/// moment the part beyond the cut (larger x) exerts on the part before it:
/// (N, Vy, Vz, T, My, Mz) at node 1 (s = 0) and node 2 (s = L). Exact for end loads.
struct BeamResultants {
  Eigen::Matrix3d R;
  double length = 0;
  Eigen::Matrix<double, 6, 1> at1, at2;
  double axial() const { return 0.5 * (at1(0) + at2(0)); }  ///< N, tension positive
};

BeamResultants beam_resultants(const Eigen::MatrixX3d& xe, const BeamSection& section, const Eigen::VectorXd& d_e);

/// Geometric stiffness of the axial force N (tension positive), body axes, 12 x 12:
///   K_G = N int (v'^2 + w'^2) ds + N (Iy + Iz)/A int rx'^2 ds
/// with v, w from the same interdependent interpolation as K and M (the standard
/// P/(30L)[36 3L ...] matrix when shear-rigid).
Eigen::MatrixXd beam_geometric_stiffness(const Eigen::MatrixX3d& xe, const BeamSection& section, double N);

/// Convenience: K_G of the axial force of the linear solution d_e.
Eigen::MatrixXd beam_geometric_stiffness(const Eigen::MatrixX3d& xe, const BeamSection& section,
                                         const Eigen::VectorXd& d_e);

}  // namespace ffr::preproc
