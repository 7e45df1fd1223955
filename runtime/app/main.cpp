// ffr-sim MODEL.json -o OUT.h5 [--csv OUT.csv]
// Exit status: 0 ok, 2 bad input (one line naming the file and the field), 1 other failure.
#include "ffr/cli/cli.hpp"
#include "ffr/cli/output_files.hpp"
#include "ffr/runtime/runtime.hpp"
#include "stop_signals.hpp"
#include "vtk_series.hpp"

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace {

const ffr::cli::Command kCommand{
    "ffr-sim",
    R"(
Integrates the multibody model in MODEL.json (rigid and flexible bodies, joints, forces,
motions; flexible bodies from SID files) and writes the requested outputs to OUT.h5
(/time, /outputs/<name>; root attributes steps, newton_iterations, integration_seconds).

  -o, --output FILE   results file (HDF5), required
      --csv FILE      also write the outputs as CSV (one column per component, name[i])
      --vtk RUN.pvd   also write a ParaView collection: one frame RUN_frames/frame_NNNNNN.vtu
                      per output sample with every flexible body's deformed outer surface
                      (the SID's /visual; point data displacement, and von_mises where the
                      SID has a /stress group) and every rigid body as the STL surface
                      of its "visual" key, else as its inertia box
      --resume PART.h5
                      go on with the run that PART.h5 holds, stopped by a signal with
                      --keep-partial (same model and SID files, checked): -o gets the whole
                      run, the samples of the run never stopped (bit for bit; with the relative
                      formulation to rounding)
      --keep-partial  if the run stops with a solver error, still write the samples recorded
                      before it (to -o, --csv and --vtk; the results file's root attributes
                      stopped_at and stop_reason say where and why); the exit status stays 1.
                      SIGINT (Ctrl-C) or SIGTERM then stops the run after its current step
                      (adaptive steps: at the next output time) and writes what it has before
                      the process ends by the signal; another one a second or more later
                      ends it at once
  -q, --quiet         no progress and no notes on stderr
  -h, --help          this text
      --version       the version

Exit status: 0 ok, 2 bad input (malformed or inconsistent model, missing or bad SID file),
1 other failure (e.g. Newton divergence, reported with the time and the residual).
)",
    "ffr-sim MODEL.json -o OUT.h5 [--csv OUT.csv] [--vtk RUN.pvd] [--keep-partial] [--resume PART.h5] [--quiet]"};

