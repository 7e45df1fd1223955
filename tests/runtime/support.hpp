#pragma once
// Helpers shared by the runtime tests.

#include "ffr/runtime/runtime.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ffr::runtime::test {

/// A fresh temporary directory for one test (removed by the destructor).
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag);
  ~TempDir();
  std::filesystem::path operator/(const std::string& f) const { return path / f; }
};

/// Writes text to a file.
void write_text(const std::filesystem::path& p, const std::string& text);

/// A compound pendulum: a 1 m bar of 20 x 20 mm section, 1 kg, hinged at one end about y,
/// horizontal at the start (its x axis along x), turning at `rate` rad/s about +y (down). `solver`
/// is the value of the model's "solver" key; the output "angle" is the hinge's angle.
constexpr double kPendulumMass = 1.0, kPendulumIyy = 0.08336666666666667, kPendulumD = 0.5, kPendulumG = 9.81;
std::string compound_pendulum_json(const std::string& solver, double rate = 0);

/// An independent oracle for it: theta'' = m g d cos(theta) / I_O from theta = 0, theta' = rate
/// (the angle about +y turns the bar's x axis towards -z), classical Runge-Kutta at 2e5 steps.
/// Returns theta at `end` (and theta' in *theta_dot).
double compound_pendulum_oracle(double end, double rate = 0, double* theta_dot = nullptr);

/// Parses a model from JSON text with relative paths resolved in `dir`.
Model model_from(const std::string& json, const std::filesystem::path& dir = {});

/// The message of the ModelError thrown while parsing `json` (in dir), or "" if none.
std::string error_of(const std::string& json, const std::filesystem::path& dir = {});
/// Expects parsing `json` to be refused with a message naming the file (test-model.json), the
/// field and what is wrong.
void expect_error(const std::string& json, const std::string& field, const std::string& what,
                  const std::filesystem::path& dir = {});

/// What a run of build/bin/ffr-sim gave: its exit status (-1 if it did not exit) and its
/// stdout and stderr together.
struct SimRun {
  int status = -1;
  std::string output;
};
/// Runs `ffr-sim ARGS` (ARGS as a shell would split them).
SimRun run_ffr_sim(const std::string& args);

/// The values of the output named `name` at the current state (evaluate_output); a missing name
/// fails the test.
std::vector<double> output(const Model& model, Data& data, const std::string& name);

/// The message of the SolverError that initialize throws on `model` (empty if none).
std::string initialize_refusal(const Model& model);

/// Two models of the same coordinates stepped side by side from their initial states, over the
/// first's step count: the largest scaled distance between their coordinates after a step, the
/// largest scaled motion of the first from its start (how far there was to go astray), the
/// first's largest constraint violation after a step, and each one's Newton iterations a step.
struct SideBySide {
  double apart = 0;
  double motion = 0;
  double violation = 0;
  double iterations_a = 0, iterations_b = 0;
};
SideBySide step_side_by_side(const Model& a, const Model& b);

}  // namespace ffr::runtime::test
