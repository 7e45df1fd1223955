#include "ffr/formats/h5.hpp"

#include "ffr/formats/content_checksum.hpp"
#include "ffr/formats/stale_temp.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fcntl.h>
#include <limits>
#include <random>
#include <sstream>
#include <unistd.h>

namespace ffr::formats {

FormatError::FormatError(std::string file, std::string object, const std::string& what)
    : std::runtime_error(file + (object.empty() ? std::string() : ": " + object) + ": " + what),
      file_(std::move(file)),
      object_(std::move(object)),
      detail_(what) {}

namespace h5 {
namespace {

// HDF5 prints its error stack to stderr by default; a library must not print.
struct SilenceHdf5 {
  SilenceHdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }
};
void silence() { static SilenceHdf5 once; }

constexpr std::uint64_t kChunkTargetElements = 1u << 17;  // 1 MiB of doubles per chunk

herr_t walk_innermost(unsigned n, const H5E_error2_t* err, void* data) {
  // The stack is walked from the innermost (n == 0) outwards; keep the innermost text.
  auto* out = static_cast<std::string*>(data);
  if (n == 0 && err && err->desc) *out = err->desc;
  return 0;
}

std::string parent_of(const std::string& path) {
  const auto pos = path.find_last_of('/');
  return pos == 0 || pos == std::string::npos ? "/" : path.substr(0, pos);
}

std::uint64_t product(const Shape& s) {
  std::uint64_t p = 1;
  for (auto d : s) p *= d;
  return p;
}

// File image callbacks that let HDF5 use the caller's bytes where it would copy them (into the
// property list, each copy of the list, the core driver): the image is opened read-only, so
// nothing writes to it, and the caller keeps it alive as long as the Reader (h5.hpp). What
// HDF5 reads is the same bytes; only the copies (three of the whole file per open) are spared.
// The scheme of the high-level library's H5LTopen_file_image with H5LT_FILE_IMAGE_DONT_COPY,
// without linking that library. HDF5 copies the user data with every
// copy of the property list (the file keeps one until it is closed): counted, freed with the last.
struct BorrowedImage {
  const void* bytes;
  std::size_t size;
  int users;
};
void* image_malloc(std::size_t size, H5FD_file_image_op_t, void* udata) {
  auto* image = static_cast<BorrowedImage*>(udata);
  return size == image->size ? const_cast<void*>(image->bytes) : nullptr;
}
void* image_memcpy(void* dest, const void* src, std::size_t size, H5FD_file_image_op_t, void* udata) {
  auto* image = static_cast<BorrowedImage*>(udata);
  return dest == image->bytes && src == image->bytes && size == image->size ? dest : nullptr;
}
void* image_realloc(void*, std::size_t, H5FD_file_image_op_t, void*) { return nullptr; }
herr_t image_free(void*, H5FD_file_image_op_t, void*) { return 0; }
void* image_udata_copy(void* udata) {
  ++static_cast<BorrowedImage*>(udata)->users;
  return udata;
}
herr_t image_udata_free(void* udata) {
  auto* image = static_cast<BorrowedImage*>(udata);
  if (--image->users == 0) delete image;
  return 0;
}

}  // namespace

namespace {
void check_chunks(const Reader& r, const std::string& path, hid_t ds);
}  // namespace

std::string last_error_text() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, walk_innermost, &text);
  return text;
}

std::string shape_string(const Shape& s) {
  std::ostringstream o;
  o << '[';
  for (std::size_t i = 0; i < s.size(); ++i) o << (i ? "," : "") << s[i];
  o << ']';
  return o.str();
}

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    this->~Handle();
    id_ = o.id_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

Handle::~Handle() {
  if (id_ < 0) return;
  switch (H5Iget_type(id_)) {
    case H5I_FILE: H5Fclose(id_); break;
    case H5I_GROUP: H5Gclose(id_); break;
    case H5I_DATASET: H5Dclose(id_); break;
    case H5I_DATASPACE: H5Sclose(id_); break;
    case H5I_DATATYPE: H5Tclose(id_); break;
    case H5I_ATTR: H5Aclose(id_); break;
    case H5I_GENPROP_LST: H5Pclose(id_); break;
    default: break;
  }
  id_ = H5I_INVALID_HID;
}

// ------------------------------------------------------------------------------------------
// Writer

Writer::Writer(const std::filesystem::path& path, std::string display_name)
    : name_(display_name.empty() ? path.string() : std::move(display_name)) {
  silence();
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS));
  // v1.8+ object headers and superblock carry checksums of their own metadata.
  H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST);
  file_ = Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()));
  if (!file_.valid()) fail("", "cannot create file (" + last_error_text() + ")");
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {
  }
}

