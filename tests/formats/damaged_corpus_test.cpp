// A deterministic corpus of damaged files, generated here from a clean SID and a clean results
// file: truncations, one-bit flips swept over the whole file and over every byte of the chunk
// indexes (version-1 B-tree nodes, "TREE": the metadata HDF5 does not checksum), and edits made
// with the HDF5 C API (wrong shapes and types, NaN, Inf, huge sizes, removed, added and renamed
// datasets, changed values). Every file whose content differs from the clean one must be
// refused by ffr-info, ffr-diff and ffr-sim with exit status 2 and a message naming the file,
// with no crash, no hang (each process has a time limit) and no output left behind.
//
// "Content differs" is decided independently of the readers under test: the file is dumped
// with the plain HDF5 C API (every object, attribute, shape, type and value, in a forked child
// so that a crash of the library counts as "unreadable") and compared with the dump of the clean
// file. A flip in bytes HDF5 never reads (padding, free space) leaves the dump identical; such a
// file may be accepted, and is counted apart.
#include "ffr/formats/content_checksum.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

using namespace ffr::formats;
namespace fs = std::filesystem;

namespace {

const std::string kBin = std::string(FFR_BINARY_DIR) + "/bin/";
constexpr int kTimeoutSeconds = 60;

fs::path dir() {
  static const fs::path d = fs::temp_directory_path() / ("ffr_corpus_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
struct RemoveTempDir : ::testing::Environment {
  void TearDown() override { fs::remove_all(dir()); }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new RemoveTempDir);

std::string slurp(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
void spit(const fs::path& f, const std::string& bytes) {
  std::ofstream out(f, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// ---- processes with a time limit ---------------------------------------------------------

struct Proc {
  int rc = -1;            // exit status, -1 if killed by a signal or the time limit
  bool crashed = false;   // a signal other than our kill
  bool timed_out = false;
  std::string out, err;
};

// Runs `fn` in a forked child (its exit status is the result) or exec's argv when fn is empty.
Proc spawn(const std::vector<std::string>& argv, const std::function<int()>& fn = {}) {
  const fs::path out = dir() / "proc.out", err = dir() / "proc.err";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    ::dup2(e, 2);
    if (fn) ::_exit(fn());
    std::vector<char*> a;
    for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
    a.push_back(nullptr);
    ::execv(a[0], a.data());
    ::_exit(127);
  }
  Proc p;
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int spin = 0;; ++spin) {
    if (::waitpid(pid, &status, WNOHANG) == pid) break;
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(kTimeoutSeconds)) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      p.timed_out = true;
      break;
    }
    ::usleep(spin < 50 ? 200 : 2000);
  }
  if (!p.timed_out && WIFEXITED(status)) p.rc = WEXITSTATUS(status);
  if (!p.timed_out && WIFSIGNALED(status)) p.crashed = true;
  p.out = slurp(out);
  p.err = slurp(err);
  return p;
}

// ---- the independent content dump (plain HDF5 C API) ---------------------------------------

struct Dump {
  std::string text;
  bool ok = true;
};

herr_t collect(hid_t, const char* name, const H5O_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

// Every object with its type, attributes (name, class, size, bytes), and for a dataset its
// shape, class, size and bytes. Any error makes the dump fail (the file is unreadable).
Dump dump(const fs::path& f, std::uint64_t max_bytes) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Dump d;
  const hid_t file = H5Fopen(f.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return {"", false};
  std::vector<std::string> names;
  if (H5Ovisit(file, H5_INDEX_NAME, H5_ITER_INC, collect, &names) < 0) d.ok = false;
  std::ostringstream o;
  auto bytes = [&](hid_t type, hssize_t n, const std::function<herr_t(hid_t, void*)>& read) {
    const std::size_t size = H5Tget_size(type);
    if (n < 0 || size == 0 || static_cast<std::uint64_t>(n) * size > max_bytes) return false;
    std::string b(static_cast<std::size_t>(n) * size, '\0');
    if (n > 0 && read(type, b.data()) < 0) return false;
    o << " class " << H5Tget_class(type) << " size " << size << " n " << n << " bytes " << b.size() << ":";
    o.write(b.data(), static_cast<std::streamsize>(b.size()));
    return true;
  };
  for (const auto& name : names) {
    if (!d.ok) break;
    const hid_t obj = H5Oopen(file, name.c_str(), H5P_DEFAULT);
    H5O_info_t info;
    if (obj < 0 || H5Oget_info(obj, &info) < 0) {
      d.ok = false;
      break;
    }
    o << "\n" << name << " type " << info.type;
    for (hsize_t i = 0; i < info.num_attrs && d.ok; ++i) {
      const hid_t a = H5Aopen_by_idx(obj, ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT);
      char an[256] = {0};
      const hid_t t = a >= 0 ? H5Aget_type(a) : -1;
      const hid_t s = a >= 0 ? H5Aget_space(a) : -1;
      if (a < 0 || t < 0 || s < 0 || H5Aget_name(a, sizeof an, an) < 0) d.ok = false;
      else {
        o << "\n  @" << an;
        d.ok = bytes(t, H5Sget_simple_extent_npoints(s), [&](hid_t mt, void* buf) { return H5Aread(a, mt, buf); });
      }
      if (s >= 0) H5Sclose(s);
      if (t >= 0) H5Tclose(t);
      if (a >= 0) H5Aclose(a);
    }
    if (d.ok && info.type == H5O_TYPE_DATASET) {
      const hid_t t = H5Dget_type(obj), s = H5Dget_space(obj);
      hsize_t dims[32];
      const int rank = s >= 0 ? H5Sget_simple_extent_dims(s, dims, nullptr) : -1;
      if (t < 0 || rank < 0) d.ok = false;
      else {
        o << " shape";
        for (int r = 0; r < rank; ++r) o << ' ' << dims[r];
        d.ok = bytes(t, H5Sget_simple_extent_npoints(s),
                     [&](hid_t mt, void* buf) { return H5Dread(obj, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf); });
      }
      if (s >= 0) H5Sclose(s);
      if (t >= 0) H5Tclose(t);
    }
    H5Oclose(obj);
  }
  H5Fclose(file);
  d.text = o.str();
  return d;
}

// True when the damaged file dumps exactly like the clean one (in a child: a crash or a hang
// of the library on the damaged file counts as "differs").
bool content_identical(const fs::path& f, const std::string& clean_dump) {
  const Proc p = spawn({}, [&] {
    const Dump d = dump(f, 64u << 20);
    return d.ok && d.text == clean_dump ? 0 : 1;
  });
  return p.rc == 0;
}

// ---- the damage ----------------------------------------------------------------------------

struct Damaged {
  std::string kind;   // truncation, flip, tree-flip, edit
  std::string label;  // what was done
  std::string bytes;  // the damaged file
};

std::string flipped(std::string b, std::size_t at, int bit) {
  b[at] = static_cast<char>(b[at] ^ (1 << bit));
  return b;
}

// The chunk indexes: every version-1 B-tree node ("TREE") of type 1 (chunked raw data). Its
// 24-byte header (signature, type, level, entries used, two sibling addresses) is followed by
// the first key (chunk size and filter mask, 8 bytes, then one 8-byte offset per dimension
// plus one), the first chunk's address, and the next key. The first key's offsets are all
// zero (the chunk at the origin), so the chunk's address is the first non-zero 8 bytes after
// the mask: that gives the key size K. Returns each node's offset and K.
std::uint64_t u64_at(const std::string& b, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

std::vector<std::pair<std::size_t, std::size_t>> tree_nodes(const std::string& b) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t at = b.find("TREE"); at != std::string::npos; at = b.find("TREE", at + 4)) {
    if (at + 24 + 8 + 8 * 34 > b.size() || b[at + 4] != 1) continue;
    std::size_t child = at + 32;
    while (child < at + 32 + 8 * 33 && u64_at(b, child) == 0) child += 8;
    const std::size_t key = child - (at + 24);
    if (u64_at(b, child) >= b.size() || key < 16) continue;
    out.emplace_back(at, key);
  }
  return out;
}

// How much of the SID's damage is swept: the suite's default covers every third chunk-index
// node and every second flip of the whole-file sweep; FFR_DAMAGED_CORPUS=full covers all (about
// three times the runs), =thin every sixth node and every fourth flip (about half the runs: the
// test command's sanitizer pass, where each run starts three instrumented programs and the
// fuzz stage's sid_reader target already feeds the same reader damaged files under ASan).
struct Sweep {
  std::size_t flips, node_every;
};
Sweep sweep() {
  const char* e = std::getenv("FFR_DAMAGED_CORPUS");
  const std::string v = e ? e : "";
  if (v == "full") return {400, 1};
  if (v == "thin") return {100, 6};
  if (!v.empty()) ADD_FAILURE() << "FFR_DAMAGED_CORPUS is full, thin or unset, not '" << v << "'";
  return {200, 3};
}

// Truncations; one bit flipped every `stride` bytes over the whole file; and in every
// `node_every`-th chunk index node, one bit in each byte of: type, level and entries used, the
// first byte of each sibling address, the chunk size and filter mask of the first key, the
// lowest and highest byte of each of its offsets, and the first chunk's address.

std::vector<Damaged> byte_damage(const std::string& clean, std::size_t stride, std::size_t node_every, std::size_t* tree_count) {
  std::vector<Damaged> out;
  const std::size_t n = clean.size();
  for (std::size_t len : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{8}, std::size_t{47}, std::size_t{96},
                          std::size_t{512}, std::size_t{2048}, n / 8, n / 4, n / 3, n / 2, 2 * n / 3, 3 * n / 4,
                          n - 4096, n - 512, n - 64, n - 1})
    if (len < n) out.push_back({"truncation", "truncated to " + std::to_string(len) + " bytes", clean.substr(0, len)});
  for (std::size_t at = 0; at < n; at += stride)
    out.push_back({"flip", "bit " + std::to_string(at % 8) + " of byte " + std::to_string(at), flipped(clean, at, static_cast<int>(at % 8))});
  const auto nodes = tree_nodes(clean);
  if (tree_count) *tree_count = nodes.size();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (i % node_every != 0) continue;
    const auto [node, key] = nodes[i];
    std::vector<std::size_t> bytes = {node + 4, node + 5, node + 6, node + 7, node + 8, node + 16};
    for (std::size_t at = node + 24; at < node + 32; ++at) bytes.push_back(at);
    for (std::size_t at = node + 32; at < node + 24 + key; at += 8) {
      bytes.push_back(at);
      bytes.push_back(at + 7);
    }
    for (std::size_t at = node + 24 + key; at < node + 24 + key + 8; ++at) bytes.push_back(at);
    for (std::size_t at : bytes)
      out.push_back({"tree-flip", "bit " + std::to_string(at % 8) + " of chunk-index byte " + std::to_string(at) + " (node at " +
                                      std::to_string(node) + ")",
                     flipped(clean, at, static_cast<int>(at % 8))});
  }
  return out;
}

