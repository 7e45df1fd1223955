#pragma once
// Requested outputs, their recording during a run, and the results file (contract "Model file":
// /time [nt], /outputs/<name> [nt, k], root attributes steps, newton_iterations,
// integration_seconds; optional CSV with one column per component headed name[i]).

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ffr::runtime {

/// Writes output `o` at the current state into out[0 .. o.size).
void evaluate_output(const Model& model, Data& data, const Output& o, double* out);

/// The force and torque (global components, the torque about marker 2's point: the joint point)
/// that body1 exerts on body2 through joint `joint`, with the force or torque of a motion
/// prescribed on it, from the multipliers data.reaction_lambda (FORMULATION.md 13). Needs update_markers.
Vector6d joint_reaction(const Model& model, const Data& data, int joint);

/// A force element's force in the current state: a spring_damper's tension or a friction_damper's
/// force (one value, positive pulling its ends together), a bushing's force and torque on body2 (six values, global
/// components, the torque about its point), a tire's contact forces and slips (six values: Fx, Fy, Fn
/// along the contact frame's rolling, lateral and normal directions, the longitudinal slip, the
/// slip angle [rad] and the deflection [m]; MODEL_FILE.md "Outputs"). Needs update_markers.
void element_force(const Model& model, const Data& data, ForceElementKind kind, int index, double* out);

/// Preallocated storage for every output at every recorded time.
class Recorder {
 public:
  Recorder(const Model& model, std::int64_t max_rows);
  /// Appends a row (no allocation while rows < max_rows).
  void record(const Model& model, Data& data);
  std::int64_t rows() const { return rows_; }
  const VectorXd& times() const { return t_; }
  const MatrixXd& values(std::size_t output) const { return v_[output]; }

 private:
  std::int64_t rows_ = 0;
  VectorXd t_;
  std::vector<MatrixXd> v_;  ///< [max_rows, k]
  VectorXd row_;
};

struct RunInfo {
  std::int64_t steps = 0;
  std::int64_t newton_iterations = 0;
  std::int64_t factorizations = 0;  ///< tangents built and factorised
  std::int64_t solves = 0;          ///< solves with a factorised tangent (Newton, projections)
  double integration_seconds = 0;
  /// A run that did not reach its end (results file attributes stopped_at and stop_reason): the
  /// time of the step that failed with a SolverError and its message, or the time reached when
  /// RunOptions::stop asked it to stop; empty for a run that reached its end.
  std::optional<double> stopped_at;
  std::string stop_reason;
};

struct RunOptions {
  /// Called from the time loop (at most every `progress_seconds` of wall time) with t and end.
  std::function<void(double t, double end)> progress;
  double progress_seconds = 1.0;
  /// If set, filled with the counts up to a SolverError, its time and message, before the
  /// error leaves simulate(): what a results file of the samples recorded so far reports.
  RunInfo* stopped = nullptr;
  /// If set and nonzero (a signal handler of the caller sets it), the run stops after its current
  /// step (with adaptive steps: at its next output time), records that state and returns with
  /// stopped_at set and stop_reason "stop requested", for the caller to say why.
  const std::atomic<int>* stop = nullptr;
};

/// Number of steps of the run (end - start) / step, rounded; with "step": "auto", the number of
/// output intervals (one record each).
std::int64_t step_count(const Model& model);

/// Runs from data's (initialised) state to settings.end, recording every output_every steps.
/// A failed step throws SolverError; the recorder then holds the samples before it.
RunInfo simulate(const Model& model, Data& data, Recorder& rec, const RunOptions& opt = {});

/// Writes the results file (HDF5) and, if asked, the same outputs as CSV. Both go to temporary
/// names first and are renamed into place only when both are complete: a failure leaves neither.
void write_results(const std::filesystem::path& h5_path, const std::optional<std::filesystem::path>& csv_path,
                   const Model& model, const Recorder& rec, const RunInfo& info);

}  // namespace ffr::runtime