void Writer::close() {
  if (!file_.valid()) return;
  attr("/", kManifestAttribute, checksum_manifest(sealed_));
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0) fail("", "flush failed (" + last_error_text() + ")");
  file_ = Handle();
}

void Writer::fail(const std::string& object, const std::string& what) const {
  throw FormatError(name_, object, what);
}

void Writer::seal(const std::string& path, std::string checksum) {
  attr(path, kChecksumAttribute, checksum);
  sealed_.emplace_back(path, std::move(checksum));
}

void Writer::ensure_group(const std::string& path) {
  if (path == "/" || path.empty()) return;
  if (H5Lexists(file_.get(), path.c_str(), H5P_DEFAULT) > 0) return;
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE));
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  Handle g(H5Gcreate2(file_.get(), path.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT));
  if (!g.valid()) fail(path, "cannot create group (" + last_error_text() + ")");
}

namespace {

// Dataset creation properties: chunked + Fletcher-32 for arrays, compact for small scalars.
Handle array_dcpl(const Shape& shape, std::size_t elem_bytes) {
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE));
  std::vector<hsize_t> chunk(shape.begin(), shape.end());
  for (auto& c : chunk) c = std::max<hsize_t>(c, 1);
  // Shrink the leading dimensions until a chunk is about kChunkTargetElements doubles.
  const std::uint64_t target = kChunkTargetElements * 8 / std::max<std::size_t>(elem_bytes, 1);
  for (std::size_t d = 0; d < chunk.size(); ++d) {
    std::uint64_t n = 1;
    for (auto c : chunk) n *= c;
    if (n <= target) break;
    const std::uint64_t rest = n / chunk[d];
    chunk[d] = std::max<hsize_t>(1, target / std::max<std::uint64_t>(rest, 1));
  }
  H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data());
  H5Pset_fletcher32(dcpl.get());
  return dcpl;
}

Handle simple_space(const Shape& shape) {
  std::vector<hsize_t> dims(shape.begin(), shape.end()), maxdims(dims);
  // A zero-length dimension cannot hold a chunk of 1 unless it may grow.
  for (auto& m : maxdims)
    if (m == 0) m = H5S_UNLIMITED;
  return Handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()));
}

Handle fixed_string_type(std::size_t len) {
  Handle t(H5Tcopy(H5T_C_S1));
  H5Tset_size(t.get(), std::max<std::size_t>(len, 1));
  H5Tset_strpad(t.get(), H5T_STR_NULLPAD);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

}  // namespace

