// The time loop: steps, recording, progress. Timing covers the loop alone (no loading, no
// writing), which is what the results file reports as integration_seconds.
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/outputs.hpp"
#include "ffr/runtime/step_control.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ffr::runtime {

std::int64_t step_count(const Model& model) {
  const auto& s = model.settings;
  if (s.adaptive) return output_count(model);
  return std::max<std::int64_t>(0, std::llround((s.end - s.start) / s.step));
}

namespace {

using clock = std::chrono::steady_clock;

// Calls the caller's progress function at most once every opt.progress_seconds of wall time.
class ProgressReport {
 public:
  ProgressReport(const RunOptions& opt, clock::time_point start) : opt_(opt), last_(start) {}
  void operator()(double t, double end) {
    if (!opt_.progress) return;
    const auto now = clock::now();
    if (std::chrono::duration<double>(now - last_).count() < opt_.progress_seconds) return;
    opt_.progress(t, end);
    last_ = now;
  }

 private:
  const RunOptions& opt_;
  clock::time_point last_;
};

RunInfo stopped_run(RunInfo info, const SolverError& e) {
  info.stopped_at = e.time();
  info.stop_reason = e.what();
  return info;
}

bool stop_requested(const RunOptions& opt) { return opt.stop && opt.stop->load(std::memory_order_relaxed) != 0; }

// The run stopped by RunOptions::stop: where, and the state to resume from (allocates: once).
RunInfo requested_stop(const Model& model, const Data& data, const StepControl* control, RunInfo info) {
  info.stopped_at = data.state.t;
  info.stop_reason = "stop requested";
  State scratch(model);
  info.restart.resize(static_cast<std::size_t>(packed_run_size(model)));
  pack_run(model, data, control, scratch, info.restart.data());
  return info;
}

// The index of the run's step (or output interval) at data's time, for a resumed run; the time
// must be on that grid.
std::int64_t resume_index(const Model& model, const Data& data, double interval) {
  const auto& s = model.settings;
  const std::int64_t i = std::llround((data.state.t - s.start) / interval);
  if (i < 0 || std::abs(data.state.t - (s.start + static_cast<double>(i) * interval)) > 1e-3 * interval)
    throw std::invalid_argument("the state to resume from, at t = " + std::to_string(data.state.t) +
                                " s, is not at a step (or output time) of the run");
  return i;
}

// The solver's counts of a run: its stats less those at its start.
void count_since(const Stats& start, const Stats& now, RunInfo& info) {
  info.newton_iterations = now.newton_iterations - start.newton_iterations;
  info.factorizations = now.factorizations - start.factorizations;
  info.solves = now.solves - start.solves;
}

RunInfo run_info(std::int64_t steps, const Stats& stats0, const Stats& now, clock::time_point start) {
  RunInfo info;
  info.steps = steps;
  count_since(stats0, now, info);
  info.integration_seconds = std::chrono::duration<double>(clock::now() - start).count();
  return info;
}

// "step": "auto": adaptive steps that land on each output time (step_control.cpp).
RunInfo simulate_adaptive(const Model& model, Data& data, Recorder& rec, const RunOptions& opt) {
  const std::int64_t n = output_count(model);
  const Stats stats0 = data.stats;
  StepControl control(model, data);
  std::int64_t i0 = 0;
  if (opt.resume) {
    i0 = resume_index(model, data, model.settings.output_interval);
    control.h_next = opt.resume->h_next;
    control.accepted_any = opt.resume->accepted_any;
  }
  const auto start = clock::now();
  ProgressReport progress(opt, start);
  if (!opt.resume) rec.record(model, data);
  try {
    for (std::int64_t i = i0 + 1; i <= n; ++i) {
      advance_to(model, data, control, output_time(model, i));
      rec.record(model, data);
      progress(data.state.t, model.settings.end);
      if (i < n && stop_requested(opt))
        return requested_stop(model, data, &control, run_info(control.accepted, stats0, data.stats, start));
    }
  } catch (const SolverError& e) {
    if (opt.stopped) *opt.stopped = stopped_run(run_info(control.accepted, stats0, data.stats, start), e);
    throw;
  }
  return run_info(control.accepted, stats0, data.stats, start);
}

}  // namespace

void add_counts(RunInfo& total, const RunInfo& part) {
  total.steps += part.steps;
  total.newton_iterations += part.newton_iterations;
  total.factorizations += part.factorizations;
  total.solves += part.solves;
  total.integration_seconds += part.integration_seconds;
}

RunInfo simulate(const Model& model, Data& data, Recorder& rec, const RunOptions& opt) {
  if (model.settings.adaptive) return simulate_adaptive(model, data, rec, opt);
  const std::int64_t n = step_count(model);
  const int every = std::max(1, model.settings.output_every);
  const Stats stats0 = data.stats;
  const std::int64_t i0 = opt.resume ? resume_index(model, data, model.settings.step) : 0;
  const auto start = clock::now();
  ProgressReport progress(opt, start);
  if (!opt.resume) rec.record(model, data);
  std::int64_t i = i0 + 1;
  try {
    for (; i <= n; ++i) {
      step(model, data);
      const bool stop = i < n && stop_requested(opt);
      if (i % every == 0 || i == n || stop) rec.record(model, data);
      progress(data.state.t, model.settings.end);
      if (stop) return requested_stop(model, data, nullptr, run_info(i - i0, stats0, data.stats, start));
    }
  } catch (const SolverError& e) {
    if (opt.stopped) *opt.stopped = stopped_run(run_info(i - 1 - i0, stats0, data.stats, start), e);
    throw;
  }
  return run_info(n - i0, stats0, data.stats, start);
}

}  // namespace ffr::runtime