// Edits with the HDF5 C API on a copy of the clean file.
using Edit = std::function<void(hid_t)>;

hid_t make_dataset(hid_t file, const char* path, hid_t type, const std::vector<hsize_t>& dims, const void* data,
                   bool chunked = false) {
  H5Ldelete(file, path, H5P_DEFAULT);
  const hid_t space = dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (chunked) {
    std::vector<hsize_t> c(dims.size(), 1);
    H5Pset_chunk(dcpl, static_cast<int>(c.size()), c.data());
  }
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  const hid_t ds = H5Dcreate2(file, path, type, space, lcpl, dcpl, H5P_DEFAULT);
  if (data) H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  H5Pclose(lcpl);
  H5Pclose(dcpl);
  H5Sclose(space);
  return ds;
}

void set_string_attr(hid_t obj, const char* name, const std::string& v) {
  H5Adelete(obj, name);
  const hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, std::max<std::size_t>(v.size(), 1));
  const hid_t s = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(obj, name, t, s, H5P_DEFAULT, H5P_DEFAULT);
  std::string buf = v.empty() ? std::string(1, '\0') : v;
  H5Awrite(a, t, buf.data());
  H5Aclose(a);
  H5Sclose(s);
  H5Tclose(t);
}

std::vector<double> read_doubles(hid_t file, const char* path, std::vector<hsize_t>& dims) {
  const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  const hid_t s = H5Dget_space(ds);
  dims.assign(static_cast<std::size_t>(H5Sget_simple_extent_ndims(s)), 0);
  H5Sget_simple_extent_dims(s, dims.data(), nullptr);
  std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(s);
  H5Dclose(ds);
  return v;
}