void Writer::write(const std::string& path, const double* data, const Shape& shape) {
  if (shape.empty()) fail(path, "internal: array dataset needs rank >= 1");
  ensure_group(parent_of(path));
  Handle space = simple_space(shape);
  Handle dcpl = array_dcpl(shape, sizeof(double));
  Handle ds(H5Dcreate2(file_.get(), path.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (!ds.valid()) fail(path, "cannot create dataset (" + last_error_text() + ")");
  if (product(shape) > 0 && H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(path, "write failed (" + last_error_text() + ")");
  seal(path, checksum_doubles(data, shape));
}

void Writer::write(const std::string& path, const std::int64_t* data, const Shape& shape) {
  if (shape.empty()) fail(path, "internal: array dataset needs rank >= 1");
  ensure_group(parent_of(path));
  Handle space = simple_space(shape);
  Handle dcpl = array_dcpl(shape, sizeof(std::int64_t));
  Handle ds(H5Dcreate2(file_.get(), path.c_str(), H5T_STD_I64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (!ds.valid()) fail(path, "cannot create dataset (" + last_error_text() + ")");
  if (product(shape) > 0 && H5Dwrite(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(path, "write failed (" + last_error_text() + ")");
  seal(path, checksum_int64(data, shape));
}

void Writer::write_scalar(const std::string& path, double v) {
  ensure_group(parent_of(path));
  Handle space(H5Screate(H5S_SCALAR));
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_layout(dcpl.get(), H5D_COMPACT);  // inside the checksummed object header
  Handle ds(H5Dcreate2(file_.get(), path.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (!ds.valid() || H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v) < 0)
    fail(path, "write failed (" + last_error_text() + ")");
  seal(path, checksum_doubles(&v, {}));
}

void Writer::write_string(const std::string& path, const std::string& s) {
  ensure_group(parent_of(path));
  Handle type = fixed_string_type(s.size());
  Handle space(H5Screate(H5S_SCALAR));
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE));
  if (s.size() < 32000) H5Pset_layout(dcpl.get(), H5D_COMPACT);
  Handle ds(H5Dcreate2(file_.get(), path.c_str(), type.get(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  std::string buf = s.empty() ? std::string(1, '\0') : s;
  if (!ds.valid() || H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    fail(path, "write failed (" + last_error_text() + ")");
  seal(path, checksum_strings({s}, {}));
}

void Writer::write_strings(const std::string& path, const std::vector<std::string>& s) {
  ensure_group(parent_of(path));
  std::size_t len = 1;
  for (const auto& x : s) len = std::max(len, x.size());
  Handle type = fixed_string_type(len);
  const Shape shape{s.size()};
  Handle space = simple_space(shape);
  Handle dcpl = array_dcpl(shape, len);
  Handle ds(H5Dcreate2(file_.get(), path.c_str(), type.get(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (!ds.valid()) fail(path, "cannot create dataset (" + last_error_text() + ")");
  std::vector<char> buf(s.size() * len, '\0');
  for (std::size_t i = 0; i < s.size(); ++i) std::copy(s[i].begin(), s[i].end(), buf.begin() + i * len);
  if (!s.empty() && H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    fail(path, "write failed (" + last_error_text() + ")");
  seal(path, checksum_strings(s, shape));
}

hid_t Writer::open_object(const std::string& object) {
  // An attribute goes on the root, on an existing object, or on a group created for it.
  if (object.empty() || object == "/") return H5Oopen(file_.get(), "/", H5P_DEFAULT);
  if (H5Lexists(file_.get(), object.c_str(), H5P_DEFAULT) <= 0) ensure_group(object);
  return H5Oopen(file_.get(), object.c_str(), H5P_DEFAULT);
}

void Writer::attr(const std::string& object, const std::string& name, const std::string& v) {
  Handle obj(open_object(object));
  Handle type = fixed_string_type(v.size());
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(obj.get(), name.c_str()) > 0) H5Adelete(obj.get(), name.c_str());
  Handle a(H5Acreate2(obj.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT));
  std::string buf = v.empty() ? std::string(1, '\0') : v;
  if (!a.valid() || H5Awrite(a.get(), type.get(), buf.data()) < 0)
    fail(object + "@" + name, "attribute write failed (" + last_error_text() + ")");
}

void Writer::attr(const std::string& object, const std::string& name, double v) {
  Handle obj(open_object(object));
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(obj.get(), name.c_str()) > 0) H5Adelete(obj.get(), name.c_str());
  Handle a(H5Acreate2(obj.get(), name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT));
  if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    fail(object + "@" + name, "attribute write failed (" + last_error_text() + ")");
}

void Writer::attr(const std::string& object, const std::string& name, std::int64_t v) {
  Handle obj(open_object(object));
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(obj.get(), name.c_str()) > 0) H5Adelete(obj.get(), name.c_str());
  Handle a(H5Acreate2(obj.get(), name.c_str(), H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT));
  if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_INT64, &v) < 0)
    fail(object + "@" + name, "attribute write failed (" + last_error_text() + ")");
}

// ------------------------------------------------------------------------------------------
// Reader

Reader::Reader(const std::filesystem::path& path, std::string display_name)
    : name_(display_name.empty() ? path.string() : std::move(display_name)) {
  silence();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("", "no such file");
  if (std::filesystem::is_directory(path, ec)) fail("", "is a directory, not a file");
  file_bytes_ = std::filesystem::file_size(path, ec);
  if (ec) fail("", "cannot read file size (" + ec.message() + ")");
  {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) fail("", "cannot open for reading");
    std::fclose(f);
  }
  const htri_t is = H5Fis_hdf5(path.c_str());
  if (is <= 0) fail("", "not an HDF5 file");
  file_ = Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file_.valid()) {
    const std::string e = last_error_text();
    if (e.find("truncated") != std::string::npos)
      fail("", "file is truncated (" + e + ")");
    fail("", "cannot open HDF5 file (" + e + ")");
  }
}

Reader::Reader(const void* image, std::size_t size, std::string display_name) : name_(std::move(display_name)) {
  silence();
  file_bytes_ = size;
  if (size < 8) fail("", "not an HDF5 file");
  // The core driver without a backing store reads the image (the caller's bytes, not a copy:
  // image_malloc above). It refuses an image whose name exists on disk ("file already
  // exists"), so it gets a name no file can have (below a file, not a folder), not the display name.
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS));
  if (!fapl.valid() || H5Pset_fapl_core(fapl.get(), 1 << 16, 0) < 0)
    fail("", "cannot hold the file image (" + last_error_text() + ")");
  auto* borrowed = new BorrowedImage{image, size, 1};
  H5FD_file_image_callbacks_t callbacks{image_malloc,     image_memcpy,     image_realloc, image_free,
                                        image_udata_copy, image_udata_free, borrowed};
  const herr_t set = H5Pset_file_image_callbacks(fapl.get(), &callbacks);
  image_udata_free(borrowed);  // the property list holds its own reference (a counted copy)
  if (set < 0 || H5Pset_file_image(fapl.get(), const_cast<void*>(image), size) < 0)
    fail("", "cannot hold the file image (" + last_error_text() + ")");
  file_ = Handle(H5Fopen("/dev/null/ffr-file-image", H5F_ACC_RDONLY, fapl.get()));
  if (!file_.valid()) {
    const std::string e = last_error_text();
    if (e.find("truncated") != std::string::npos)
      fail("", "file is truncated (" + e + ")");
    fail("", "cannot open HDF5 file (" + e + ")");
  }
}

void Reader::fail(const std::string& object, const std::string& what) const {
  throw FormatError(name_, object, what);
}

bool Reader::exists(const std::string& path) const {
  if (path == "/") return true;
  // Check each link along the path; H5Lexists fails on a missing intermediate group.
  std::string partial;
  std::size_t pos = 1;
  while (pos <= path.size()) {
    const auto next = path.find('/', pos);
    partial = path.substr(0, next);
    const htri_t e = H5Lexists(file_.get(), partial.c_str(), H5P_DEFAULT);
    // An error (not "no") means the parent group's metadata cannot be read: damaged file.
    if (e < 0) fail(partial, "cannot read the group's metadata: the file is damaged (" + last_error_text() + ")");
    if (e == 0) return false;
    if (next == std::string::npos) break;
    pos = next + 1;
  }
  return H5Oexists_by_name(file_.get(), path.c_str(), H5P_DEFAULT) > 0;
}

bool Reader::is_group(const std::string& path) const {
  if (!exists(path)) return false;
  H5O_info_t info;
  if (H5Oget_info_by_name(file_.get(), path.c_str(), &info, H5P_DEFAULT) < 0) return false;
  return info.type == H5O_TYPE_GROUP;
}

std::vector<std::string> Reader::members(const std::string& group) const {
  std::vector<std::string> names;
  if (!is_group(group)) return names;
  Handle g(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT));
  H5G_info_t info;
  if (!g.valid() || H5Gget_info(g.get(), &info) < 0) fail(group, "cannot list group (" + last_error_text() + ")");
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t n = H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (n < 0) fail(group, "cannot list group (" + last_error_text() + ")");
    std::string s(static_cast<std::size_t>(n), '\0');
    H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, s.data(), s.size() + 1, H5P_DEFAULT);
    names.push_back(s);
  }
  std::sort(names.begin(), names.end());
  return names;
}

Handle Reader::open_dataset(const std::string& path) const {
  if (!exists(path)) fail(path, "missing dataset");
  // The object header is read (and its checksum checked) first: H5Dopen2 on a damaged header
  // fails too, but libhdf5 1.10 leaks the half-opened dataset on that path.
  H5O_info_t info;
  if (H5Oget_info_by_name(file_.get(), path.c_str(), &info, H5P_DEFAULT) < 0)
    fail(path, "not a dataset or unreadable (" + last_error_text() + ")");
  if (info.type != H5O_TYPE_DATASET) fail(path, "not a dataset");
  Handle ds(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT));
  if (!ds.valid()) fail(path, "not a dataset or unreadable (" + last_error_text() + ")");
  return ds;
}

Shape Reader::shape(const std::string& path) const {
  Handle ds = open_dataset(path);
  Handle space(H5Dget_space(ds.get()));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(path, "unreadable dataspace (" + last_error_text() + ")");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return Shape(dims.begin(), dims.end());
}

void Reader::check_shape(const std::string& path, hid_t space, const Shape& expected) const {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) fail(path, "unreadable dataspace (" + last_error_text() + ")");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  const Shape got(dims.begin(), dims.end());
  if (got != expected)
    fail(path, "wrong shape: expected " + shape_string(expected) + ", found " + shape_string(got));
}

