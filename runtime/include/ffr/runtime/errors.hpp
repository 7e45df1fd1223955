#pragma once
// The two ways the runtime refuses to go on, kept apart because the caller reacts differently:
// a ModelError is the user's input (exit status 2 in ffr-sim), a SolverError is the physics or
// the numerics failing on valid input (exit status 1).

#include <stdexcept>
#include <string>

namespace ffr::runtime {

/// Bad input: names the file and the offending field ("bodies[1].mass", "/refmod/mass", ...).
class ModelError : public std::runtime_error {
 public:
  ModelError(std::string file, std::string field, const std::string& what)
      : std::runtime_error(file + ": " + (field.empty() ? std::string() : field + ": ") + what),
        file_(std::move(file)), field_(std::move(field)) {}
  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }

 private:
  std::string file_, field_;
};

/// The integration could not proceed (Newton divergence, singular tangent, NaN state).
class SolverError : public std::runtime_error {
 public:
  SolverError(double time, double residual, const std::string& what)
      : std::runtime_error(what), time_(time), residual_(residual) {}
  double time() const { return time_; }
  double residual() const { return residual_; }

 private:
  double time_, residual_;
};

}  // namespace ffr::runtime