// Rewrites a float dataset with one value changed and, when `reseal`, with the content
// checksums made consistent again: a file as a faulty writer would make it, so that the
// refusal must come from the value check itself.
Edit change_value(const char* path, double value, bool reseal) {
  return [=](hid_t file) {
    std::vector<hsize_t> dims;
    std::vector<double> v = read_doubles(file, path, dims);
    v[0] = value;
    const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    if (reseal) {
      set_string_attr(ds, kChecksumAttribute, checksum_doubles(v.data(), std::vector<std::uint64_t>(dims.begin(), dims.end())));
      // The root's list of checksums, recomputed from every dataset's attribute.
      std::vector<std::string> names;
      H5Ovisit(file, H5_INDEX_NAME, H5_ITER_INC, collect, &names);
      std::vector<std::pair<std::string, std::string>> entries;
      for (const auto& n : names) {
        H5O_info_t info;
        H5Oget_info_by_name(file, n.c_str(), &info, H5P_DEFAULT);
        if (info.type != H5O_TYPE_DATASET) continue;
        const hid_t a = H5Aopen_by_name(file, n.c_str(), kChecksumAttribute, H5P_DEFAULT, H5P_DEFAULT);
        const hid_t t = H5Aget_type(a);
        std::string s(H5Tget_size(t), '\0');
        H5Aread(a, t, s.data());
        s.resize(std::strlen(s.c_str()));
        entries.emplace_back("/" + n, s);
        H5Tclose(t);
        H5Aclose(a);
      }
      const hid_t root = H5Oopen(file, "/", H5P_DEFAULT);
      set_string_attr(root, kManifestAttribute, checksum_manifest(entries));
      H5Oclose(root);
    }
    H5Dclose(ds);
  };
}

