#pragma once
// The slepc backend's distributed path through the pipeline (run_pipeline): each rank of the
// ParallelSession assembles only its share of the elements, the ranks' contributions to the
// constrained K and M are summed by PETSc into matrices of which each rank stores a block of
// rows, the eigen-solve with its Rayleigh-Ritz step and checks runs on those blocks
// (solver/slepc_distributed.hpp), and the shape integrals are each rank's elements' sums,
// added over the ranks. The SID is the serial path's up to the sign of each mode.
//
// An element belongs to the rank that owns the lowest of its independent DOFs in PETSc's
// split of the rows, so most of what a rank assembles lands in its own rows.
//
// Taken for the free and clamped methods of a part with its own mesh; Craig-Bampton, the
// stiffening, a preload and a part's own assembled matrices take the replicated path (every
// rank assembles the whole body; the solves are distributed).

#include "ffr/formats/sid.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/constraints.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/reduce/reduction.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace ffr::preproc::detail {

/// Whether run_pipeline takes the distributed path for this part (in an active ParallelSession).
bool distributed_reduction_applies(const PartSpec& part);

class DistributedReduction {
 public:
  /// Builds the reduction's DOF transform and this rank's share of the elements. Collective.
  DistributedReduction(const FeModel& model, const ReductionSpec& spec);

  /// This rank's elements' K, M and Ms; the scalar sums (mass, rdm, rrdm, rotary_I, the element
  /// count and the worst element) are the whole body's. Collective.
  Assembled assemble(const std::function<void(double)>& progress);
  /// The reduction of fe (from assemble(); its K and M are freed on the way). Collective.
  ReductionResult reduce(Assembled& fe, const ReductionLog& log);
  /// sid.refmod.mass, sid.integrals and sid.rotary of the whole body for the modes Phi (every
  /// rank's). Collective.
  void integrals(const Assembled& fe, const Eigen::MatrixXd& Phi, formats::Sid& sid) const;
  /// One line a rank: its elements, the entries of K and M it assembled, the entries of its
  /// rows of the summed K and M, and its peak resident memory so far. Collective.
  std::vector<std::string> rank_lines() const;

 private:
  const FeModel& model_;
  const ReductionSpec& spec_;
  DofTransform t_;
  std::vector<ElementRef> elements_;
  std::int64_t assembled_entries_ = 0, row_entries_ = 0;
};

}  // namespace ffr::preproc::detail
