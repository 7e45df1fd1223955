#pragma once
// Pieces of the serial reduction (reduction.cpp) that its distributed path
// (distributed_reduction.cpp) shares, so that both refuse alike and ask the eigen-solver alike.
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/solver/eigen_solver.hpp"

#include <string>

namespace ffr::preproc::detail {

/// omega^2 of a frequency in Hz, in the part's time unit.
double lambda_of_frequency(double hz, const PartSpec& part);
/// The eigen-solver's options for the reduction spec at the shift sigma.
EigenOptions reduction_eigen_options(const ReductionSpec& spec, const PartSpec& part, double sigma);
/// Refuses (formats::FormatError) a body in several pieces.
void require_connected(const FeModel& model);
/// Refuses (formats::FormatError) near-zero eigenvalues: mechanisms.
void require_no_zero_modes(const FeModel& model, const Eigen::VectorXd& lambda, const std::string& held);
/// Refuses (formats::FormatError) `massless` DOFs of `n` without mass (a density of 0).
void require_mass(Index massless, Index n, const PartSpec& part);

}  // namespace ffr::preproc::detail