std::vector<std::pair<std::string, Edit>> sid_edits() {
  std::vector<std::pair<std::string, Edit>> e;
  e.emplace_back("NaN in /sid/Ke/M0 (checksums consistent)", change_value("/sid/Ke/M0", NAN, true));
  e.emplace_back("Inf in /sid/J/M0 (checksums consistent)", change_value("/sid/J/M0", INFINITY, true));
  e.emplace_back("1e300 in /integrals/PPdm (checksums consistent)", change_value("/integrals/PPdm", 1e300, true));
  e.emplace_back("NaN in /sid/Gr/M0", change_value("/sid/Gr/M0", NAN, false));
  e.emplace_back("one value of /sid/Ke/M0 changed in its last bit", [](hid_t f) {
    std::vector<hsize_t> dims;
    const double v = read_doubles(f, "/sid/Ke/M0", dims)[0];
    change_value("/sid/Ke/M0", std::nextafter(v, 2 * v + 1), false)(f);
  });
  e.emplace_back("/sid/Me/M0 of wrong shape [4,3]", [](hid_t f) {
    const std::vector<double> v(12, 0.5);
    H5Dclose(make_dataset(f, "/sid/Me/M0", H5T_NATIVE_DOUBLE, {4, 3}, v.data()));
  });
  e.emplace_back("/sid/Ke/M0 as integers", [](hid_t f) {
    const std::vector<long long> v(16, 1);
    H5Dclose(make_dataset(f, "/sid/Ke/M0", H5T_NATIVE_LLONG, {4, 4}, v.data()));
  });
  e.emplace_back("/refmod/mass as a string", [](hid_t f) {
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, 3);
    H5Dclose(make_dataset(f, "/refmod/mass", t, {}, "1.0"));
    H5Tclose(t);
  });
  e.emplace_back("/sid/Oe/M1 declared [1e9,4,6] (no data)", [](hid_t f) {
    H5Dclose(make_dataset(f, "/sid/Oe/M1", H5T_NATIVE_DOUBLE, {1000000000, 4, 6}, nullptr, true));
  });
  e.emplace_back("/refmod/frequency_hz declared [2^40] (no data)", [](hid_t f) {
    H5Dclose(make_dataset(f, "/refmod/frequency_hz", H5T_NATIVE_DOUBLE, {hsize_t{1} << 40}, nullptr, true));
  });
  e.emplace_back("/sid/Gr/M0 removed", [](hid_t f) { H5Ldelete(f, "/sid/Gr/M0", H5P_DEFAULT); });
  e.emplace_back("/stiffening removed (optional group)", [](hid_t f) { H5Ldelete(f, "/stiffening", H5P_DEFAULT); });
  e.emplace_back("/visual-like extra dataset added", [](hid_t f) {
    const double v[3] = {1, 2, 3};
    H5Dclose(make_dataset(f, "/extra/values", H5T_NATIVE_DOUBLE, {3}, v));
  });
  e.emplace_back("/sid/Ge/M0 renamed", [](hid_t f) { H5Lmove(f, "/sid/Ge/M0", f, "/sid/Ge/M9", H5P_DEFAULT, H5P_DEFAULT); });
  e.emplace_back("/sid/Ge/M0 swapped with /sid/Cr/M1 (same shape)", [](hid_t f) {
    H5Lmove(f, "/sid/Ge/M0", f, "/sid/tmp", H5P_DEFAULT, H5P_DEFAULT);
    H5Lmove(f, "/sid/Cr/M1", f, "/sid/Ge/M0", H5P_DEFAULT, H5P_DEFAULT);
    H5Lmove(f, "/sid/tmp", f, "/sid/Cr/M1", H5P_DEFAULT, H5P_DEFAULT);
  });
  e.emplace_back("checksum attribute of /sid/J/M1 removed", [](hid_t f) {
    const hid_t ds = H5Dopen2(f, "/sid/J/M1", H5P_DEFAULT);
    H5Adelete(ds, kChecksumAttribute);
    H5Dclose(ds);
  });
  e.emplace_back("root content checksum removed", [](hid_t f) { H5Adelete(f, kManifestAttribute); });
  e.emplace_back("chunk of /sid/Gr/M0 unallocated (reads as fill values)", [](hid_t f) {
    // Rewriting the dataset without data: the chunk is never allocated, as after a damaged key.
    std::vector<hsize_t> dims;
    read_doubles(f, "/sid/Gr/M0", dims);
    const hid_t ds = H5Dopen2(f, "/sid/Gr/M0", H5P_DEFAULT);
    const hid_t a = H5Aopen(ds, kChecksumAttribute, H5P_DEFAULT);
    const hid_t t = H5Aget_type(a);
    std::string sum(H5Tget_size(t), '\0');
    H5Aread(a, t, sum.data());
    sum.resize(std::strlen(sum.c_str()));
    H5Tclose(t);
    H5Aclose(a);
    H5Dclose(ds);
    const hid_t fresh = make_dataset(f, "/sid/Gr/M0", H5T_NATIVE_DOUBLE, dims, nullptr, true);
    set_string_attr(fresh, kChecksumAttribute, sum);
    H5Dclose(fresh);
  });
  return e;
}