std::vector<double> Reader::read_array(const std::string& path, const Shape& expected, bool allow_nonfinite) const {
  // Check shape and size against the file before allocating anything.
  const Shape got = shape(path);
  if (got != expected)
    fail(path, "wrong shape: expected " + shape_string(expected) + ", found " + shape_string(got));
  if (product(expected) * 8 > file_bytes_)
    fail(path, "dataset larger than the file: the file is truncated or corrupt");
  std::vector<double> out(product(expected));
  read(path, expected, out.data(), allow_nonfinite);
  return out;
}

void Reader::read(const std::string& path, const Shape& expected, double* out, bool allow_nonfinite) const {
  Handle ds = open_dataset(path);
  Handle type(H5Dget_type(ds.get()));
  if (H5Tget_class(type.get()) != H5T_FLOAT || H5Tget_size(type.get()) != 8)
    fail(path, "wrong type: expected 64-bit float");
  Handle space(H5Dget_space(ds.get()));
  check_shape(path, space.get(), expected);
  const std::uint64_t n = product(expected);
  // Sizes were checked above; we never compress, so the data cannot exceed the file.
  if (n * 8 > file_bytes_) fail(path, "dataset larger than the file: the file is truncated or corrupt");
  if (n == 0) return check_content(path, ds.get(), checksum_doubles(out, expected));
  check_chunks(*this, path, ds.get());
  if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0) {
    const std::string e = last_error_text();
    if (e.find("checksum") != std::string::npos || e.find("Fletcher") != std::string::npos ||
        e.find("filter") != std::string::npos)
      fail(path, "checksum mismatch: the data is damaged (" + e + ")");
    fail(path, "read failed (" + e + ")");
  }
  if (!allow_nonfinite)
    for (std::uint64_t i = 0; i < n; ++i)
      if (!(std::abs(out[i]) <= max_magnitude_)) {
        std::ostringstream o;
        o << (std::isfinite(out[i]) ? "value beyond the magnitude this file may hold: " : "non-finite value ") << out[i]
          << " at flat index " << i;
        fail(path, o.str());
      }
  check_content(path, ds.get(), checksum_doubles(out, expected));
}

