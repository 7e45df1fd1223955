#pragma once
// Requested outputs, their recording during a run, and the results file (contract "Model file":
// /time [nt], /outputs/<name> [nt, k], root attributes steps, newton_iterations,
// integration_seconds; optional CSV with one column per component headed name[i]).

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"
#include "ffr/runtime/step_control.hpp"

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
  /// Appends a row of known values, one vector per output (the samples of a partial run that
  /// a resumed run goes on from). Throws std::invalid_argument on a wrong count or size.
  void append(double t, const std::vector<Eigen::VectorXd>& values);
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
  /// After a stop request: the state reached (step_control.hpp's pack_run, as the C API's
  /// ffr_save_state packs it), from which RunOptions::resume goes on. Empty otherwise.
  std::vector<double> restart;
};

/// Adds `part`'s counts (steps, iterations, factorizations, solves, seconds) to `total`'s: a
/// resumed run's and those of the run it goes on from.
void add_counts(RunInfo& total, const RunInfo& part);

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
  /// Set: data's state is one the run reached (restored from RunInfo::restart), at one of its
  /// steps (with adaptive steps at one of its output times); the run goes on from there to its
  /// end, the steps and samples those of the run never stopped, the state's own sample not
  /// recorded again.
  std::optional<ResumePoint> resume;
};

/// Number of steps of the run (end - start) / step, rounded; with "step": "auto", the number of
/// output intervals (one record each).
std::int64_t step_count(const Model& model);

/// Runs from data's (initialised) state to settings.end, recording every output_every steps.
/// A failed step throws SolverError; the recorder then holds the samples before it.
RunInfo simulate(const Model& model, Data& data, Recorder& rec, const RunOptions& opt = {});

/// The identity of a run's inputs: SHA-256 over the SHA-256 digests of the model file and its SID files; ""
/// when the model file cannot be read again (a pipe). A results file holding a restart state
/// carries it, so that a run resumed from it is known to be of the same model.
std::string input_identity(const Model& model);

/// Prepares the resumption of the interrupted run whose results file (ffr-sim --keep-partial,
/// stopped by a stop request: its /restart state) is `path`: appends its samples on the run's
/// own schedule to `rec` (those the run never stopped records), restores its state into `data`
/// (initialised), sets `counts` to its counts and returns the point for RunOptions::resume.
/// Throws ModelError naming the file: no restart state (a run that failed, or a complete one),
/// inputs that changed since (model or SID files), outputs that differ.
ResumePoint resume_from(const std::filesystem::path& path, const Model& model, Data& data, Recorder& rec, RunInfo& counts);

/// Writes the results file (HDF5) and, if asked, the same outputs as CSV. Both go to temporary
/// names first and are renamed into place only when both are complete: a failure leaves neither.
void write_results(const std::filesystem::path& h5_path, const std::optional<std::filesystem::path>& csv_path,
                   const Model& model, const Recorder& rec, const RunInfo& info);

}  // namespace ffr::runtime