std::vector<Damaged> edits(const fs::path& clean, const std::vector<std::pair<std::string, Edit>>& list) {
  std::vector<Damaged> out;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  for (const auto& [label, fn] : list) {
    const fs::path f = dir() / "edit.h5";
    fs::copy_file(clean, f, fs::copy_options::overwrite_existing);
    const hid_t file = H5Fopen(f.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    fn(file);
    H5Fclose(file);
    out.push_back({"edit", label, slurp(f)});
    fs::remove(f);
  }
  return out;
}

// ---- the check -------------------------------------------------------------------------------

struct Tally {
  int files = 0, differing = 0, refused = 0, identical = 0, identical_accepted = 0, runs = 0;
  int crashes = 0, hangs = 0, wrong_status = 0, unnamed = 0, leftovers = 0;
  std::map<std::string, int> by_kind;
  std::vector<std::string> failures;
  void fail(const std::string& s) {
    if (failures.size() < 20) failures.push_back(s);
  }
  std::string summary(const std::string& what) const {
    std::ostringstream o;
    o << what << ": " << files << " damaged files (";
    for (const auto& [k, n] : by_kind) o << k << " " << n << ", ";
    o << "), " << runs << " runs: " << differing << " with different content, " << refused << " of them refused by every tool; "
      << identical << " content-identical (" << identical_accepted << " of those accepted); crashes " << crashes << ", hangs "
      << hangs << ", wrong status " << wrong_status << ", message without the file " << unnamed << ", left-over files "
      << leftovers;
    return o.str();
  }
};

// Checks one tool run on a file that must be refused (or, if content-identical, may pass).
bool judge(Tally& t, const std::string& tool, const Proc& p, const fs::path& named, bool identical, const std::string& label) {
  ++t.runs;
  if (p.crashed) {
    ++t.crashes;
    t.fail(tool + " crashed on " + label);
    return false;
  }
  if (p.timed_out) {
    ++t.hangs;
    t.fail(tool + " hung on " + label);
    return false;
  }
  if (identical && p.rc == 0) return true;
  if (p.rc != 2) {
    ++t.wrong_status;
    t.fail(tool + " exit " + std::to_string(p.rc) + " on " + label + ": " + p.err.substr(0, 300));
    return false;
  }
  if (p.err.find(named.string()) == std::string::npos || std::count(p.err.begin(), p.err.end(), '\n') != 1) {
    ++t.unnamed;
    t.fail(tool + " message on " + label + " does not name the file in one line: " + p.err.substr(0, 300));
    return false;
  }
  return true;
}

std::set<std::string> listing(const fs::path& d) {
  std::set<std::string> s;
  for (const auto& e : fs::directory_iterator(d)) s.insert(e.path().filename().string());
  return s;
}

fs::path clean_sid() {
  synthetic::ChainParams p;
  p.stiffening = true;
  p.clamped = true;
  const fs::path f = dir() / "clean.sid.h5";
  write_sid(synthetic::spring_chain(p).sid, f);
  return f;
}

// Model file for ffr-sim: the chain on a hinge at its node A, a few steps.
const char* kModel = R"({
  "gravity": [0, 0, -9.81],
  "bodies": [{"name": "chain", "type": "flexible", "sid": "body.sid.h5"}],
  "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "chain", "node2": "A", "axis": [0, 1, 0]}],
  "solver": {"end": 0.005, "step": 0.001},
  "outputs": [{"name": "tip", "type": "node_position", "body": "chain", "node": "B"}]
})";