void Reader::read(const std::string& path, const Shape& expected, std::int64_t* out) const {
  Handle ds = open_dataset(path);
  Handle type(H5Dget_type(ds.get()));
  if (H5Tget_class(type.get()) != H5T_INTEGER) fail(path, "wrong type: expected integer");
  Handle space(H5Dget_space(ds.get()));
  check_shape(path, space.get(), expected);
  const std::uint64_t n = product(expected);
  if (n * H5Tget_size(type.get()) > file_bytes_)
    fail(path, "dataset larger than the file: the file is truncated or corrupt");
  if (n == 0) return check_content(path, ds.get(), checksum_int64(out, expected));
  check_chunks(*this, path, ds.get());
  if (H5Dread(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0) {
    const std::string e = last_error_text();
    if (e.find("checksum") != std::string::npos || e.find("filter") != std::string::npos)
      fail(path, "checksum mismatch: the data is damaged (" + e + ")");
    fail(path, "read failed (" + e + ")");
  }
  check_content(path, ds.get(), checksum_int64(out, expected));
}

double Reader::read_scalar(const std::string& path) const {
  Handle ds = open_dataset(path);
  Handle type(H5Dget_type(ds.get()));
  if (H5Tget_class(type.get()) != H5T_FLOAT || H5Tget_size(type.get()) != 8)
    fail(path, "wrong type: expected 64-bit float");
  Handle space(H5Dget_space(ds.get()));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != 0) fail(path, "wrong shape: expected a scalar, found rank " + std::to_string(rank));
  double v = 0;
  if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v) < 0)
    fail(path, "read failed (" + last_error_text() + ")");
  if (!std::isfinite(v)) fail(path, "non-finite value");
  if (!(std::abs(v) <= max_magnitude_)) fail(path, "value beyond the magnitude this file may hold");
  check_content(path, ds.get(), checksum_doubles(&v, {}));
  return v;
}

namespace {
// Reads `count` strings of an open dataset or attribute with string type `ftype`.
template <class ReadFn>
std::vector<std::string> read_string_values(hid_t ftype, std::size_t count, ReadFn&& read_fn, bool& ok) {
  std::vector<std::string> out(count);
  ok = true;
  if (H5Tis_variable_str(ftype) > 0) {
    Handle mem(H5Tcopy(H5T_C_S1));
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(ftype));
    std::vector<char*> ptrs(count, nullptr);
    if (count && read_fn(mem.get(), ptrs.data()) < 0) {
      ok = false;
      return out;
    }
    for (std::size_t i = 0; i < count; ++i) {
      out[i] = ptrs[i] ? ptrs[i] : "";
      std::free(ptrs[i]);
    }
    return out;
  }
  const std::size_t len = H5Tget_size(ftype);
  Handle mem(H5Tcopy(H5T_C_S1));
  H5Tset_size(mem.get(), len);
  H5Tset_strpad(mem.get(), H5T_STR_NULLPAD);
  H5Tset_cset(mem.get(), H5Tget_cset(ftype));
  std::vector<char> buf(count * len + 1, '\0');
  if (count && read_fn(mem.get(), buf.data()) < 0) {
    ok = false;
    return out;
  }
  for (std::size_t i = 0; i < count; ++i) {
    const char* p = buf.data() + i * len;
    std::size_t l = 0;
    while (l < len && p[l] != '\0') ++l;
    out[i].assign(p, l);
  }
  return out;
}
}  // namespace

