#pragma once
// ffr.Simulation: one ffr_sim handle of the C interface (ffr_runtime.h), so Python drives the
// runtime exactly as a C program does; run() records like ffr-sim's time loop.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>

struct ffr_sim;

namespace ffr::python {

class Simulation {
 public:
  /// From a model file, or from the model's JSON text with relative paths against base_dir.
  static Simulation from_file(const std::string& path);
  static Simulation from_text(const std::string& text, const std::string& base_dir, const std::string& name);
  Simulation(Simulation&& o) noexcept : sim_(o.sim_) { o.sim_ = nullptr; }
  Simulation(const Simulation&) = delete;
  ~Simulation();

  double time() const;
  double step_size() const;
  double end() const;
  pybind11::list outputs() const;
  void step(int n);
  void reinitialize();
  pybind11::array_t<double> output(const std::string& name);
  void set_load(const std::string& body, std::optional<std::string> node, pybind11::object force, pybind11::object torque);
  void clear_loads();
  void set_motion(const std::string& joint, double value, double rate, double acceleration);
  void release_motion(const std::string& joint);
  pybind11::array_t<double> state() const;
  void set_state(pybind11::object state);
  pybind11::dict stats() const;
  /// From the current time to the model's end: {"time": [nt], "outputs": {name: [nt, k]}, ...},
  /// the current state as the first row; from the start, the rows of ffr-sim's results file.
  pybind11::dict run();

 private:
  explicit Simulation(ffr_sim* s) : sim_(s) {}
  void check(int status) const;
  ffr_sim* sim_ = nullptr;
};

void bind_simulation(pybind11::module_& m);

}  // namespace ffr::python
