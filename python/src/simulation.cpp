#include "simulation.hpp"

#include "errors.hpp"
#include "sim_handle.hpp"  // runtime/src/capi: run() uses the handle's model and data

#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace py = pybind11;

namespace ffr::python {
namespace {

// A 3-vector from None (zeros), a sequence or an array of three finite numbers.
std::optional<std::vector<double>> vec3(py::object v, const char* what) {
  if (v.is_none()) return std::nullopt;
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 1 || a.size() != 3)
    raise(PyExc_TypeError, std::string("ffr.Simulation.set_load: ") + what + " must be three numbers (or None)");
  return std::vector<double>(a.data(), a.data() + 3);
}

}  // namespace

Simulation Simulation::from_file(const std::string& path) {
  ffr_sim* s = nullptr;
  const int status = ffr_open(path.c_str(), &s);
  Simulation sim(s);
  sim.check(status);
  return sim;
}

Simulation Simulation::from_text(const std::string& text, const std::string& base_dir, const std::string& name) {
  ffr_sim* s = nullptr;
  const int status = ffr_open_json(text.c_str(), base_dir.c_str(), name.c_str(), &s);
  Simulation sim(s);
  sim.check(status);
  return sim;
}

Simulation::~Simulation() { ffr_close(sim_); }

void Simulation::check(int status) const {
  if (status == FFR_OK) return;
  const auto& e = exceptions();
  const std::string msg = ffr_last_error();
  switch (status) {
    case FFR_ERROR_INPUT: raise(e.input, msg);
    case FFR_ERROR_SOLVER: raise(e.solver, msg);
    case FFR_ERROR_ARGUMENT: raise(PyExc_ValueError, msg);
    case FFR_ERROR_NOT_FOUND: raise(e.not_found, msg);
    default: raise(e.error, msg);
  }
}

double Simulation::time() const {
  double t = 0;
  check(ffr_time(sim_, &t));
  return t;
}

double Simulation::step_size() const {
  double h = 0;
  check(ffr_step_size(sim_, &h));
  return h;
}

double Simulation::end() const { return sim_->model.settings.end; }

py::list Simulation::outputs() const {
  py::list l;
  for (const auto& o : sim_->model.outputs) l.append(o.name);
  return l;
}

// The GIL stays held while the runtime works: a handle is not thread-safe, and holding it keeps
// another Python thread from calling into the same handle meanwhile.
void Simulation::step(int n) { check(ffr_step(sim_, n)); }

void Simulation::reinitialize() { check(ffr_reinitialize(sim_)); }

py::array_t<double> Simulation::output(const std::string& name) {
  int k = 0;
  check(ffr_output_size(sim_, name.c_str(), &k));
  py::array_t<double> a(k);
  check(ffr_get_output(sim_, name.c_str(), a.mutable_data(), k));
  return a;
}

void Simulation::set_load(const std::string& body, std::optional<std::string> node, py::object force, py::object torque) {
  const auto f = vec3(force, "force"), tau = vec3(torque, "torque");
  check(ffr_set_load(sim_, body.c_str(), node ? node->c_str() : nullptr, f ? f->data() : nullptr,
                     tau ? tau->data() : nullptr));
}

void Simulation::clear_loads() { check(ffr_clear_loads(sim_)); }

void Simulation::set_motion(const std::string& joint, double value, double rate, double acceleration) {
  check(ffr_set_motion(sim_, joint.c_str(), value, rate, acceleration));
}

void Simulation::release_motion(const std::string& joint) { check(ffr_release_motion(sim_, joint.c_str())); }

py::array_t<double> Simulation::state() const {
  int n = 0;
  check(ffr_state_size(sim_, &n));
  py::array_t<double> a(n);
  check(ffr_save_state(sim_, a.mutable_data(), n));
  return a;
}

void Simulation::set_state(py::object state) {
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(state);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 1)
    raise(PyExc_TypeError, "ffr.Simulation.set_state: expected the 1-D array of numbers that state() returned");
  check(ffr_restore_state(sim_, a.data(), static_cast<int>(a.size())));
}

py::dict Simulation::stats() const {
  long long steps = 0, iterations = 0;
  check(ffr_stats(sim_, &steps, &iterations));
  py::dict d;
  d["steps"] = steps;
  d["newton_iterations"] = iterations;
  return d;
}

