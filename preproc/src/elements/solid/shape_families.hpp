#pragma once
// Private: the per-family shape functions behind solid_shape().
#include "ffr/preproc/elements/solid_shape.hpp"

#include <array>
#include <vector>

namespace ffr::preproc::detail {

/// gmsh reference coordinates of the nodes of a supported solid type (gmsh 4.8,
/// gmsh::model::mesh::getElementProperties; also the reference manual's "Node ordering").
const std::vector<std::array<double, 3>>& reference_nodes(ElementType t);

void shape_tet4(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);
void shape_tet10(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);
void shape_hex8(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);
void shape_hex20(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);
void shape_hex27(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);
void shape_wedge6(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);
void shape_wedge15(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);
void shape_pyramid5(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN);

}  // namespace ffr::preproc::detail
