// _ffr: the compiled half of the Python package (python/ffr/__init__.py is the other, with the
// argument checks and the documentation). Errors become the package's exceptions with the
// libraries' messages unchanged.
#include "errors.hpp"
#include "h5_tree.hpp"
#include "simulation.hpp"

#include "ffr/cli/output_files.hpp"
#include "ffr/cli/process_threads.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/stress_history.hpp"
#include "ffr/formats/validate.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "ffr/preproc/threads.hpp"
#include "ffr/version.hpp"

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <dlfcn.h>

#include <cstdio>
#include <exception>
#include <mutex>
#include <stdexcept>

namespace py = pybind11;

namespace ffr::python {
namespace {

// For the duration of one reduce(): the BLAS and OpenMP settings ffr-reduce runs with
// (process_threads.hpp says why), so that the SID is ffr-reduce's bit for bit (a dgemm's sums
// depend on its thread count); the caller's settings (numpy shares the BLAS) come back after.
class ReduceThreads {
 public:
  explicit ReduceThreads(const std::string& factorization) {
    get_blas_ = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    set_blas_ = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    get_levels_ = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
    set_levels_ = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
    if (get_blas_) blas_ = get_blas_();
    if (get_levels_) levels_ = get_levels_();
    cli::set_numerical_library_threads(cli::blas_threads_for(factorization.c_str(), preproc::max_threads()));
  }
  ~ReduceThreads() {
    if (set_blas_ && blas_ > 0) set_blas_(blas_);
    if (set_levels_ && levels_ >= 0) set_levels_(levels_);
  }
  ReduceThreads(const ReduceThreads&) = delete;
  ReduceThreads& operator=(const ReduceThreads&) = delete;