std::string Reader::read_string(const std::string& path) const {
  Handle ds = open_dataset(path);
  Handle type(H5Dget_type(ds.get()));
  if (H5Tget_class(type.get()) != H5T_STRING) fail(path, "wrong type: expected a string");
  Handle space(H5Dget_space(ds.get()));
  if (H5Sget_simple_extent_ndims(space.get()) != 0) fail(path, "wrong shape: expected a scalar string");
  bool ok = true;
  auto v = read_string_values(type.get(), 1, [&](hid_t mem, void* buf) {
    return H5Dread(ds.get(), mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  }, ok);
  if (!ok) fail(path, "read failed (" + last_error_text() + ")");
  check_content(path, ds.get(), checksum_strings(v, {}));
  return v[0];
}

std::vector<std::string> Reader::read_strings(const std::string& path, std::uint64_t n) const {
  Handle ds = open_dataset(path);
  Handle type(H5Dget_type(ds.get()));
  if (H5Tget_class(type.get()) != H5T_STRING) fail(path, "wrong type: expected strings");
  Handle space(H5Dget_space(ds.get()));
  check_shape(path, space.get(), Shape{n});
  if (H5Tis_variable_str(type.get()) <= 0 && n * H5Tget_size(type.get()) > file_bytes_)
    fail(path, "dataset larger than the file: the file is truncated or corrupt");
  check_chunks(*this, path, ds.get());
  bool ok = true;
  auto v = read_string_values(type.get(), n, [&](hid_t mem, void* buf) {
    return H5Dread(ds.get(), mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  }, ok);
  if (!ok) {
    const std::string e = last_error_text();
    if (e.find("checksum") != std::string::npos || e.find("filter") != std::string::npos)
      fail(path, "checksum mismatch: the data is damaged (" + e + ")");
    fail(path, "read failed (" + e + ")");
  }
  check_content(path, ds.get(), checksum_strings(v, Shape{n}));
  return v;
}

bool Reader::has_attr(const std::string& object, const std::string& name) const {
  if (!exists(object)) return false;
  const htri_t e = H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT);
  if (e < 0) fail(object, "cannot read the attributes: the file's metadata is damaged (" + last_error_text() + ")");
  return e > 0;
}

std::string Reader::attr_string(const std::string& object, const std::string& name) const {
  const std::string where = object + "@" + name;
  if (!has_attr(object, name)) fail(where, "missing attribute");
  Handle a(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
  Handle type(H5Aget_type(a.get()));
  if (H5Tget_class(type.get()) != H5T_STRING) fail(where, "wrong type: expected a string");
  bool ok = true;
  auto v = read_string_values(type.get(), 1, [&](hid_t mem, void* buf) { return H5Aread(a.get(), mem, buf); }, ok);
  if (!ok) fail(where, "read failed (" + last_error_text() + ")");
  return v[0];
}

double Reader::attr_double(const std::string& object, const std::string& name) const {
  const std::string where = object + "@" + name;
  if (!has_attr(object, name)) fail(where, "missing attribute");
  Handle a(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
  Handle type(H5Aget_type(a.get()));
  const auto cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) fail(where, "wrong type: expected a number");
  Handle space(H5Aget_space(a.get()));
  if (H5Sget_simple_extent_npoints(space.get()) != 1) fail(where, "wrong shape: expected a scalar");
  double v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0) fail(where, "read failed (" + last_error_text() + ")");
  if (!std::isfinite(v)) fail(where, "non-finite value");
  return v;
}

std::int64_t Reader::attr_int(const std::string& object, const std::string& name) const {
  const std::string where = object + "@" + name;
  if (!has_attr(object, name)) fail(where, "missing attribute");
  Handle a(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
  Handle type(H5Aget_type(a.get()));
  if (H5Tget_class(type.get()) != H5T_INTEGER) fail(where, "wrong type: expected an integer");
  Handle space(H5Aget_space(a.get()));
  if (H5Sget_simple_extent_npoints(space.get()) != 1) fail(where, "wrong shape: expected a scalar");
  std::int64_t v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_INT64, &v) < 0) fail(where, "read failed (" + last_error_text() + ")");
  return v;
}

