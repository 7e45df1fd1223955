// Going on with an interrupted run (outputs.hpp: RunOptions::stop, RunInfo::restart,
// resume_from; ffr-sim --keep-partial then --resume). The reference is the same run never
// stopped: the resumed run's samples, steps and iterations must be its own, bit for bit.
#include "ffr/formats/results_io.hpp"
#include "ffr/runtime/runtime.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>

namespace {

using namespace ffr::runtime;

// A pendulum on a friction damper in series with a rubber bearing (its slip and dissipated
// energy are state of the run beyond the coordinates), a spring, and outputs that read them.
std::string model_text(const std::string& solver) {
  return R"({
  "gravity": [0, 0, -9.81],
  "bodies": [{"name": "bar", "type": "rigid", "mass": 1.0, "com": [0.5, 0, 0],
              "inertia": [[1e-4, 0, 0], [0, 0.0834, 0], [0, 0, 0.0834]]}],
  "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bar", "at": [0, 0, 0], "axis": [0, 1, 0]}],
  "forces": [{"name": "rub", "type": "friction_damper", "body1": "ground", "at1": [1, 0, -1], "body2": "bar", "at2": [1, 0, 0],
              "force": 0.5, "series_stiffness": 2000},
             {"type": "spring_damper", "body1": "ground", "at1": [1, 0, 1], "body2": "bar", "at2": [1, 0, 0], "k": 30}],
  "solver": )" + solver + R"(,
  "outputs": [{"name": "angle", "type": "joint_coordinate", "joint": "hinge"}, {"name": "energy", "type": "energy"},
              {"name": "rub", "type": "element_force", "force": "rub"}]
})";
}

struct Stepped {
  Recorder rec;
  RunInfo info;
};

// The run from its start; with `stop_at`, asked to stop (as a signal does) once t passes it.
Stepped run(const Model& model, double stop_at = -1) {
  Data data(model);
  initialize(model, data);
  Stepped r{Recorder(model, step_count(model) / std::max(1, model.settings.output_every) + 2), {}};
  std::atomic<int> stop{0};
  RunOptions opt;
  if (stop_at >= 0) {
    opt.stop = &stop;
    opt.progress_seconds = 0;  // called after every step (fixed) or output (adaptive)
    opt.progress = [&](double t, double) {
      if (t >= stop_at) stop = 1;
    };
  }
  r.info = simulate(model, data, r.rec, opt);
  return r;
}

// `tolerance` 0: bit for bit; else each output to that fraction of its largest value.
void expect_same_samples(const Recorder& a, const Recorder& b, const Model& model, double tolerance) {
  ASSERT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.times().head(a.rows()), b.times().head(b.rows()));
  for (std::size_t o = 0; o < model.outputs.size(); ++o) {
    const Eigen::MatrixXd d = a.values(o).topRows(a.rows()) - b.values(o).topRows(b.rows());
    Eigen::Index row = 0, col = 0;
    const double largest = d.cwiseAbs().maxCoeff(&row, &col);
    EXPECT_LE(largest, tolerance * b.values(o).topRows(b.rows()).cwiseAbs().maxCoeff())
        << model.outputs[o].name << ": the largest difference at t = " << a.times()[row];
  }
}

// (The stop comes a step after the step that passes stop_at: the flag is read before each step's
// sample, and set by the progress call after it.)
void resumes_as_never_stopped(const std::string& solver, double stop_at, double tolerance = 0) {
  ffr::runtime::test::TempDir dir("resume");
  ffr::runtime::test::write_text(dir / "m.json", model_text(solver));
  const Model model = load_model((dir / "m.json").string());
  const Stepped whole = run(model);
  ASSERT_FALSE(whole.info.stopped_at.has_value());

  const Stepped first = run(model, stop_at);
  ASSERT_TRUE(first.info.stopped_at.has_value());
  ASSERT_FALSE(first.info.restart.empty());
  EXPECT_GE(*first.info.stopped_at, stop_at);
  EXPECT_LT(*first.info.stopped_at, model.settings.end);
  if (!model.settings.adaptive && model.settings.output_every > 1)  // the stop's sample is off the run's own schedule
    EXPECT_NE(std::llround((*first.info.stopped_at - model.settings.start) / model.settings.step) % model.settings.output_every, 0);
  write_results(dir / "part.h5", std::nullopt, model, first.rec, first.info);

  Data data(model);
  initialize(model, data);
  Recorder rec(model, step_count(model) / std::max(1, model.settings.output_every) + 2);
  RunInfo counts;
  RunOptions opt;
  opt.resume = resume_from(dir / "part.h5", model, data, rec, counts);
  const RunInfo rest = simulate(model, data, rec, opt);
  expect_same_samples(rec, whole.rec, model, tolerance);
  EXPECT_EQ(counts.steps + rest.steps, whole.info.steps);
  if (tolerance == 0) EXPECT_EQ(counts.newton_iterations + rest.newton_iterations, whole.info.newton_iterations);
}

}  // namespace

