#pragma once
// Adaptive steps ("step": "auto", FORMULATION.md section 9): each step's local error is
// estimated (local_error in scheme.hpp) and held below its share h / (end - start) of the
// tolerances (error per unit step), a step above them or one whose Newton fails is
// taken again from the saved state with a smaller step, and the steps land on the requested
// output times.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"
#include "ffr/runtime/state.hpp"

#include <cstdint>
#include <vector>

namespace ffr::runtime {

/// The controller's constants (why each value: step_control.cpp).
struct StepControlLimits {
  double safety = 0.9;        ///< factor on the step the error estimate asks for
  double grow_max = 2.0;      ///< largest growth from one step to the next
  double shrink_min = 0.2;    ///< smallest factor after a rejected step
  double first_shrink = 1e-2; ///< smallest factor while no step has been accepted (h0 a guess)
  double min_step_fraction = 1e-10;  ///< minimum step, relative to end - start
};

/// The controller's state and the saved start of the step being tried, sized once.
struct StepControl {
  explicit StepControl(const Model& model, const Data& data);
  StepControlLimits limits;
  double h_next = 0;             ///< the next step to try
  bool accepted_any = false;
  std::int64_t accepted = 0, rejected = 0, newton_failures = 0;
  /// The start of the step being tried: what a rejected step is restored to (state.hpp).
  State saved;
};

/// The controller's part of a run's state: what a run restored from a saved state goes on with.
struct ResumePoint {
  double h_next = 0;
  bool accepted_any = false;
};

/// A run's whole state as the C API (ffr_save_state) and a stopped run's restart hold it: the
/// packed State (state.hpp), then the controller's next step and whether it has accepted a step
/// (zeros with fixed steps, `control` null).
int packed_run_size(const Model& model);
/// Allocation-free: `scratch` is a State sized for the model.
void pack_run(const Model& model, const Data& data, const StepControl* control, State& scratch, double* out);
/// Unpacks `in` into `state` and returns the controller's part. Throws std::invalid_argument,
/// leaving `state` unchanged, on a wrong length, a non-finite coordinate or, with adaptive
/// steps, a next step that is not a positive number.
ResumePoint unpack_run(const Model& model, const double* in, int size, State& state);

/// The first step tried: settings.step, which the model file's "step": "auto" sets to a hundredth
/// of the output interval (a guess the first steps correct).
double initial_step(const Model& model);

/// The requested output times after the start: start + k output_interval, the last one `end`.
std::int64_t output_count(const Model& model);
double output_time(const Model& model, std::int64_t k);

/// Advances data from data.state.t to exactly t_target with steps whose estimated local error is within
/// their share of the tolerances. Throws SolverError (naming the time) when the step falls below the minimum.
/// Allocation-free.
void advance_to(const Model& model, Data& data, StepControl& control, double t_target);

}  // namespace ffr::runtime
