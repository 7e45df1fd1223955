#pragma once
// Test support for the solid elements: straight-sided elements built from corner points,
// structured (optionally distorted) patches split into any solid type, assembly, Dirichlet
// solves, consistent surface loads, and an independent oracle for the volume moments of a
// polyhedron (tetrahedral decomposition; no shape functions involved).
#include "ffr/preproc/elements/solid.hpp"
#include "ffr/preproc/elements/solid_shape.hpp"

#include <Eigen/Core>
#include <Eigen/Sparse>

#include <functional>
#include <map>
#include <vector>

namespace ffr::test {

using preproc::ElementType;

/// The corner-only type with the same reference shape (TET10 -> TET4, HEX27 -> HEX8, ...).
ElementType linear_type(ElementType t);
/// The reference coordinates of the corners as a (corners x 3) matrix.
Eigen::MatrixX3d reference_corners(ElementType t);
/// Faces of the element as corner-index lists, counter-clockwise seen from outside.
std::vector<std::vector<int>> corner_faces(ElementType t);
/// Nodes of a type-t element whose map is the linear interpolation of `corners`
/// (midside nodes at edge midpoints etc.): a straight-sided element.
Eigen::MatrixX3d straight_element(ElementType t, const Eigen::MatrixX3d& corners);
/// A projective image p -> (A p + b) / (c.p + d) of the reference corners: planar faces,
/// non-affine (so detJ varies for hexes, prisms, pyramids).
Eigen::MatrixX3d projective_corners(ElementType t);

struct Moments {
  double V = 0;
  Eigen::Vector3d S1 = Eigen::Vector3d::Zero();  ///< int x dV
  Eigen::Matrix3d S2 = Eigen::Matrix3d::Zero();  ///< int x x^T dV
};
/// Exact moments of the polyhedron with the given corners and faces (planar faces).
Moments polyhedron_moments(const Eigen::MatrixX3d& corners, const std::vector<std::vector<int>>& faces);

/// A mesh of one element type.
struct Patch {
  ElementType type = ElementType::Hex8;
  std::vector<Eigen::Vector3d> x;
  std::vector<std::vector<int>> elems;
  int ndof() const { return 3 * static_cast<int>(x.size()); }
  Eigen::MatrixX3d coords(int e) const;
};
/// Box [0,Lx]x[0,Ly]x[0,Lz] cut into nx x ny x nz cells; interior lattice points moved by up
/// to `distortion` x cell size (boundary points stay put); each cell split into elements of
/// type t (6 tets, 2 prisms, 6 pyramids around an added centre point, or 1 hex); quadratic
/// elements straight-sided.
Patch make_box(ElementType t, int nx, int ny, int nz, const Eigen::Vector3d& L, double distortion = 0,
               unsigned seed = 1);

using Sparse = Eigen::SparseMatrix<double>;
Sparse assemble_stiffness(const Patch& p, const preproc::Material& m, const preproc::SolidOptions& o = {});
/// Geometric stiffness of the stress field produced by the global displacement d.
Sparse assemble_geometric(const Patch& p, const preproc::Material& m, const Eigen::VectorXd& d,
                          const preproc::SolidOptions& o = {});
/// Solves K u = f with u(dof) = value for the fixed DOFs.
Eigen::VectorXd solve_dirichlet(const Sparse& K, const Eigen::VectorXd& f, const std::map<int, double>& fixed);

/// Consistent nodal loads of a surface traction t(x, n) over the element faces that lie on the
/// plane x_k = value (outward normal n = sign e_k), integrated with the element's own shape
/// functions on the face (degree-5 triangle or 4x4 Gauss rules).
Eigen::VectorXd face_loads(const Patch& p, int k, double value, double sign,
                           const std::function<Eigen::Vector3d(const Eigen::Vector3d& x,
                                                               const Eigen::Vector3d& n)>& traction);

/// All solid types under test.
const std::vector<ElementType>& all_solid_types();

}  // namespace ffr::test