int run(ffr::cli::Args& args) {
  using namespace ffr::runtime;
  auto out = args.option("-o");
  if (auto o = args.option("--output")) out = o;
  const auto csv = args.option("--csv");
  const auto vtk = args.option("--vtk");
  const bool quiet = args.flag("-q") || args.flag("--quiet");
  const bool keep_partial = args.flag("--keep-partial");
  const auto resume = args.option("--resume");
  const auto pos = args.positionals();
  if (pos.empty()) throw ffr::cli::UsageError("no model file given");
  if (pos.size() > 1) throw ffr::cli::UsageError("more than one model file given");
  if (!out) throw ffr::cli::UsageError("no results file given (-o OUT.h5)");

  Model model;
  try {
    model = load_model(pos[0]);
  } catch (const ModelError& e) {
    std::fprintf(stderr, "ffr-sim: error: %s\n", e.what());
    return 2;
  }
  // Before the run, which may take long: outputs that cannot be written or would replace an
  // input or each other.
  std::vector<ffr::cli::NamedPath> outputs{{"-o", *out}}, inputs{{"the model file", pos[0]}};
  if (csv) outputs.push_back({"--csv", *csv});
  if (vtk) outputs.push_back({"--vtk", *vtk});
  for (const auto& sid : model.sid_files) inputs.push_back({"the SID file", sid});
  if (resume) inputs.push_back({"the run to resume", *resume});
  if (resume && vtk)
    throw ffr::cli::UsageError("--vtk with --resume: the frames before the stop are not in the results file to resume "
                               "(resume without --vtk, or run the model again with it)");
  ffr::cli::check_outputs(outputs, inputs);
  // Checked before the run (a SID without a surface is bad input); adds its hidden outputs.
  std::optional<ffr::vtk::Series> series;
  if (vtk) series.emplace(*vtk, pos[0], model);
  try {
    Data data(model);
    std::vector<std::string> notes = model.notes;
    for (auto& n : initialize(model, data)) notes.push_back(std::move(n));
    if (!quiet)
      for (const auto& n : notes) std::fprintf(stderr, "ffr-sim: note: %s\n", n.c_str());
    // The recorder holds every recorded step from the start (the time loop allocates nothing).
    const std::int64_t rows = step_count(model) / std::max(1, model.settings.output_every) + 2;
    std::optional<Recorder> recorder;
    try {
      recorder.emplace(model, rows);
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "ffr-sim: error: %s: solver.output_every: the outputs of %lld recorded steps do not fit in memory; record fewer\n",
                   pos[0].c_str(), static_cast<long long>(rows));
      return 2;
    }
    Recorder& rec = *recorder;
    RunOptions opt;
    RunInfo resumed;  // the counts of the run resumed from
    if (resume) try {
        opt.resume = resume_from(*resume, model, data, rec, resumed);
      } catch (const ModelError& e) {
        std::fprintf(stderr, "ffr-sim: error: --resume %s\n", e.what());
        return 2;
      }
    bool reported = false;
    if (!quiet) {
      opt.progress_seconds = 2.0;
      // The time left is the elapsed time scaled by the simulated time left: a guess that holds
      // while the steps cost alike (an adaptive run's steps do not).
      const auto wall0 = std::chrono::steady_clock::now();
      opt.progress = [&, wall0](double t, double end) {
        const double s = model.settings.start, done = (t - s) / (end - s);
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
        std::fprintf(stderr, "\rffr-sim: t = %.6g of %.6g s (%.0f%%), %.0f s elapsed, about %.0f s left  ", t, end,
                     100.0 * done, elapsed, done > 0 ? elapsed * (1 - done) / done : 0.0);
        std::fflush(stderr);
        reported = true;
      };
    }
    const auto write = [&](const RunInfo& info) {
      if (series) {
        series->write_frames(model, rec);
        model.outputs.resize(series->user_outputs());  // the results file holds the model file's outputs only
      }
      write_results(*out, csv ? std::optional<std::filesystem::path>(*csv) : std::nullopt, model, rec, info);
      if (series) series->commit();
    };
    RunInfo stopped;
    opt.stopped = &stopped;
    std::optional<ffr::sim::StopOnSignals> signals;
    if (keep_partial) opt.stop = signals.emplace().flag();
    RunInfo info;
    try {
      info = simulate(model, data, rec, opt);
      add_counts(info, resumed);  // the whole run's: the run resumed from and this one
    } catch (const SolverError& e) {
      add_counts(stopped, resumed);
      if (reported) std::fputc('\n', stderr);
      std::fprintf(stderr, "ffr-sim: error: %s\n", e.what());
      const double last = rec.times()[rec.rows() - 1];
      if (keep_partial) {
        write(stopped);  // (simulate() filled it, stopped_at and stop_reason included)
        std::fprintf(stderr, "ffr-sim: the %lld samples to t = %.9g s written to %s (stopped_at %.9g s)\n",
                     static_cast<long long>(rec.rows()), last, out->c_str(), e.time());
      } else if (!quiet) {
        std::fprintf(stderr, "ffr-sim: note: nothing written; run again with --keep-partial to keep the %lld samples recorded to t = %.9g s\n",
                     static_cast<long long>(rec.rows()), last);
      }
      return 1;
    }
    if (reported) std::fputc('\n', stderr);
    if (info.stopped_at) {  // a signal asked the run to stop: what it has, then the signal's own end
      const int sig = signals->signal();
      info.stop_reason = std::string("interrupted by ") + (sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal");
      write(info);
      std::fprintf(stderr, "ffr-sim: %s at t = %.9g s; the %lld samples written to %s\n", info.stop_reason.c_str(),
                   *info.stopped_at, static_cast<long long>(rec.rows()), out->c_str());
      signals->reraise();
      return 1;  // (reached only if the signal no longer ends the process)
    }
    write(info);
    if (!quiet)
      std::fprintf(stderr, "ffr-sim: %lld steps, %lld Newton iterations, %lld tangents, %lld solves, %.3f s integration (%.2f us per step)\n",
                   static_cast<long long>(info.steps), static_cast<long long>(info.newton_iterations),
                   static_cast<long long>(info.factorizations), static_cast<long long>(info.solves),
                   info.integration_seconds,
                   info.steps ? 1e6 * info.integration_seconds / static_cast<double>(info.steps) : 0.0);
    return 0;
  } catch (const SolverError& e) {
    std::fprintf(stderr, "ffr-sim: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) { return ffr::cli::run_main(argc, argv, kCommand, run); }
