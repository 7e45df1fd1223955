#pragma once
// Element geometric (initial-stress) stiffness K_G for the stress of a displacement field u
// over the full DOFs, for the stiffening assembly.
#include "ffr/preproc/assembly/assembly.hpp"

namespace ffr::preproc::detail {

/// Which points a solid's K_G is integrated at. Shells and beams are the same either way.
enum class GeometricRule {
  /// The element's stiffness rule (where its stress is recovered): the K0 load cases.
  Stiffness,
  /// The element's mass rule, exact for the cubic integrand sigma(u) : grad(v)^T grad(w) of
  /// affine TET10, HEX8, HEX20/27 elements (the stiffness rule is one degree short for the
  /// quadratic ones): Ke.M1, whose cubic form must be the FE model's Green-Lagrange energy.
  Cubic,
};

/// K_G of one element (in K's slot; M left empty). Attached masses carry no stress: zero.
ElementMatrices geometric_element(const FeModel& model, const ElementRef& ref, const Eigen::VectorXd& u,
                                  GeometricRule rule = GeometricRule::Stiffness);

}  // namespace ffr::preproc::detail
