#pragma once
// Element geometric (initial-stress) stiffness K_G for the stress of a displacement field u
// over the full DOFs, for the stiffening assembly.
#include "ffr/preproc/assembly/assembly.hpp"

namespace ffr::preproc::detail {

/// K_G of one element (in K's slot; M left empty). Attached masses carry no stress: zero.
ElementMatrices geometric_element(const FeModel& model, const ElementRef& ref, const Eigen::VectorXd& u);

}  // namespace ffr::preproc::detail
