#pragma once
// The package's exceptions (created in module.cpp, documented in ffr/__init__.py) and the
// translation of the libraries' C++ errors into them, with the libraries' messages unchanged.
#include <pybind11/pybind11.h>

#include <string>

namespace ffr::python {

struct Exceptions {
  PyObject* error = nullptr;      ///< ffr.Error: base of the three below
  PyObject* input = nullptr;      ///< ffr.InputError (also ValueError): bad part, model, SID or results file
  PyObject* solver = nullptr;     ///< ffr.SolverError (also RuntimeError): the integration failed
  PyObject* not_found = nullptr;  ///< ffr.NotFoundError (also LookupError): no body, node, joint, output ...
};

Exceptions& exceptions();

/// Raises `type` with `message` (throws pybind11::error_already_set).
[[noreturn]] void raise(PyObject* type, const std::string& message);

/// Runs f(); formats::FormatError and runtime::ModelError become InputError, runtime::SolverError
/// SolverError, std::invalid_argument ValueError, other std::exception ffr.Error.
template <class F>
auto translated(F&& f) -> decltype(f());

void raise_current();  ///< the translation of the exception being handled

template <class F>
auto translated(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const pybind11::error_already_set&) {
    throw;
  } catch (...) {
    raise_current();
    throw;  // not reached
  }
}

}  // namespace ffr::python
