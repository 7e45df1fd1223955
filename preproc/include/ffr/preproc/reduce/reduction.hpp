#pragma once
// The three reductions of the part file (contract: reduction.method):
//  - free: free-free eigenmodes; rigid-body modes deflated exactly (negative shift, so
//    nothing singular is factorized); elastic modes M-orthonormal and M-orthogonal to the
//    rigid-body motion, hence Ct.M0 = Cr.M0 = 0.
//  - clamped: the named interface held; its fixed-interface eigenmodes.
//  - craig-bampton: the frame interface held; six static constraint modes per other
//    interface (unit motion of one interface DOF, the others held), then fixed-interface
//    eigenmodes; optionally the whole basis orthonormalized by a reduced eigen-solve.
// The basis is returned over the full DOFs (Phi = T Phi_ind), ready for the invariants.

#include "ffr/formats/sid.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/constraints.hpp"
#include "ffr/preproc/solver/cholmod_factor.hpp"

#include <functional>
#include <string>

namespace ffr::preproc {

struct ReductionLog {
  std::function<void(const std::string&)> message;  ///< stage lines ("factorizing ...")
  std::function<void(const std::string&)> progress; ///< transient progress (Lanczos rounds)
};

struct ReductionResult {
  Eigen::MatrixXd Phi;                      ///< num_dofs x nq, over the full DOFs
  Eigen::VectorXd lambda;                   ///< omega^2 (Rayleigh quotient for static modes)
  std::vector<formats::ModeType> types;
  std::string reference;                    ///< "free", "clamped:<interface>", "craig-bampton"
  Eigen::MatrixXd Ke, Me;                   ///< Phi^T K Phi, Phi^T M Phi (from the FE matrices)
  std::string parameters_json;              ///< method and parameters, for provenance
  // Statistics of the eigen-solve, for the log and provenance.
  FactorStatistics factor;
  double factor_seconds = 0, lanczos_seconds = 0, max_residual = 0, orthonormality_error = 0;
  int iterations = 0;
  std::string backend;
};

/// Runs the part's reduction. Throws formats::FormatError (exit 2) for a mechanism, a body in
/// several pieces, an unknown interface; other failures as std::runtime_error.
ReductionResult reduce(const FeModel& model, const Assembled& fe, const ReductionSpec& spec,
                       const ReductionLog& log = {});

}  // namespace ffr::preproc
