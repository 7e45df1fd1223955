#pragma once
// Flat-facet shell kernels: QUAD4 and TRI3, six DOFs per node (ux, uy, uz, rx, ry, rz) in
// body axes, nodes in gmsh order. Pure functions of the geometry and the section.
//
// QUAD4 = membrane (bilinear + Wilson/Taylor incompatible modes, Hughes–Brezzi drilling
//         rotation: gamma = G on the element mean of (omega - rz), 0.01 G on its fluctuation,
//         see src/elements/shell/hb_drilling.hpp) + Reissner–Mindlin plate (bilinear bending, MITC4 transverse shear of
//         Bathe–Dvorkin), built on the element's mean plane; a warped quad is joined to its
//         projected nodes by rigid links (u_proj = u + theta x (x_proj - x)), which keeps the
//         six rigid-body modes exact.
// TRI3  = Felippa's OPT membrane with drilling freedoms + the DKT plate (Batoz–Bathe–Ho);
//         the mass samples interpolate translations and rotations linearly.
//
// Mass (see element.hpp): samples at 2 x 2 (QUAD4) or 3 (TRI3) surface points times 2 Gauss
// points through the thickness; each sample moves with u = sum N_i (u_i + theta_i x z n)
// (a fibre along the element normal n at height z), so the section rotary inertia
// rho t^3/12 of the two bending rotations is in the samples. The drilling rotation carries no
// material point; a lumped rho t^3/12 (int N_i dA) n n^T per node keeps M definite and goes
// into M_rotary. For a flat element every inertia integral of the samples is exact.

#include "ffr/preproc/elements/element.hpp"
#include "ffr/preproc/mesh/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace ffr::preproc {

struct ShellSection {
  double thickness = 0;
  Material material;
};

/// K, consistent M and mass samples of one shell element (TRI3 or QUAD4; other types throw
/// ElementError naming the type). Throws ElementError for zero/negative thickness, bad material,
/// degenerate, non-convex or excessively warped geometry.
ElementMatrices shell_element(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section);

/// The mass part of shell_element() alone: the same M, M_rotary and samples; K is a zero
/// matrix of the right size (the stiffness kernels are not run). For the inertia integrals,
/// which need only the samples, at a quarter of the cost.
ElementMatrices shell_mass_element(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section);

/// Linear stress resultants of a displacement d_e (6 n, body axes) at the element's in-plane
/// integration points, in the element's local axes (rows of R).
struct ShellResultants {
  Eigen::Matrix3d R;                  ///< rows e1, e2, e3 (e3 = normal) in body axes
  std::vector<Eigen::Vector2d> xi;    ///< natural coordinates of the points
  std::vector<double> area;           ///< area weight of each point (sum = element area)
  std::vector<Eigen::Vector3d> N;     ///< membrane forces (Nxx, Nyy, Nxy) [N/m]
  std::vector<Eigen::Vector3d> M;     ///< bending moments (Mxx, Myy, Mxy) [N m/m], M = D kappa
  std::vector<Eigen::Vector2d> Q;     ///< transverse shear forces (Qx, Qy) [N/m]; zero for DKT
};

ShellResultants shell_resultants(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section,
                                 const Eigen::VectorXd& d_e);

/// Stresses at the element's nodes as linear maps of its displacement d_e (6 n, body axes):
/// rows 6a..6a+5 give node a's Cauchy stress in body axes, Voigt (xx, yy, zz, xy, yz, xz), tensor
/// shear. The resultants at the integration points are extrapolated to the corners by the corner
/// shape functions, then spread through the thickness with the plane-stress assumption
/// (src/elements/shell/shell_stress.cpp): top (z = +t/2 along `normal`) and bottom carry
/// membrane +- bending stress, the middle the membrane stress and the peak transverse shear
/// 3 Q / (2 t) (none for TRI3: the DKT plate has no shear strain).
struct ShellStressMap {
  Eigen::Vector3d normal;              ///< the element's normal e3 in body axes ("top" is its + side)
  Eigen::MatrixXd top, middle, bottom; ///< 6n x 6n each
};

ShellStressMap shell_stress_map(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section);

/// Geometric (initial-stress) stiffness of the membrane forces in `r`:
///   K_G = int N_ab (du/dx_a) . (du/dx_b) dA   for all three displacement components,
/// on the translational DOFs (rotational rows/columns are zero). 6n x 6n, body axes.
Eigen::MatrixXd shell_geometric_stiffness(ElementType type, const Eigen::MatrixX3d& xe, const ShellResultants& r);

/// Convenience: K_G of the membrane forces of the linear solution d_e.
Eigen::MatrixXd shell_geometric_stiffness(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section,
                                          const Eigen::VectorXd& d_e);

}  // namespace ffr::preproc