std::size_t stride_for(std::size_t size, std::size_t flips) { return std::max<std::size_t>(1, size / flips) | 1; }

}  // namespace

TEST(DamagedCorpus, EveryDamagedSidIsRefusedByInfoDiffAndSim) {
  const fs::path clean = clean_sid();
  const std::string clean_bytes = slurp(clean);
  const Dump clean_dump = dump(clean, 64u << 20);
  ASSERT_TRUE(clean_dump.ok);
  const fs::path work = dir() / "sim";
  fs::create_directories(work);
  spit(work / "model.json", kModel);
  const fs::path body = work / "body.sid.h5";
  const fs::path results = work / "out.h5";

  // The clean file passes every tool (else the corpus would prove nothing).
  spit(body, clean_bytes);
  ASSERT_EQ(spawn({kBin + "ffr-info", body.string()}).rc, 0);
  ASSERT_EQ(spawn({kBin + "ffr-diff", clean.string(), body.string()}).rc, 0);
  const Proc ok = spawn({kBin + "ffr-sim", (work / "model.json").string(), "-o", results.string(), "-q"});
  ASSERT_EQ(ok.rc, 0) << ok.err;
  fs::remove(results);
  const std::set<std::string> before = listing(work);

  std::size_t nodes = 0;
  const Sweep how = sweep();
  std::vector<Damaged> corpus = byte_damage(clean_bytes, stride_for(clean_bytes.size(), how.flips), how.node_every, &nodes);
  for (auto& d : edits(clean, sid_edits())) corpus.push_back(std::move(d));

  Tally t;
  for (const auto& d : corpus) {
    ++t.files;
    ++t.by_kind[d.kind];
    spit(body, d.bytes);
    const bool identical = content_identical(body, clean_dump.text);
    const std::string label = d.kind + " (" + d.label + ")";
    bool all = true;
    all &= judge(t, "ffr-info", spawn({kBin + "ffr-info", body.string(), "--json"}), body, identical, label);
    all &= judge(t, "ffr-diff", spawn({kBin + "ffr-diff", clean.string(), body.string()}), body, identical, label);
    const Proc sim = spawn({kBin + "ffr-sim", (work / "model.json").string(), "-o", results.string(), "-q"});
    all &= judge(t, "ffr-sim", sim, body, identical, label);
    if (sim.rc == 0 && identical) fs::remove(results);
    if (listing(work) != before) {
      ++t.leftovers;
      t.fail("files left behind after " + label);
      for (const auto& name : listing(work))
        if (!before.count(name)) fs::remove(work / name);
    }
    if (identical) {
      ++t.identical;
      if (sim.rc == 0) ++t.identical_accepted;
    } else {
      ++t.differing;
      if (all) ++t.refused;
    }
  }
  const std::string summary = t.summary("SID corpus of a " + std::to_string(clean_bytes.size()) + "-byte file with " +
                                        std::to_string(nodes) + " chunk-index nodes");
  std::printf("%s\n", summary.c_str());
  RecordProperty("summary", summary);
  for (const auto& f : t.failures) ADD_FAILURE() << f;
  EXPECT_EQ(t.refused, t.differing);
  EXPECT_EQ(t.crashes + t.hangs + t.wrong_status + t.unnamed + t.leftovers, 0);
  EXPECT_GE(nodes, 40u) << "the chunk indexes were not found";
}

