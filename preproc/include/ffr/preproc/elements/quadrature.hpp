#pragma once
// Quadrature rules on the gmsh reference elements (the same reference coordinates as the
// gmsh reference manual's "Node ordering"): line [-1,1], triangle and tetrahedron with unit
// legs at the origin, hexahedron [-1,1]^3, prism = triangle x [-1,1], pyramid with base
// [-1,1]^2 at zeta = 0 and apex (0,0,1).
//
// Every rule here has positive weights (mass samples are weights times density, and a
// negative mass sample would be nonsense) and integrates the stated polynomial degree
// exactly; tests/solid_elements/quadrature_test.cpp checks each against exact monomial
// integrals.

#include <Eigen/Core>

#include <vector>

namespace ffr::preproc::quadrature {

struct Rule {
  std::vector<Eigen::Vector3d> xi;  ///< points in reference coordinates (unused components 0)
  std::vector<double> w;            ///< weights; sum = measure of the reference element
  int size() const { return static_cast<int>(w.size()); }
};

/// Gauss-Legendre points and weights on [-1, 1], n = 1..5 (exact to degree 2n - 1).
void gauss_legendre(int n, double* x, double* w);

/// n x n x n tensor Gauss rule on [-1,1]^3 (degree 2n-1 in each variable).
Rule hexahedron(int n);
/// Triangle rule exact to `degree` (1: centroid, 2: 3 points, 3..5: Radon's 7 points).
Rule triangle(int degree);
/// Tetrahedron rule exact to `degree` (1: centroid, 2: 4 points, 3..5: 14 points).
Rule tetrahedron(int degree);
/// Prism rule: triangle rule of degree `tri_degree` times n-point Gauss in zeta.
Rule prism(int tri_degree, int n);
/// Pyramid rule by the Duffy collapse of the cube: xi = a(1-c), eta = b(1-c), zeta = c
/// with n-point Gauss in a, b in [-1,1] and c in [0,1]; weights carry the (1-c)^2 factor.
/// Exact for every f whose pull-back f(a(1-c), b(1-c), c) (1-c)^2 has degree <= 2n-1 per
/// variable (this includes the mass integrand of the rational 5-node pyramid).
Rule pyramid(int n);

}  // namespace ffr::preproc::quadrature
