// Going on with an interrupted run: the identity of its inputs, and its results file read back
// into the recorder and the state (ffr-sim --resume).
#include "ffr/formats/h5.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sha256.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/outputs.hpp"
#include "ffr/runtime/state.hpp"
#include "ffr/runtime/step_control.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffr::runtime {

std::string input_identity(const Model& model) {
  if (!std::filesystem::is_regular_file(model.source)) return "";
  std::vector<std::string> files{model.source};
  files.insert(files.end(), model.sid_files.begin(), model.sid_files.end());
  formats::Sha256 h;
  for (const std::string& f : files) {
    const std::string d = formats::sha256_file(f);
    if (d.empty()) return "";
    h.update(d.data(), d.size());
  }
  return h.hex();
}

ResumePoint resume_from(const std::filesystem::path& path, const Model& model, Data& data, Recorder& rec, RunInfo& counts) {
  const std::string file = path.string();
  const formats::Results partial = formats::read_results(path);
  const formats::h5::Reader r(path);
  if (!r.exists("/restart/state"))
    throw ModelError(file, "/restart", "no state to resume from: only a run stopped by a signal with --keep-partial can be "
                                       "resumed (a run that failed needs a change to the model, and a run again)");
  const std::string here = input_identity(model);
  if (here.empty()) throw ModelError(model.source, "", "a model read from a pipe cannot be resumed (its inputs cannot be checked)");
  if (!r.has_attr("/restart", "inputs_sha256") || r.attr_string("/restart", "inputs_sha256") != here)
    throw ModelError(file, "/restart@inputs_sha256", "the model file or its SID files changed since this run was stopped; "
                                                     "resume it only with the inputs it ran with");
  const auto shape = r.shape("/restart/state");
  const int n = packed_run_size(model);
  if (shape.size() != 1 || shape[0] != static_cast<std::uint64_t>(n))
    r.fail("/restart/state", "wrong shape: expected [" + std::to_string(n) + "], found " + formats::h5::shape_string(shape));
  const std::vector<double> restart = r.read_array("/restart/state", shape);

  // Its samples, on the schedule of the run never stopped: with a fixed step every
  // output_every-th step (the stop's own sample between them is not one of them).
  const auto& s = model.settings;
  const int every = s.adaptive ? 1 : std::max(1, s.output_every);
  std::vector<const formats::Results::Output*> columns;
  for (const Output& o : model.outputs) {
    const auto* c = partial.find(o.name);
    if (!c || c->values.cols() != o.size)
      throw ModelError(file, "/outputs/" + o.name, "missing or of another size than the model's output");
    columns.push_back(c);
  }
  std::vector<Eigen::VectorXd> row(columns.size());
  const double interval = s.adaptive ? s.output_interval : s.step;
  for (Eigen::Index k = 0; k < partial.time.size(); ++k) {
    const std::int64_t i = std::llround((partial.time[k] - s.start) / interval);
    if (i % every != 0) continue;
    for (std::size_t c = 0; c < columns.size(); ++c) row[c] = columns[c]->values.row(k).transpose();
    rec.append(partial.time[k], row);
  }

  State state(model);
  ResumePoint point;
  try {
    point = unpack_run(model, restart.data(), n, state);
  } catch (const std::invalid_argument& e) {
    throw ModelError(file, "/restart/state", e.what());
  }
  restore_state(state, data);
  counts = RunInfo{};
  counts.steps = partial.steps;
  counts.newton_iterations = partial.newton_iterations;
  counts.factorizations = r.attr_int("/", "factorizations");
  counts.solves = r.attr_int("/", "solves");
  counts.integration_seconds = partial.integration_seconds;
  return point;
}

}  // namespace ffr::runtime
