#include "errors.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/runtime/errors.hpp"

#include <new>
#include <stdexcept>

namespace ffr::python {

Exceptions& exceptions() {
  static Exceptions e;
  return e;
}

void raise(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw pybind11::error_already_set();
}

void raise_current() {
  const auto& e = exceptions();
  try {
    throw;
  } catch (const pybind11::error_already_set&) {
    throw;
  } catch (const formats::FormatError& x) {
    raise(e.input, x.what());
  } catch (const runtime::ModelError& x) {
    raise(e.input, x.what());
  } catch (const runtime::SolverError& x) {
    raise(e.solver, x.what());
  } catch (const std::invalid_argument& x) {
    raise(PyExc_ValueError, x.what());
  } catch (const std::bad_alloc&) {
    raise(PyExc_MemoryError, "out of memory");
  } catch (const std::exception& x) {
    raise(e.error, x.what());
  }
}

}  // namespace ffr::python