std::vector<std::pair<std::string, std::string>> Reader::attrs(const std::string& object) const {
  std::vector<std::pair<std::string, std::string>> out;
  if (!exists(object)) return out;
  Handle obj(H5Oopen(file_.get(), object.c_str(), H5P_DEFAULT));
  H5O_info_t info;
  if (!obj.valid() || H5Oget_info(obj.get(), &info) < 0) return out;
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    Handle a(H5Aopen_by_idx(obj.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT));
    if (!a.valid()) continue;
    const ssize_t n = H5Aget_name(a.get(), 0, nullptr);
    std::string name(static_cast<std::size_t>(std::max<ssize_t>(n, 0)), '\0');
    H5Aget_name(a.get(), name.size() + 1, name.data());
    Handle type(H5Aget_type(a.get()));
    switch (H5Tget_class(type.get())) {
      case H5T_STRING: out.emplace_back(name, attr_string(object, name)); break;
      case H5T_INTEGER: out.emplace_back(name, std::to_string(attr_int(object, name))); break;
      case H5T_FLOAT: {
        std::ostringstream o;
        o.precision(17);
        o << attr_double(object, name);
        out.emplace_back(name, o.str());
        break;
      }
      default: out.emplace_back(name, "<unsupported type>");
    }
  }
  return out;
}

// ------------------------------------------------------------------------------------------
// Chunk index

// Checks a chunked dataset's index before HDF5 reads through it: each chunk inside the file, of
// exactly the size written (the raw chunk plus the Fletcher-32 trailer: we never compress) and
// with no filter skipped. A damaged chunk size made libhdf5 1.10 run the Fletcher-32 filter
// over fewer than 4 bytes, which crashed the process.
namespace {
void check_chunks(const Reader& r, const std::string& path, hid_t ds) {
  const auto fail = [&](const std::string& what) { r.fail(path, what); };
  const std::uint64_t file_bytes_ = r.file_bytes();
  Handle dcpl(H5Dget_create_plist(ds));
  if (!dcpl.valid()) fail("unreadable creation properties: the file is damaged (" + last_error_text() + ")");
  if (H5Pget_layout(dcpl.get()) != H5D_CHUNKED) return;
  Handle space(H5Dget_space(ds));
  Handle type(H5Dget_type(ds));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank <= 0 || rank > 32) return;
  std::vector<hsize_t> chunk(static_cast<std::size_t>(rank));
  if (H5Pget_chunk(dcpl.get(), rank, chunk.data()) != rank) fail("unreadable chunk shape: the file is damaged");
  std::uint64_t expected = H5Tis_variable_str(type.get()) > 0 ? 0 : H5Tget_size(type.get());
  for (auto c : chunk) expected *= c;
  const int nfilters = H5Pget_nfilters(dcpl.get());
  bool fletcher = false;
  for (int i = 0; i < nfilters; ++i) {
    unsigned flags = 0;
    std::size_t nelmts = 0;
    char name[64];
    if (H5Pget_filter2(dcpl.get(), static_cast<unsigned>(i), &flags, &nelmts, nullptr, sizeof name, name, nullptr) ==
        H5Z_FILTER_FLETCHER32)
      fletcher = true;
    else
      return;  // another filter (a file not written by ffr): its sizes are not ours to check
  }
  if (fletcher) expected += 4;
  hsize_t nchunks = 0;
  if (H5Dget_num_chunks(ds, space.get(), &nchunks) < 0) fail("unreadable chunk index: the file is damaged (" + last_error_text() + ")");
  std::vector<hsize_t> offset(static_cast<std::size_t>(rank));
  for (hsize_t i = 0; i < nchunks; ++i) {
    unsigned mask = 0;
    haddr_t addr = 0;
    hsize_t size = 0;
    if (H5Dget_chunk_info(ds, space.get(), i, offset.data(), &mask, &addr, &size) < 0)
      fail("unreadable chunk index: the file is damaged (" + last_error_text() + ")");
    if (mask != 0 || (expected && size != expected) || addr == HADDR_UNDEF || addr + size > file_bytes_)
      fail("damaged chunk index: a chunk's size, filters or address differ from those written");
  }
}

}  // namespace

// ------------------------------------------------------------------------------------------
// Content checksums

