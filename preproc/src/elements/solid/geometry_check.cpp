// Validity of the element geometry: the Jacobian determinant must be positive at every
// corner and at every quadrature point (a negative value anywhere means an inverted or
// tangled element, or midside nodes placed so far off that the map folds over).
#include "isoparametric.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace ffr::preproc::detail {

namespace {
// detJ at one corner. The PYRAMID5 apex needs no check of its own: the limit of the collapsed
// Jacobian there is spanned by the base corners' edge triples, which the base corners check.
void scan(const SolidShape& s, const Eigen::MatrixX3d& xe, JacobianRange& r, bool& first,
          const ShapeGradients& dN, const char* kind, int index) {
  const double d = jacobian(xe, dN).determinant();
  if (first || d < r.min) {
    r.min = d;
    r.where = std::string(kind) + " " + std::to_string(index);
  }
  if (first || d > r.max) r.max = d;
  first = false;
}
}  // namespace

JacobianRange jacobian_range(const SolidShape& s, const Eigen::MatrixX3d& xe) {
  JacobianRange r;
  bool first = true;
  for (int c = 0; c < s.corners; ++c) {
    if (s.type == ElementType::Pyramid5 && c == 4) continue;
    scan(s, xe, r, first, s.dN_corner[c], "corner node", c);
  }
  for (int g = 0; g < s.stiffness_rule.size(); ++g)
    scan(s, xe, r, first, s.dN_stiffness[g], "stiffness integration point", g);
  for (int g = 0; g < s.mass_rule.size(); ++g)
    scan(s, xe, r, first, s.dN_mass[g], "mass integration point", g);
  return r;
}

void check_geometry(const SolidShape& s, const Eigen::MatrixX3d& xe) {
  const char* tn = name(s.type);
  if (xe.rows() != s.nodes)
    throw ElementError(std::string(tn) + " element needs " + std::to_string(s.nodes) + " nodes, got " +
                       std::to_string(xe.rows()));
  if (!xe.allFinite()) throw ElementError(std::string(tn) + " element has non-finite node coordinates");
  // Size scale: the bounding-box diagonal h; detJ / h^3 below 1e-10 counts as zero volume.
  const double h = (xe.colwise().maxCoeff() - xe.colwise().minCoeff()).norm();
  const double tol = 1e-10 * h * h * h;
  const JacobianRange r = jacobian_range(s, xe);
  std::ostringstream m;
  m.precision(6);
  if (h == 0 || std::abs(r.min) <= tol) {
    m << tn << " element is degenerate (zero volume): Jacobian determinant " << r.min << " at " << r.where
      << " (nodes numbered from 0 in gmsh order); look for coincident or collapsed nodes";
    throw ElementError(m.str());
  }
  if (r.min < 0) {
    if (r.max > tol)
      m << tn << " element is distorted: Jacobian determinant changes sign (min " << r.min << " at " << r.where
        << ", max " << r.max << "); the element folds over itself or its midside nodes are misplaced";
    else
      m << tn << " element is inverted: Jacobian determinant negative everywhere (" << r.min << " at "
        << r.where << "); the node order is reversed";
    throw ElementError(m.str());
  }
}

}  // namespace ffr::preproc::detail
