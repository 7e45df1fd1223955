// A plain walk over the file with the HDF5 C library: the strict readers of ffr::formats check
// the layout, this gives the user every stored value as it is, bit for bit.
#include "h5_tree.hpp"

#include "errors.hpp"

#include <hdf5.h>
#include <pybind11/numpy.h>

#include <cstdint>
#include <vector>

namespace py = pybind11;

namespace ffr::python {
namespace {

struct Id {  // closes an HDF5 identifier with its own function
  hid_t id;
  herr_t (*close)(hid_t);
  ~Id() {
    if (id >= 0) close(id);
  }
};

[[noreturn]] void fail(const std::string& file, const std::string& object, const std::string& what) {
  raise(exceptions().input, file + ": " + object + ": " + what);
}

std::vector<py::ssize_t> extent(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(rank > 0 ? rank : 0);
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return {dims.begin(), dims.end()};
}

py::ssize_t count(const std::vector<py::ssize_t>& shape) {
  py::ssize_t n = 1;
  for (auto d : shape) n *= d;
  return n;
}

// Strings of a dataset or attribute (variable or fixed length); `read` reads into the buffer
// with a memory type.
template <class Read>
py::object strings(hid_t stored, const std::vector<py::ssize_t>& shape, Read&& read) {
  const auto n = static_cast<std::size_t>(count(shape));
  std::vector<std::string> out(n);
  if (H5Tis_variable_str(stored) > 0) {
    Id mem{H5Tcopy(H5T_C_S1), H5Tclose};
    H5Tset_size(mem.id, H5T_VARIABLE);
    H5Tset_cset(mem.id, H5Tget_cset(stored));
    std::vector<char*> p(n, nullptr);
    if (read(mem.id, p.data()) < 0) return py::none();
    for (std::size_t i = 0; i < n; ++i) out[i] = p[i] ? p[i] : "";
    for (auto* s : p) H5free_memory(s);
  } else {
    const std::size_t len = H5Tget_size(stored);
    Id mem{H5Tcopy(H5T_C_S1), H5Tclose};
    H5Tset_size(mem.id, len);
    H5Tset_strpad(mem.id, H5T_STR_NULLPAD);
    H5Tset_cset(mem.id, H5Tget_cset(stored));
    std::vector<char> buf(n * len + 1, 0);
    if (read(mem.id, buf.data()) < 0) return py::none();
    for (std::size_t i = 0; i < n; ++i) {
      const char* s = buf.data() + i * len;
      std::size_t k = 0;
      while (k < len && s[k]) ++k;
      out[i] = std::string(s, k);
    }
  }
  if (shape.empty()) return py::str(out[0]);
  py::list l;
  for (auto& s : out) l.append(py::str(s));
  return l;
}

// A numeric or string value read by `read(memory type, buffer)`.
template <class Read>
py::object value(hid_t stored, hid_t space, Read&& read) {
  const auto shape = extent(space);
  switch (H5Tget_class(stored)) {
    case H5T_FLOAT: {
      py::array_t<double> a(shape);
      if (read(H5T_NATIVE_DOUBLE, a.mutable_data()) < 0) return py::none();
      return shape.empty() ? py::object(py::float_(*a.data())) : py::object(a);
    }
    case H5T_INTEGER: {
      py::array_t<std::int64_t> a(shape);
      if (read(H5T_NATIVE_INT64, a.mutable_data()) < 0) return py::none();
      return shape.empty() ? py::object(py::int_(*a.data())) : py::object(a);
    }
    case H5T_STRING:
      return strings(stored, shape, read);
    default:
      return py::none();
  }
}

struct Walk {
  std::string file;
  py::dict datasets, attributes;
};

// Attributes by index, outside any HDF5 callback (a Python error must not unwind through C).
void attributes_of(Walk& w, hid_t object, const std::string& path) {
  H5O_info_t info{};
  if (H5Oget_info2(object, &info, H5O_INFO_NUM_ATTRS) < 0) fail(w.file, path, "cannot read its attributes");
  py::dict attrs;
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    Id a{H5Aopen_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
    if (a.id < 0) fail(w.file, path, "cannot open attribute " + std::to_string(i));
    const ssize_t len = H5Aget_name(a.id, 0, nullptr);
    std::string name(len > 0 ? static_cast<std::size_t>(len) : 0, '\0');
    if (len > 0) H5Aget_name(a.id, name.size() + 1, name.data());
    Id type{H5Aget_type(a.id), H5Tclose};
    Id space{H5Aget_space(a.id), H5Sclose};
    py::object v = value(type.id, space.id, [&](hid_t mem, void* buf) { return H5Aread(a.id, mem, buf); });
    if (v.is_none()) fail(w.file, path, "attribute " + name + " is not a number or string");
    attrs[py::str(name)] = v;
  }
  if (py::len(attrs)) w.attributes[py::str(path)] = attrs;
}

struct Entry {
  std::string name;
  H5O_type_t type;
};

// Only collects (no Python, no exceptions inside the C library's walk).
herr_t on_object(hid_t, const char* name, const H5O_info_t* info, void* op) {
  static_cast<std::vector<Entry>*>(op)->push_back({name, info->type});
  return 0;
}

void read_object(Walk& w, hid_t file, const Entry& e) {
  const std::string path = e.name == "." ? "/" : "/" + e.name;
  Id object{H5Oopen(file, e.name.c_str(), H5P_DEFAULT), H5Oclose};
  if (object.id < 0) fail(w.file, path, "cannot open");
  attributes_of(w, object.id, path);
  if (e.type != H5O_TYPE_DATASET) return;
  Id type{H5Dget_type(object.id), H5Tclose};
  Id space{H5Dget_space(object.id), H5Sclose};
  py::object v = value(type.id, space.id, [&](hid_t mem, void* buf) {
    return H5Dread(object.id, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  });
  if (v.is_none()) fail(w.file, path, "cannot read the dataset (not a number or string)");
  w.datasets[py::str(path)] = v;
}

}  // namespace

py::tuple read_h5_tree(const std::string& path) {
  Walk w{path, {}, {}};
  Id file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (file.id < 0) fail(path, "/", "cannot open as HDF5");
  std::vector<Entry> entries;
  if (H5Ovisit2(file.id, H5_INDEX_NAME, H5_ITER_INC, on_object, &entries, H5O_INFO_BASIC) < 0)
    fail(path, "/", "cannot walk the file");
  for (const auto& e : entries) read_object(w, file.id, e);
  return py::make_tuple(w.datasets, w.attributes);
}

}  // namespace ffr::python
