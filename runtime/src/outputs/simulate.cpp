// The time loop: steps, recording, progress. Timing covers the loop alone (no loading, no
// writing), which is what the results file reports as integration_seconds.
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/outputs.hpp"
#include "ffr/runtime/step_control.hpp"

#include <chrono>
#include <cmath>

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

RunInfo requested_stop(RunInfo info, const Data& data) {
  info.stopped_at = data.state.t;
  info.stop_reason = "stop requested";
  return info;
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
  const auto start = clock::now();
  ProgressReport progress(opt, start);
  rec.record(model, data);
  try {
    for (std::int64_t i = 1; i <= n; ++i) {
      advance_to(model, data, control, output_time(model, i));
      rec.record(model, data);
      progress(data.state.t, model.settings.end);
      if (i < n && stop_requested(opt)) return requested_stop(run_info(control.accepted, stats0, data.stats, start), data);
    }
  } catch (const SolverError& e) {
    if (opt.stopped) *opt.stopped = stopped_run(run_info(control.accepted, stats0, data.stats, start), e);
    throw;
  }
  return run_info(control.accepted, stats0, data.stats, start);
}

}  // namespace

RunInfo simulate(const Model& model, Data& data, Recorder& rec, const RunOptions& opt) {
  if (model.settings.adaptive) return simulate_adaptive(model, data, rec, opt);
  const std::int64_t n = step_count(model);
  const int every = std::max(1, model.settings.output_every);
  const Stats stats0 = data.stats;
  const auto start = clock::now();
  ProgressReport progress(opt, start);
  rec.record(model, data);
  std::int64_t i = 1;
  try {
    for (; i <= n; ++i) {
      step(model, data);
      const bool stop = i < n && stop_requested(opt);
      if (i % every == 0 || i == n || stop) rec.record(model, data);
      progress(data.state.t, model.settings.end);
      if (stop) return requested_stop(run_info(i, stats0, data.stats, start), data);
    }
  } catch (const SolverError& e) {
    if (opt.stopped) *opt.stopped = stopped_run(run_info(i - 1, stats0, data.stats, start), e);
    throw;
  }
  return run_info(n, stats0, data.stats, start);
}

}  // namespace ffr::runtime