py::dict Simulation::run() {
  using namespace ffr::runtime;
  const Model& model = sim_->model;
  Data& data = *sim_->data;
  const auto& s = model.settings;
  // The step (or output) index of the current time, counted from the start as simulate() does.
  const double interval = s.adaptive ? s.output_interval : s.step;
  const std::int64_t n = step_count(model);
  const std::int64_t i0 = std::llround((data.state.t - s.start) / interval);
  const int every = s.adaptive ? 1 : std::max(1, s.output_every);
  const std::int64_t rows = (n > i0 ? (n - i0) / every : 0) + 2;
  // Steps as ffr-sim counts them: with adaptive steps the accepted ones.
  auto steps_now = [&] { return sim_->control ? sim_->control->accepted : data.stats.steps; };
  const std::int64_t steps0 = steps_now(), iterations0 = data.stats.newton_iterations;
  std::optional<Recorder> recorder;
  translated([&] { return recorder.emplace(model, rows), 0; });
  Recorder& rec = *recorder;
  // The rows recorded so far as the dict run() returns.
  const auto collect = [&] {
    py::dict out, values;
    const auto nt = static_cast<py::ssize_t>(rec.rows());
    py::array_t<double> t(nt);
    for (py::ssize_t r = 0; r < nt; ++r) t.mutable_at(r) = rec.times()[r];
    for (std::size_t o = 0; o < model.outputs.size(); ++o) {
      const auto& m = rec.values(o);
      py::array_t<double> a({nt, static_cast<py::ssize_t>(m.cols())});
      for (py::ssize_t r = 0; r < nt; ++r)
        for (py::ssize_t c = 0; c < m.cols(); ++c) a.mutable_at(r, c) = m(r, c);
      values[py::str(model.outputs[o].name)] = a;
    }
    out["time"] = t;
    out["outputs"] = values;
    out["steps"] = static_cast<long long>(steps_now() - steps0);
    out["newton_iterations"] = static_cast<long long>(data.stats.newton_iterations - iterations0);
    return out;
  };
  // (The GIL stays held: see step(). A failed step leaves the last accepted state, as ffr_step.)
  try {
    rec.record(model, data);
    for (std::int64_t i = i0 + 1; i <= n; ++i) {
      save_state(data, *sim_->last);
      try {
        if (sim_->control) advance_to(model, data, *sim_->control, output_time(model, i));
        else ffr::runtime::step(model, data);
      } catch (...) {
        restore_state(*sim_->last, data);
        throw;
      }
      if (i % every == 0 || i == n) rec.record(model, data);
      // The GIL is held, so Python's own handlers (Ctrl-C's KeyboardInterrupt) run only here:
      // the run stops after this step, the simulation at it (run() again goes on from there).
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  } catch (const SolverError& e) {
    // ffr.SolverError with the rows before the failed step as its `results` (what ffr-sim
    // --keep-partial writes), marked with where and why it stopped.
    py::dict partial = collect();
    partial["stopped_at"] = e.time();
    partial["stop_reason"] = e.what();
    py::object error = py::reinterpret_borrow<py::object>(exceptions().solver)(py::str(e.what()));
    error.attr("results") = partial;
    PyErr_SetObject(exceptions().solver, error.ptr());
    throw py::error_already_set();
  } catch (...) {
    raise_current();
  }
  return collect();
}

}  // namespace ffr::python

namespace ffr::python {

void bind_simulation(py::module_& m) {
  py::class_<Simulation>(m, "Simulation")
      .def_static("_from_file", &Simulation::from_file)
      .def_static("_from_text", &Simulation::from_text)
      .def_property_readonly("time", &Simulation::time)
      .def_property_readonly("step_size", &Simulation::step_size)
      .def_property_readonly("end", &Simulation::end)
      .def_property_readonly("outputs", &Simulation::outputs)
      .def("step", &Simulation::step, py::arg("n") = 1)
      .def("reinitialize", &Simulation::reinitialize)
      .def("output", &Simulation::output, py::arg("name"))
      .def("set_load", &Simulation::set_load, py::arg("body"), py::arg("node") = py::none(),
           py::arg("force") = py::none(), py::arg("torque") = py::none())
      .def("clear_loads", &Simulation::clear_loads)
      .def("set_motion", &Simulation::set_motion, py::arg("joint"), py::arg("value"), py::arg("rate") = 0.0,
           py::arg("acceleration") = 0.0)
      .def("release_motion", &Simulation::release_motion, py::arg("joint"))
      .def("state", &Simulation::state)
      .def("set_state", &Simulation::set_state, py::arg("state"))
      .def("stats", &Simulation::stats)
      .def("run", &Simulation::run);
}

}  // namespace ffr::python
