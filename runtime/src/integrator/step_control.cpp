// Adaptive steps: error-per-unit-step control of the index-3 step (FORMULATION.md section 9).
//
// Each step's local error is estimated from the converged coordinates and the second-order
// Taylor predictor (local_error, scheme_coefficients.cpp) and held below the step's share
// h / (end - start) of the tolerances: the local errors of the run then add up to at most the
// tolerance, so the error at the end is the tolerance times the mechanism's own amplification of
// errors, and falls in proportion to it (with a bound on each step's error alone, a
// second-order scheme's end error is the tolerance times the number of steps, ~rtol^(2/3)).
// The local error of the positions being O(h^3), the error per unit step is O(h^2) and the next
// step is h (safety / err)^(1/2):
//   safety 0.9: the usual margin (Hairer, Norsett & Wanner, Solving ODEs I, II.4) so that the
//     next step does not land just above the tolerance and get rejected;
//   growth at most 2 a step: the estimate comes from one step of a second-order scheme, and the
//     predictor (ali3p.cpp) extrapolates the accelerations over the step ratio;
//   reduction at least to 0.2 after a rejection (1e-2 before the first accepted step, whose
//     size is a guess), and no growth right after one.
// A step whose Newton iteration fails (SolverError) is retried at half the step. Both give up
// below min_step_fraction of the run (or below what the run's times resolve, model.hpp) with an
// error naming the time, the step and the last Newton failure. The steps land on the output
// times (cut to the time left, or to half of it when the step covers more than half of it, so
// that no sliver of a step follows); the outputs are therefore the scheme's own states, not
// interpolated.
#include "ffr/runtime/step_control.hpp"

#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace ffr::runtime {
namespace {

// (The control's own limits: a caller may have set them.)
double fraction_step(const Model& model, const StepControlLimits& lim) {
  return model.settings.end > model.settings.start ? lim.min_step_fraction * (model.settings.end - model.settings.start) : 0;
}

// Also no step the run's times cannot resolve (time_resolution_step, model.hpp): far from t = 0
// a step below it would move t by a rounded amount or not at all.
double min_step(const Model& model, const StepControlLimits& lim) {
  return std::max(fraction_step(model, lim), time_resolution_step(model.settings.start, model.settings.end));
}

[[noreturn]] void give_up(const Model& model, const StepControlLimits& lim, const Data& data, double h, const std::string& why) {
  char buf[200];
  const double least = min_step(model, lim);
  const bool by_time = least > fraction_step(model, lim);
  std::snprintf(buf, sizeof buf, "adaptive step: the step fell below the minimum %.3g s%s at t = %.9g s (last tried %.3g s): ",
                least, by_time ? " (what times this far from t = 0 resolve)" : "", data.state.t, h);
  throw SolverError(data.state.t, h,
                    buf + why + (by_time ? "; start the run nearer to t = 0 (shifting its tables and motions alike), or " : "; ") +
                        "loosen rtol/atol, or look for a discontinuity or a locked mechanism at that time");
}

}  // namespace

StepControl::StepControl(const Model& model, const Data& data) : saved(model) {
  save_state(data, saved);
  h_next = initial_step(model);
}

double initial_step(const Model& model) { return model.settings.step; }

std::int64_t output_count(const Model& model) {
  const SolverSettings& s = model.settings;
  const double n = (s.end - s.start) / s.output_interval;
  // A last interval shorter than a millionth of the others is rounding, not an interval.
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(n - 1e-6)));
}

double output_time(const Model& model, std::int64_t k) {
  const SolverSettings& s = model.settings;
  return k >= output_count(model) ? s.end : s.start + static_cast<double>(k) * s.output_interval;
}

void advance_to(const Model& model, Data& data, StepControl& c, double t_target) {
  const StepControlLimits& lim = c.limits;
  const double h_min = min_step(model, lim);
  const SolverSettings& s = model.settings;
  const double h_max = s.max_step > 0 ? s.max_step : s.output_interval > 0 ? s.output_interval : std::numeric_limits<double>::infinity();
  bool after_reject = false;
  while (data.state.t < t_target) {
    const double left = t_target - data.state.t;
    const double wanted = std::min(c.h_next, h_max);
    double h = wanted;
    bool lands = false;
    if (h >= left * (1 - 1e-12)) {
      h = left;
      lands = true;
    } else if (h > 0.5 * left) {
      h = 0.5 * left;
    }
    if (h < h_min) give_up(model, lim, data, h, "the error estimate kept rejecting the step");
    save_state(data, c.saved);
    // With reuse_jacobian a tangent of another step size would be stale from its first iterate.
    if (h != data.state.k.h) data.tangent_valid = false;
    try {
      step(model, data, h);
    } catch (const SolverError& e) {
      restore_state(c.saved, data);
      ++c.newton_failures;
      if (0.5 * h < h_min) give_up(model, lim, data, 0.5 * h, e.what());
      c.h_next = 0.5 * h;
      after_reject = true;
      continue;
    }
    const double err = local_error(model, data);
    const double fac = err > 0 ? lim.safety * std::pow(err, -1.0 / 2.0) : lim.grow_max;
    if (!(err <= 1.0)) {
      restore_state(c.saved, data);
      ++c.rejected;
      c.h_next = h * std::max(c.accepted_any ? lim.shrink_min : lim.first_shrink, std::min(fac, lim.safety));
      after_reject = true;
      continue;
    }
    if (lands) data.state.t = t_target;  // t + (t_target - t) may miss it by the last bit
    ++c.accepted;
    c.accepted_any = true;
    c.h_next = h * std::min(after_reject ? 1.0 : lim.grow_max, fac);
    // A step cut to land on an output time says nothing against the step wanted before it.
    if (h < wanted && !after_reject) c.h_next = std::max(c.h_next, wanted);
    after_reject = false;
  }
}

int packed_run_size(const Model& model) { return packed_state_size(model) + 2; }

void pack_run(const Model& model, const Data& data, const StepControl* control, State& scratch, double* out) {
  const int n = packed_state_size(model);
  save_state(data, scratch);
  pack_state(scratch, out);
  out[n] = control ? control->h_next : 0.0;
  out[n + 1] = control && control->accepted_any ? 1.0 : 0.0;
}

ResumePoint unpack_run(const Model& model, const double* in, int size, State& state) {
  const int n = packed_state_size(model);
  if (size != n + 2)
    throw std::invalid_argument("the state has " + std::to_string(size) + " values, this model's has " + std::to_string(n + 2));
  if (model.settings.adaptive && !(std::isfinite(in[n]) && in[n] > 0))
    throw std::invalid_argument("the saved next step is not a positive number");
  unpack_state(model, in, n, state);
  return {in[n], in[n + 1] != 0};
}

}  // namespace ffr::runtime
