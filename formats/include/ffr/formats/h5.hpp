#pragma once
// A thin, strict layer over the HDF5 C API, shared by the SID and results files.
//
// Writing: every array dataset is chunked and carries HDF5's Fletcher-32 checksum filter;
// scalars and short strings are stored compact, inside their object header, which the
// latest file-format version protects with its own checksum. On top of these, every dataset
// gets a SHA-256 of its values (content_checksum.hpp) and the root one of the list of all
// datasets: what HDF5 does not check (a chunk index, which can make a chunk read back as fill
// values) is caught by comparing the values read with those written.
//
// Reading: every access checks existence, type class, rank and every dimension against
// what the caller expects *before* allocating, and all failures throw FormatError naming the
// file and the dataset. The HDF5 library's own error printing is switched off: this layer
// never prints.

#include <hdf5.h>

#include <set>
#include <utility>

#include <cstdint>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffr::formats {

/// Any problem with a file: names the file and, where there is one, the dataset or attribute.
/// The largest magnitude a number may have in the files users give (part and model files, SID
/// files): no quantity in any supported unit system comes near it, and larger ones overflowed in
/// products downstream (NaN in K, a non-finite state) where no file or field could be named.
inline constexpr double kMaxInputMagnitude = 1e30;

class FormatError : public std::runtime_error {
 public:
  FormatError(std::string file, std::string object, const std::string& what);
  const std::string& file() const { return file_; }
  const std::string& object() const { return object_; }
  /// The message without the file and object in front.
  const std::string& detail() const { return detail_; }

 private:
  std::string file_, object_, detail_;
};

namespace h5 {

using Shape = std::vector<std::uint64_t>;
std::string shape_string(const Shape& s);

/// Owns one hid_t and closes it with the right H5*close.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept;
  ~Handle();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

/// Writes one new HDF5 file. Paths are absolute ("/sid/J/M0"); parent groups are created.
class Writer {
 public:
  /// Creates (truncates) `path`. `display_name` is used in error messages.
  explicit Writer(const std::filesystem::path& path, std::string display_name = {});
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// Row-major (C order) doubles of the given shape; rank >= 1.
  void write(const std::string& path, const double* data, const Shape& shape);
  void write(const std::string& path, const std::int64_t* data, const Shape& shape);
  void write_scalar(const std::string& path, double v);
  void write_string(const std::string& path, const std::string& s);
  void write_strings(const std::string& path, const std::vector<std::string>& s);

  void attr(const std::string& object, const std::string& name, const std::string& v);
  void attr(const std::string& object, const std::string& name, double v);
  void attr(const std::string& object, const std::string& name, std::int64_t v);

  void ensure_group(const std::string& path);
  /// Writes the root's checksum of the list of datasets, flushes and closes; after this the
  /// writer is unusable. Called by the destructor too.
  void close();

 private:
  hid_t open_object(const std::string& object);
  /// Stores `checksum` as the dataset's content checksum and adds it to the root's list.
  void seal(const std::string& path, std::string checksum);
  [[noreturn]] void fail(const std::string& object, const std::string& what) const;
  Handle file_;
  std::string name_;
  std::vector<std::pair<std::string, std::string>> sealed_;
};

/// Reads an existing HDF5 file strictly.
class Reader {
 public:
  /// Opens read-only. Throws FormatError if missing, unreadable, not HDF5, or truncated.
  explicit Reader(const std::filesystem::path& path, std::string display_name = {});
  /// Opens the bytes of an HDF5 file held in memory (HDF5's core driver on them, not copied:
  /// they must outlive the Reader),
  /// named `display_name` in every message; everything after the open is the same reading as
  /// from a file. The fuzzing of the SID reader uses it (tools/fuzz/), to spare a file per input.
  Reader(const void* image, std::size_t size, std::string display_name);

  const std::string& name() const { return name_; }
  /// Size of the file on disk in bytes: an upper bound for any dataset (we never compress).
  std::uint64_t file_bytes() const { return file_bytes_; }

  bool exists(const std::string& path) const;
  bool is_group(const std::string& path) const;
  /// Names of the members of a group, sorted.
  std::vector<std::string> members(const std::string& group) const;

  /// Shape of a dataset (throws if missing). A scalar dataset has an empty shape.
  Shape shape(const std::string& path) const;

  /// From now on, float values of larger magnitude are refused like non-finite ones (the SID
  /// reader sets kMaxInputMagnitude).
  void set_max_magnitude(double m) { max_magnitude_ = m; }

  /// Reads a float64 dataset into `out`, which must hold product(expected) values; the
  /// dataset's shape must equal `expected` exactly. Values must be finite unless allow_nonfinite.
  void read(const std::string& path, const Shape& expected, double* out, bool allow_nonfinite = false) const;
  void read(const std::string& path, const Shape& expected, std::int64_t* out) const;
  /// Like read(), but checks shape and size against the file before allocating the result.
  std::vector<double> read_array(const std::string& path, const Shape& expected, bool allow_nonfinite = false) const;
  double read_scalar(const std::string& path) const;
  std::string read_string(const std::string& path) const;
  /// A 1-D string dataset of exactly n entries.
  std::vector<std::string> read_strings(const std::string& path, std::uint64_t n) const;

  bool has_attr(const std::string& object, const std::string& name) const;
  std::string attr_string(const std::string& object, const std::string& name) const;
  double attr_double(const std::string& object, const std::string& name) const;
  std::int64_t attr_int(const std::string& object, const std::string& name) const;
  /// All attributes of an object as text (numbers formatted with full precision).
  std::vector<std::pair<std::string, std::string>> attrs(const std::string& object) const;

  [[noreturn]] void fail(const std::string& object, const std::string& what) const;

  /// Content checksums (content_checksum.hpp). Every read compares the values it read with
  /// the dataset's checksum when it has one and refuses a mismatch at once. After
  /// require_checksums() (a file whose version promises them) a dataset without one is
  /// refused by verify_content(), which also checks every dataset not read so far and the
  /// root's checksum of the list of datasets. Called last, so that a file edited by hand
  /// keeps the more specific refusal of its content (a wrong shape, a NaN, ...).
  void require_checksums() { require_checksums_ = true; }
  void verify_content() const;

 private:
  Handle open_dataset(const std::string& path) const;
  void check_shape(const std::string& path, hid_t space, const Shape& expected) const;
  /// Compares the checksum of the values read from `path` with the one stored.
  void check_content(const std::string& path, hid_t ds, const std::string& checksum) const;
  /// The paths of every dataset below `group`, depth first (refuses link cycles).
  void collect_datasets(const std::string& group, int depth, std::set<haddr_t>& seen,
                        std::vector<std::string>& out) const;
  /// Reads a dataset of any supported type and returns the checksum of its values.
  std::string content_checksum(const std::string& path) const;
  Handle file_;
  std::string name_;
  std::uint64_t file_bytes_ = 0;
  double max_magnitude_ = HUGE_VAL;
  bool require_checksums_ = false;
  mutable std::set<std::string> verified_;
  mutable std::vector<std::string> unsealed_;
};

/// Temporary file next to `target`, renamed over it by commit(); removed if never committed.
/// This is how every output of the project is written, so nothing is left half-written.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& target() const { return target_; }
  /// fsyncs the temporary file and renames it over the target.
  void commit();

 private:
  std::filesystem::path target_, temp_;
  bool committed_ = false;
};

/// The text of the innermost HDF5 error on the current error stack ("" if none).
std::string last_error_text();

}  // namespace h5
}  // namespace ffr::formats