TEST(DamagedCorpus, EveryDamagedResultsFileIsRefusedByInfo) {
  Results r;
  r.time = Eigen::VectorXd::LinSpaced(51, 0.0, 0.5);
  r.outputs.push_back({"tip", "node_position", Eigen::MatrixXd::Random(51, 3)});
  r.outputs.push_back({"energy", "energy", Eigen::MatrixXd::Random(51, 3)});
  r.steps = 50;
  r.newton_iterations = 120;
  r.integration_seconds = 0.25;
  const fs::path clean = dir() / "clean.results.h5";
  write_results(r, clean);
  const std::string clean_bytes = slurp(clean);
  const Dump clean_dump = dump(clean, 64u << 20);
  ASSERT_TRUE(clean_dump.ok);
  const fs::path f = dir() / "res" / "results.h5";
  fs::create_directories(f.parent_path());
  spit(f, clean_bytes);
  ASSERT_EQ(spawn({kBin + "ffr-info", f.string()}).rc, 0);

  std::size_t nodes = 0;
  std::vector<Damaged> corpus = byte_damage(clean_bytes, stride_for(clean_bytes.size(), 300), 1, &nodes);
  std::vector<std::pair<std::string, Edit>> list;
  list.emplace_back("NaN in /time (checksums consistent)", change_value("/time", NAN, true));
  list.emplace_back("/outputs/tip changed", change_value("/outputs/tip", 0.125, false));
  list.emplace_back("/outputs/energy removed", [](hid_t h) { H5Ldelete(h, "/outputs/energy", H5P_DEFAULT); });
  list.emplace_back("/outputs/tip of wrong shape", [](hid_t h) {
    const std::vector<double> v(7, 0.5);
    H5Dclose(make_dataset(h, "/outputs/tip", H5T_NATIVE_DOUBLE, {7}, v.data()));
  });
  for (auto& d : edits(clean, list)) corpus.push_back(std::move(d));

  Tally t;
  for (const auto& d : corpus) {
    ++t.files;
    ++t.by_kind[d.kind];
    spit(f, d.bytes);
    const bool identical = content_identical(f, clean_dump.text);
    const Proc info = spawn({kBin + "ffr-info", f.string(), "--json"});
    const bool all = judge(t, "ffr-info", info, f, identical, d.kind + " (" + d.label + ")");
    if (identical) {
      ++t.identical;
      if (info.rc == 0) ++t.identical_accepted;
    } else {
      ++t.differing;
      if (all) ++t.refused;
    }
  }
  const std::string summary = t.summary("results corpus of a " + std::to_string(clean_bytes.size()) + "-byte file with " +
                                        std::to_string(nodes) + " chunk-index nodes");
  std::printf("%s\n", summary.c_str());
  RecordProperty("summary", summary);
  for (const auto& x : t.failures) ADD_FAILURE() << x;
  EXPECT_EQ(t.refused, t.differing);
  EXPECT_EQ(t.crashes + t.hangs + t.wrong_status + t.unnamed, 0);
}
