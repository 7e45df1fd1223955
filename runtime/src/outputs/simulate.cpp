// The time loop: steps, recording, progress. Timing covers the loop alone (no loading, no
// writing), which is what the results file reports as integration_seconds.
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

// "step": "auto": adaptive steps that land on each output time (step_control.cpp).
RunInfo simulate_adaptive(const Model& model, Data& data, Recorder& rec, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const std::int64_t n = output_count(model);
  const std::int64_t iterations0 = data.stats.newton_iterations;
  StepControl control(model, data);
  const auto start = clock::now();
  auto last_report = start;
  rec.record(model, data);
  for (std::int64_t i = 1; i <= n; ++i) {
    advance_to(model, data, control, output_time(model, i));
    rec.record(model, data);
    if (opt.progress) {
      const auto now = clock::now();
      if (std::chrono::duration<double>(now - last_report).count() >= opt.progress_seconds) {
        opt.progress(data.t, model.settings.end);
        last_report = now;
      }
    }
  }
  RunInfo info;
  info.steps = control.accepted;
  info.newton_iterations = data.stats.newton_iterations - iterations0;
  info.integration_seconds = std::chrono::duration<double>(clock::now() - start).count();
  return info;
}

}  // namespace

RunInfo simulate(const Model& model, Data& data, Recorder& rec, const RunOptions& opt) {
  if (model.settings.adaptive) return simulate_adaptive(model, data, rec, opt);
  using clock = std::chrono::steady_clock;
  const std::int64_t n = step_count(model);
  const int every = std::max(1, model.settings.output_every);
  const std::int64_t iterations0 = data.stats.newton_iterations;
  const auto start = clock::now();
  auto last_report = start;
  rec.record(model, data);
  for (std::int64_t i = 1; i <= n; ++i) {
    step(model, data);
    if (i % every == 0 || i == n) rec.record(model, data);
    if (opt.progress) {
      const auto now = clock::now();
      if (std::chrono::duration<double>(now - last_report).count() >= opt.progress_seconds) {
        opt.progress(data.t, model.settings.end);
        last_report = now;
      }
    }
  }
  RunInfo info;
  info.steps = n;
  info.newton_iterations = data.stats.newton_iterations - iterations0;
  info.integration_seconds = std::chrono::duration<double>(clock::now() - start).count();
  return info;
}

}  // namespace ffr::runtime