void Reader::check_content(const std::string& path, hid_t ds, const std::string& checksum) const {
  const htri_t has = H5Aexists(ds, kChecksumAttribute);
  if (has < 0) fail(path, "cannot read the attributes: the file's metadata is damaged (" + last_error_text() + ")");
  if (has == 0) {
    if (require_checksums_) unsealed_.push_back(path);
    return;
  }
  const std::string stored = attr_string(path, kChecksumAttribute);
  if (stored != checksum)
    fail(path, "content checksum mismatch: the values read differ from those written (the file is damaged)");
  verified_.insert(path);
}

void Reader::collect_datasets(const std::string& group, int depth, std::set<haddr_t>& seen,
                              std::vector<std::string>& out) const {
  // Hard links may form a cycle only in a damaged file; the depth bound is far beyond any
  // layout of SPEC.md.
  if (depth > 32) fail(group, "groups nested more than 32 deep: the file is damaged");
  for (const auto& name : members(group)) {
    const std::string path = (group == "/" ? "/" : group + "/") + name;
    H5O_info_t info;
    if (H5Oget_info_by_name(file_.get(), path.c_str(), &info, H5P_DEFAULT) < 0)
      fail(path, "cannot read the object's header: the file is damaged (" + last_error_text() + ")");
    if (info.type == H5O_TYPE_GROUP) {
      if (!seen.insert(info.addr).second) fail(path, "a group linked twice: the file is damaged");
      collect_datasets(path, depth + 1, seen, out);
    } else if (info.type == H5O_TYPE_DATASET) {
      out.push_back(path);
    }
  }
}

std::string Reader::content_checksum(const std::string& path) const {
  const Shape s = shape(path);
  const std::uint64_t n = product(s);
  Handle ds = open_dataset(path);
  Handle type(H5Dget_type(ds.get()));
  check_chunks(*this, path, ds.get());
  switch (H5Tget_class(type.get())) {
    case H5T_FLOAT: {
      if (H5Tget_size(type.get()) != 8) fail(path, "wrong type: expected 64-bit float");
      if (n * 8 > file_bytes_) fail(path, "dataset larger than the file: the file is truncated or corrupt");
      std::vector<double> v(n);
      if (n && H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
        fail(path, "read failed: the data is damaged (" + last_error_text() + ")");
      return checksum_doubles(v.data(), s);
    }
    case H5T_INTEGER: {
      if (n * H5Tget_size(type.get()) > file_bytes_) fail(path, "dataset larger than the file: the file is truncated or corrupt");
      std::vector<std::int64_t> v(n);
      if (n && H5Dread(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
        fail(path, "read failed: the data is damaged (" + last_error_text() + ")");
      return checksum_int64(v.data(), s);
    }
    case H5T_STRING:
      return checksum_strings(s.empty() ? std::vector<std::string>{read_string(path)} : read_strings(path, n), s);
    default: fail(path, "unsupported type: the file is damaged or not written by ffr");
  }
}

void Reader::verify_content() const {
  const std::string hint = ": the dataset was not written by ffr, or was changed since";
  if (!unsealed_.empty()) fail(unsealed_.front(), std::string("no content checksum (attribute ") + kChecksumAttribute + ")" + hint);
  std::vector<std::string> datasets;
  std::set<haddr_t> seen;
  collect_datasets("/", 0, seen, datasets);
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& path : datasets) {
    if (!has_attr(path, kChecksumAttribute))
      fail(path, std::string("no content checksum (attribute ") + kChecksumAttribute + ")" + hint);
    if (!verified_.count(path) && content_checksum(path) != attr_string(path, kChecksumAttribute))
      fail(path, "content checksum mismatch: the values read differ from those written (the file is damaged)");
    verified_.insert(path);
    entries.emplace_back(path, attr_string(path, kChecksumAttribute));
  }
  const std::string where = std::string("/@") + kManifestAttribute;
  if (!has_attr("/", kManifestAttribute)) fail(where, "missing attribute: the file has no checksum of its list of datasets");
  if (attr_string("/", kManifestAttribute) != checksum_manifest(entries))
    fail(where, "the datasets in the file differ from those written (one was removed, added or renamed): the file is damaged");
}

// ------------------------------------------------------------------------------------------
// AtomicFile

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  // Temporary files of earlier writers of this target that were killed (stale_temp.hpp).
  detail::remove_stale_temporaries(target_);
  std::random_device rd;
  temp_ = detail::temporary_name(target_, rd());
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  const int fd = ::open(temp_.c_str(), O_RDONLY);
  if (fd < 0) throw FormatError(target_.string(), "", "temporary file vanished before commit");
  ::fsync(fd);
  ::close(fd);
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw FormatError(target_.string(), "", "cannot rename temporary file into place (" + ec.message() + ")");
  committed_ = true;
}

}  // namespace h5
}  // namespace ffr::formats
