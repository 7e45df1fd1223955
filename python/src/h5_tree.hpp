#pragma once
// Every dataset and attribute of an HDF5 file as Python objects: numbers as numpy arrays of
// their stored shape (float64 or int64), strings as str or a list of str.
#include <pybind11/pybind11.h>

#include <string>

namespace ffr::python {

/// (datasets, attributes): {"/refmod/frequency_hz": array, ...} and
/// {"/": {"format": "ffr-sid", ...}, "/refmod": {...}, ...} (objects without attributes left out).
/// The caller has read the file strictly first; a failure here raises ffr.InputError naming it.
pybind11::tuple read_h5_tree(const std::string& path);

}  // namespace ffr::python
