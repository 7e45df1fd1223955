#pragma once
// Static solutions K u = f under a body's reference conditions, many load cases with one
// factorization. Held interfaces come through the DOF transformation; a body with nothing
// held is solved by inertia relief: the load's rigid-body part is removed
// (f - M R (R^T M R)^-1 R^T f), the body rests on a statically determinate support of six
// DOFs (chosen by pivoted QR of the rigid-body modes, so they fix the six motions as well
// as possible), and the displacement is made M-orthogonal to the rigid-body modes.
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/constraints.hpp"
#include "ffr/preproc/solver/cholmod_factor.hpp"

namespace ffr::preproc::detail {

class StaticSolver {
 public:
  StaticSolver(const FeModel& model, const Assembled& fe, const std::vector<InterfaceState>& states);
  /// Displacements (num_dofs x cases) for loads over the full DOFs (num_dofs x cases).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& F_full) const;
  bool inertia_relief() const { return relief_; }
  const FactorStatistics& factor_statistics() const { return factor_.info().stats; }

 private:
  DofTransform t_;
  SparseMatrix K_, M_;      // over the independent DOFs
  bool relief_ = false;
  Eigen::MatrixXd R_;       // rigid-body modes (independent DOFs), M-orthonormal, if relief
  std::vector<Index> free_; // independent DOFs kept after the six support DOFs (if relief)
  CholmodFactor factor_;
};

}  // namespace ffr::preproc::detail