 private:
  int (*get_blas_)() = nullptr;
  void (*set_blas_)(int) = nullptr;
  int (*get_levels_)() = nullptr;
  void (*set_levels_)(int) = nullptr;
  int blas_ = -1, levels_ = -1;
};

// ffr-reduce without its command line: the same pipeline, validation and atomic write.
std::string reduce(const std::string& part_path, const std::string& output, py::object progress) {
  preproc::PipelineLog log;
  if (!progress.is_none())
    log.stage = [&progress](const std::string& s) {  // (by reference: no reference counting without the GIL)
      py::gil_scoped_acquire hold;
      progress(s);
    };
  std::exception_ptr failure;  // raised as a Python error once the GIL is held again
  {
    // Without the GIL (the pipeline may report progress from its own threads), one reduce at a
    // time: the BLAS settings above are the process's.
    py::gil_scoped_release free;
    static std::mutex one_at_a_time;
    const std::lock_guard<std::mutex> lock(one_at_a_time);
    try {
      const preproc::PartSpec part = preproc::load_part(part_path);
      cli::check_outputs({{"output", output}}, {{"the part file", part.file}, {"the part's geometry", part.geometry}});
      const ReduceThreads threads(part.reduction.factorization);
      const formats::Sid sid = preproc::run_pipeline(part, {}, log);
      const auto report = formats::validate(sid);
      if (!report.ok()) {
        std::string text;
        for (const auto& c : report.checks)
          if (c.applicable && !c.pass) {
            char nums[96];
            std::snprintf(nums, sizeof nums, ": violation %.3g (tolerance %.3g) ", c.rel, c.tol);
            text += "\n  " + c.name + nums + c.note;
          }
        throw std::runtime_error("the reduced body fails validation (nothing written):" + text);
      }
      formats::write_sid(sid, output);
    } catch (...) {
      failure = std::current_exception();
    }
  }
  if (failure) translated([&] { return std::rethrow_exception(failure), 0; });
  return output;
}

py::tuple read_sid(const std::string& path) {
  translated([&] { return formats::read_sid(path), 0; });  // strict: layout, identities of shape, checksums
  return read_h5_tree(path);
}

py::dict read_results(const std::string& path) {
  const formats::Results r = translated([&] { return formats::read_results(path); });
  py::dict out, values;
  py::array_t<double> t(r.time.size());
  for (Eigen::Index i = 0; i < r.time.size(); ++i) t.mutable_at(i) = r.time[i];
  for (const auto& o : r.outputs) {
    py::array_t<double> a({static_cast<py::ssize_t>(o.values.rows()), static_cast<py::ssize_t>(o.values.cols())});
    for (Eigen::Index i = 0; i < o.values.rows(); ++i)
      for (Eigen::Index j = 0; j < o.values.cols(); ++j) a.mutable_at(i, j) = o.values(i, j);
    values[py::str(o.name)] = a;
  }
  out["time"] = t;
  out["outputs"] = values;
  out["steps"] = static_cast<long long>(r.steps);
  out["newton_iterations"] = static_cast<long long>(r.newton_iterations);
  out["integration_seconds"] = r.integration_seconds;
  if (r.stopped_at) {  // a run that stopped before its end (ffr-sim --keep-partial)
    out["stopped_at"] = *r.stopped_at;
    out["stop_reason"] = r.stop_reason;
  }
  return out;
}

// ffr.stress(): the stress history of formats::recover_stress, the same numbers as
// `ffr-info --stress --json` (one implementation for both).
py::dict stress(const std::string& path, const std::string& body, const std::string& model) {
  const formats::StressHistory h = translated([&] { return formats::recover_stress(path, body, model); });
  const auto nt = static_cast<py::ssize_t>(h.time.size()), ns = static_cast<py::ssize_t>(h.node.size());
  py::array_t<double> t(nt), position({ns, py::ssize_t{3}}), vm({nt, ns}), principal({nt, ns, py::ssize_t{3}});
  py::array_t<std::int64_t> nodes(ns);
  py::list layer;
  for (py::ssize_t i = 0; i < nt; ++i) t.mutable_at(i) = h.time[i];
  for (py::ssize_t j = 0; j < ns; ++j) {
    nodes.mutable_at(j) = h.node[static_cast<std::size_t>(j)];
    layer.append(formats::layer_name(h.layer[static_cast<std::size_t>(j)]));
    for (py::ssize_t c = 0; c < 3; ++c) position.mutable_at(j, c) = h.position(j, c);
    const auto& P = h.principal[static_cast<std::size_t>(j)];
    for (py::ssize_t i = 0; i < nt; ++i) {
      vm.mutable_at(i, j) = h.von_mises(i, j);
      for (py::ssize_t c = 0; c < 3; ++c) principal.mutable_at(i, j, c) = P(i, c);
    }
  }
  py::dict out;
  out["body"] = h.body;
  out["sid"] = h.sid.string();
  out["output"] = h.output;
  out["selection"] = h.selection;
  out["time"] = t;
  out["nodes"] = nodes;
  out["position"] = position;
  out["layer"] = layer;
  out["von_mises"] = vm;
  out["principal"] = principal;
  return out;
}

PyObject* new_exception(py::module_& m, const char* name, PyObject* bases, const char* doc) {
  PyObject* type = PyErr_NewExceptionWithDoc((std::string("ffr.") + name).c_str(), doc, bases, nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::reinterpret_borrow<py::object>(type));
  return type;
}

}  // namespace
}  // namespace ffr::python

PYBIND11_MODULE(_ffr, m) {
  using namespace ffr::python;
  m.doc() = "ffr's compiled core; use the package ffr";
  auto& e = exceptions();
  e.error = new_exception(m, "Error", PyExc_Exception, "Base of ffr's errors.");
  e.input = new_exception(m, "InputError", py::make_tuple(py::handle(e.error), py::handle(PyExc_ValueError)).release().ptr(),
                          "Bad input: a part, model, SID or results file (the message names the file and the field).");
  e.solver = new_exception(m, "SolverError", py::make_tuple(py::handle(e.error), py::handle(PyExc_RuntimeError)).release().ptr(),
                           "The integration failed (the message names the time, the equation and what to try).");
  e.not_found = new_exception(m, "NotFoundError", py::make_tuple(py::handle(e.error), py::handle(PyExc_LookupError)).release().ptr(),
                              "No body, node, joint, motion or output of that name in the model.");
  m.attr("__version__") = ffr::kVersion;
  m.def("reduce", &reduce, py::arg("part"), py::arg("output"), py::arg("progress") = py::none());
  m.def("read_sid", &read_sid, py::arg("path"));
  m.def("read_h5", &read_h5_tree, py::arg("path"));
  m.def("read_results", &read_results, py::arg("path"));
  m.def("stress", &stress, py::arg("path"), py::arg("body"), py::arg("model"));
  bind_simulation(m);
}
