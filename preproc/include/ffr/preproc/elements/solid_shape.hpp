#pragma once
// Reference-element data of the isoparametric solid elements: shape functions in gmsh's
// reference coordinates and node order (gmsh reference manual, "Node ordering"), and the
// quadrature rules the kernels use for stiffness and for mass.
//
// Supported: TET4, TET10, HEX8, HEX20, HEX27, WEDGE6, WEDGE15, PYRAMID5.
//
//   type      stiffness rule               mass rule (exact for straight-sided elements)
//   TET4      1 point (B constant)         4-point degree 2   (N_i N_j: degree 2, detJ const)
//   TET10     4-point degree 2             14-point degree 5  (N_i N_j: degree 4, detJ const)
//   HEX8      2x2x2 Gauss (+ incompatible  3x3x3 Gauss        (N_i N_j: 2 per variable,
//             modes, see solid.hpp)                            trilinear detJ: 2 per variable)
//   HEX20     3x3x3 Gauss                  4x4x4 Gauss        (4 + 2 = 6 per variable)
//   HEX27     3x3x3 Gauss                  4x4x4 Gauss        (4 + 2 = 6 per variable)
//   WEDGE6    3-pt triangle x 2 Gauss      7-pt degree-5 triangle x 3 Gauss
//                                                             (N_i N_j detJ: 3 in (r,s), 4 in zeta)
//   WEDGE15   7-pt triangle x 3 Gauss      7-pt triangle x 4 Gauss (5 in (r,s), 6 in zeta)
//   PYRAMID5  collapsed 3x3x3              collapsed 3x3x3    (polynomial of degree 4 per
//                                                             collapsed variable, see quadrature.hpp)
//
// The PYRAMID5 basis is the rational one (Bedrosian 1992): for base node i,
// N_i = (1 - zeta + xi_i xi)(1 - zeta + eta_i eta) / (4 (1 - zeta)), apex N_4 = zeta. It is
// bilinear on the base and linear on the triangular faces, so it conforms to HEX8 and TET4
// neighbours, and it is trilinear in the collapsed coordinates of quadrature::pyramid.

#include "ffr/preproc/elements/quadrature.hpp"
#include "ffr/preproc/mesh/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace ffr::preproc {

/// Largest node count of a supported solid element plus room for HEX8's incompatible modes.
inline constexpr int kMaxSolidNodes = 27;

/// Shape-function values (nn) and reference derivatives (nn x 3) with stack storage.
using ShapeValues = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSolidNodes, 1>;
using ShapeGradients = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxSolidNodes, 3>;

struct SolidShape {
  ElementType type = ElementType::Tet4;
  int nodes = 0;    ///< nodes in gmsh order
  int corners = 0;  ///< the first `corners` nodes are the vertices
  /// Evaluates N (nodes) and dN/dxi (nodes x 3) at reference point xi (both pre-sized).
  void (*eval)(const Eigen::Vector3d& xi, ShapeValues& N, ShapeGradients& dN) = nullptr;
  std::vector<Eigen::Vector3d> reference_nodes;  ///< gmsh reference coordinates of the nodes
  quadrature::Rule stiffness_rule, mass_rule;
  /// Shape functions cached at the rule points (index = point).
  std::vector<ShapeValues> N_stiffness, N_mass;
  std::vector<ShapeGradients> dN_stiffness, dN_mass;
  std::vector<ShapeGradients> dN_corner;  ///< at each corner (PYRAMID5 apex: unused, see quality)
};

/// True for the element types solid_element() accepts.
bool is_solid(ElementType t);
/// The reference data of a supported solid type; throws ElementError for other types.
const SolidShape& solid_shape(ElementType t);

}  // namespace ffr::preproc
