#pragma once
// Isoparametric solid element kernels (3 DOFs per node, gmsh node order), isotropic linear
// elasticity. Element types, shape functions and quadrature rules: solid_shape.hpp.
//
// HEX8 formulation: by default the incompatible-modes element of Wilson et al. (1973) with
// the correction of Taylor, Beresford & Wilson (1976, IJNME 10:1211) -- the 3 x 3 bubble
// modes (1 - xi^2), (1 - eta^2), (1 - zeta^2) are differentiated with the Jacobian of the
// element centre and scaled by detJ(0)/detJ(xi), which makes their volume integral vanish on
// any shape so the element passes the patch test. They are integrated with 2x2x2 Gauss and
// condensed statically, so K stays 24 x 24 and is free of shear locking in bending. The mass
// uses the compatible (trilinear) field only. SolidOptions::hex8_incompatible = false gives
// the plain trilinear element (full 2x2x2 integration), which locks in bending: Abaqus's and
// CalculiX's C3D8, chosen per mesh block (ElementBlock::hex8, solid_options()).
//
// Stress and strain use Voigt order (xx, yy, zz, xy, yz, xz) with tensor shear components
// (sigma_xy, not 2 eps_xy) for stress.

#include "ffr/preproc/elements/element.hpp"
#include "ffr/preproc/mesh/mesh.hpp"

#include <Eigen/Core>

namespace ffr::preproc {

struct SolidOptions {
  bool hex8_incompatible = true;  ///< HEX8: incompatible modes (true) or plain trilinear
  bool mass_samples = true;       ///< fill ElementMatrices::samples (M is always computed)
};

/// The options of the elements of mesh block `b`: HEX8 formulated as the block says
/// (ElementBlock::hex8: an FE deck's C3D8 or C3D8I).
inline SolidOptions solid_options(const ElementBlock& b, bool mass_samples = true) {
  return SolidOptions{b.hex8 == Hex8Formulation::Incompatible, mass_samples};
}

/// Stiffness, consistent mass and exact mass samples of one solid element. The samples are
/// the points of the type's mass rule: w = rho detJ weight, c = x(xi), N = [N_a I3]_a (3 x 3nn).
/// Throws ElementError for bad material data, unsupported types, or inverted/degenerate
/// geometry (Jacobian checked at every quadrature point and every corner).
ElementMatrices solid_element(ElementType t, const Eigen::MatrixX3d& xe, const Material& mat,
                              const SolidOptions& opt = {});

/// Checks E > 0, -1 < nu < 0.5, rho >= 0 (all finite); throws ElementError naming the field.
void check_solid_material(const Material& mat);

/// Cauchy stress at the stiffness-rule points from the linear strain of d_e (for HEX8 with
/// incompatible modes, including the condensed internal modes).
struct SolidStress {
  Eigen::Matrix3Xd x;                        ///< physical position of each point
  Eigen::Matrix<double, 6, Eigen::Dynamic> sigma;  ///< (xx, yy, zz, xy, yz, xz) per point
};
SolidStress solid_stress(ElementType t, const Eigen::MatrixX3d& xe, const Material& mat,
                         const Eigen::VectorXd& d_e, const SolidOptions& opt = {});

/// Geometric (initial-stress) stiffness K_G = int G^T S G dV, S = sigma (x) I3 acting on the
/// displacement gradient: block (a, b) = (grad N_a . sigma grad N_b) I3. `sigma` holds the
/// stress at the points of the stiffness rule (6 x n, as returned by solid_stress).
Eigen::MatrixXd solid_geometric_stiffness(ElementType t, const Eigen::MatrixX3d& xe,
                                          const Eigen::Matrix<double, 6, Eigen::Dynamic>& sigma);
/// Same with sigma = solid_stress(t, xe, mat, d_e).
Eigen::MatrixXd solid_geometric_stiffness(ElementType t, const Eigen::MatrixX3d& xe,
                                          const Material& mat, const Eigen::VectorXd& d_e,
                                          const SolidOptions& opt = {});

/// Shape quality for the mesh report (never throws on bad geometry; reports it).
struct SolidQuality {
  double min_det_j = 0, max_det_j = 0;  ///< over corners and all quadrature points
  /// min detJ / max detJ (gmsh's "minJ/maxJ" measure): 1 for affine elements, <= 0 invalid.
  double jacobian_ratio = 0;
  /// Verdict-style scaled Jacobian: min over corners of det of the unit edge vectors leaving
  /// the corner, normalised so the ideal shape (cube, regular tet, equilateral prism and
  /// pyramid) scores 1; <= 0 means inverted.
  double min_scaled_jacobian = 0;
};
SolidQuality solid_quality(ElementType t, const Eigen::MatrixX3d& xe);
/// SolidQuality::min_scaled_jacobian alone (0 for invalid coordinates, as there): what the
/// assembly reports for every solid. Why apart: solid_quality's detJ range evaluates ~20
/// Jacobians of a TET10, which the element's own geometry check has just done, and the
/// assembly does not read it.
double solid_min_scaled_jacobian(ElementType t, const Eigen::MatrixX3d& xe);

}  // namespace ffr::preproc