// Fixed steps, a sample every third step, stopped between two samples: the stop's own sample is
// not one of the run's, so the resumed results leave it out.
TEST(Resume, FixedStepsGoOnAsTheRunNeverStopped) {
  resumes_as_never_stopped(R"({"end": 1.0, "step": 0.001, "output_every": 3})", 0.4015);  // stops at step 403
}

// The generalized-alpha scheme's own state (its pseudo-accelerations) goes on as well.
TEST(Resume, GeneralizedAlphaGoesOnAsTheRunNeverStopped) {
  resumes_as_never_stopped(R"({"end": 1.0, "step": 0.001, "integrator": "generalized_alpha", "spectral_radius": 0.6})", 0.3);
}

// The relative formulation takes its joint coordinates afresh from the absolute state restored
// (as after the C API's ffr_restore_state), its predictor's history not kept: the run goes on
// to rounding, not bit for bit (measured: 1e-10 rad of the angle with the trapezoidal rule).
TEST(Resume, RelativeFormulationGoesOnToRounding) {
  resumes_as_never_stopped(R"({"end": 1.0, "step": 0.001, "formulation": "relative"})", 0.3, 1e-8);
}

TEST(Resume, AdaptiveStepsGoOnAsTheRunNeverStopped) {
  resumes_as_never_stopped(R"({"end": 1.0, "step": "auto", "output_interval": 0.01, "rtol": 1e-6})", 0.4);
}

// Refused, naming the file: a run that failed (no state to go on from: it needs another model),
// a model changed since, and a state of another model's size.
TEST(Resume, WhatCannotBeResumedIsRefused) {
  ffr::runtime::test::TempDir dir("resume");
  ffr::runtime::test::write_text(dir / "m.json", model_text(R"({"end": 0.2, "step": 0.001})"));
  const Model model = load_model((dir / "m.json").string());
  const Stepped first = run(model, 0.1);
  write_results(dir / "part.h5", std::nullopt, model, first.rec, first.info);
  const auto refusal = [&](const Model& m, const std::filesystem::path& file) {
    Data data(m);
    initialize(m, data);
    Recorder rec(m, step_count(m) + 2);
    RunInfo counts;
    try {
      resume_from(file, m, data, rec, counts);
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string("(resumed)");
  };
  RunInfo failed = first.info;  // as ffr-sim writes a run that stopped with a solver error
  failed.restart.clear();
  write_results(dir / "failed.h5", std::nullopt, model, first.rec, failed);
  EXPECT_NE(refusal(model, dir / "failed.h5").find((dir / "failed.h5").string() + ": /restart: no state to resume from"),
            std::string::npos);
  // The model file edited since (a stiffer spring): refused, not resumed with other physics.
  EXPECT_EQ(refusal(model, dir / "part.h5"), "(resumed)");
  std::string text = model_text(R"({"end": 0.2, "step": 0.001})");
  text.replace(text.find("\"k\": 30"), 7, "\"k\": 40");
  ffr::runtime::test::write_text(dir / "m.json", text);
  const Model edited = load_model((dir / "m.json").string());
  EXPECT_NE(refusal(edited, dir / "part.h5").find((dir / "part.h5").string() + ": /restart@inputs_sha256: the model file or its SID files changed"),
            std::string::npos);
}
