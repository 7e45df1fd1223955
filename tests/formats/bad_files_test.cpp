// Damaged and malformed SID files: every one is refused with a FormatError whose message
// names the file and the dataset or attribute. The damage is done with the HDF5 C API or by
// byte surgery on a clean synthetic file.
#include "ffr/formats/content_checksum.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>

using namespace ffr::formats;
namespace fs = std::filesystem;

namespace {

fs::path dir() {
  static const fs::path d = fs::temp_directory_path() / ("ffr_badfiles_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

struct RemoveTempDir : ::testing::Environment {
  void TearDown() override { fs::remove_all(dir()); }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new RemoveTempDir);

// A clean file to damage: 4 modes, nodes A and B, interfaces, stiffening.
fs::path clean_copy(const std::string& name) {
  static const fs::path clean = [] {
    synthetic::ChainParams p;
    p.stiffening = true;
    const fs::path f = dir() / "clean.sid.h5";
    write_sid(synthetic::spring_chain(p).sid, f);
    return f;
  }();
  const fs::path f = dir() / name;
  fs::copy_file(clean, f, fs::copy_options::overwrite_existing);
  return f;
}

// Opens read-write, runs the edit, closes.
void edit(const fs::path& f, const std::function<void(hid_t)>& fn) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = H5Fopen(f.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  fn(file);
  ASSERT_GE(H5Fclose(file), 0);
}

void replace(hid_t file, const char* path, hid_t type, std::vector<hsize_t> dims, const void* data) {
  H5Ldelete(file, path, H5P_DEFAULT);
  const hid_t space = dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t ds = H5Dcreate2(file, path, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(ds, 0) << path;
  ASSERT_GE(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), 0);
  H5Dclose(ds);
  H5Sclose(space);
}

void replace_doubles(hid_t file, const char* path, std::vector<hsize_t> dims) {
  std::size_t n = 1;
  for (auto d : dims) n *= d;
  const std::vector<double> v(n, 0.5);
  replace(file, path, H5T_NATIVE_DOUBLE, std::move(dims), v.data());
}

void replace_string(hid_t file, const char* path, const std::string& s) {
  const hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, s.size());
  replace(file, path, t, {}, s.data());
  H5Tclose(t);
}

void replace_strings(hid_t file, const char* path, const std::vector<std::string>& s) {
  std::size_t len = 1;
  for (const auto& x : s) len = std::max(len, x.size());
  std::vector<char> buf(s.size() * len, '\0');
  for (std::size_t i = 0; i < s.size(); ++i) std::copy(s[i].begin(), s[i].end(), buf.begin() + i * len);
  const hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, len);
  replace(file, path, t, {s.size()}, buf.data());
  H5Tclose(t);
}

// Overwrites one value of an existing float dataset through the API (checksums stay valid).
void poke(hid_t file, const char* path, double value) {
  const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  const hid_t space = H5Dget_space(ds);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> v(static_cast<std::size_t>(n));
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  v[v.size() / 2] = value;
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(ds);
}

void set_root_attr(hid_t file, const char* name, hid_t type, const void* v) {
  H5Adelete(file, name);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(file, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, v);
  H5Aclose(a);
  H5Sclose(space);
}

std::uint64_t object_address(const fs::path& f, const char* path) {
  std::uint64_t addr = 0;
  edit(f, [&](hid_t file) {
    H5O_info_t info;
    ASSERT_GE(H5Oget_info_by_name(file, path, &info, H5P_DEFAULT), 0);
    addr = info.addr;
  });
  return addr;
}

std::uint64_t chunk_address(const fs::path& f, const char* path) {
  std::uint64_t addr = 0;
  edit(f, [&](hid_t file) {
    const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
    hsize_t offset[4];
    unsigned mask = 0;
    haddr_t a = 0;
    hsize_t size = 0;
    const hid_t space = H5Dget_space(ds);
    ASSERT_GE(H5Dget_chunk_info(ds, space, 0, offset, &mask, &a, &size), 0);
    addr = a + size / 2;  // inside the data of the first chunk
    H5Sclose(space);
    H5Dclose(ds);
  });
  return addr;
}

void flip_byte(const fs::path& f, std::uint64_t at) {
  std::fstream io(f, std::ios::in | std::ios::out | std::ios::binary);
  io.seekg(static_cast<std::streamoff>(at));
  char c = 0;
  io.read(&c, 1);
  c = static_cast<char>(c ^ 0x5A);
  io.seekp(static_cast<std::streamoff>(at));
  io.write(&c, 1);
}

// The read must fail with a FormatError naming the file, `object` and containing `what`.
void expect_refused(const fs::path& f, const std::string& object, const std::string& what) {
  try {
    read_sid(f);
    ADD_FAILURE() << f << ": read although damaged (" << object << ")";
  } catch (const FormatError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(f.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(object), std::string::npos) << "expected '" << object << "' in: " << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << f << ": not a FormatError: " << e.what();
  }
}

}  // namespace

TEST(BadFiles, CleanFileReads) { EXPECT_NO_THROW(read_sid(clean_copy("ok.sid.h5"))); }

TEST(BadFiles, MissingDataset) {
  const auto f = clean_copy("missing.sid.h5");
  edit(f, [](hid_t h) { H5Ldelete(h, "/sid/Ge/M0", H5P_DEFAULT); });
  expect_refused(f, "/sid/Ge/M0", "missing dataset");
}

TEST(BadFiles, WrongShape) {
  const auto f = clean_copy("shape.sid.h5");
  edit(f, [](hid_t h) { replace_doubles(h, "/sid/Me/M0", {4, 3}); });
  expect_refused(f, "/sid/Me/M0", "wrong shape: expected [4,4], found [4,3]");
}

TEST(BadFiles, WrongRank) {
  const auto f = clean_copy("rank.sid.h5");
  edit(f, [](hid_t h) { replace_doubles(h, "/sid/J/M0", {9}); });
  expect_refused(f, "/sid/J/M0", "wrong shape");
}

TEST(BadFiles, IntegerInsteadOfFloat) {
  const auto f = clean_copy("int.sid.h5");
  edit(f, [](hid_t h) {
    const std::vector<std::int64_t> v(16, 1);
    replace(h, "/sid/Ke/M0", H5T_NATIVE_INT64, {4, 4}, v.data());
  });
  expect_refused(f, "/sid/Ke/M0", "wrong type");
}

TEST(BadFiles, StringInsteadOfNumber) {
  const auto f = clean_copy("string.sid.h5");
  edit(f, [](hid_t h) { replace_string(h, "/refmod/mass", "1.0"); });
  expect_refused(f, "/refmod/mass", "wrong type");
}

TEST(BadFiles, NaN) {
  const auto f = clean_copy("nan.sid.h5");
  edit(f, [](hid_t h) { poke(h, "/sid/Oe/M0", std::numeric_limits<double>::quiet_NaN()); });
  expect_refused(f, "/sid/Oe/M0", "non-finite");
}

TEST(BadFiles, HugeValue) {
  // Finite but absurd (found by fuzzing): ffr-sim integrated it into a Newton failure, exit 1.
  const auto f = clean_copy("huge.sid.h5");
  edit(f, [](hid_t h) { poke(h, "/integrals/Pdm", 1e308); });
  expect_refused(f, "/integrals/Pdm", "value beyond the magnitude this file may hold: 1e+308");
}

TEST(BadFiles, Inf) {
  const auto f = clean_copy("inf.sid.h5");
  edit(f, [](hid_t h) { poke(h, "/integrals/PPdm", -INFINITY); });
  expect_refused(f, "/integrals/PPdm", "non-finite");
}

TEST(BadFiles, Truncated) {
  const auto f = clean_copy("truncated.sid.h5");
  fs::resize_file(f, fs::file_size(f) / 2);
  expect_refused(f, "", "truncated");
}

TEST(BadFiles, FlippedByteInsideDatasetDataFailsTheChecksum) {
  const auto f = clean_copy("flipdata.sid.h5");
  flip_byte(f, chunk_address(f, "/sid/Gr/M0"));
  expect_refused(f, "/sid/Gr/M0", "checksum");
}

TEST(BadFiles, FlippedByteInMetadataIsRefused) {
  // Inside the object header of a dataset: its own checksum (v2 headers) fails on open.
  const auto f = clean_copy("flipmeta.sid.h5");
  flip_byte(f, object_address(f, "/sid/Cr/M1") + 12);
  expect_refused(f, "/sid/Cr/M1", "");
  // And inside the root group's header (the format attributes live there).
  const auto g = clean_copy("fliproot.sid.h5");
  flip_byte(g, object_address(g, "/") + 12);
  expect_refused(g, "", "checksum");
}

TEST(BadFiles, UnknownFormatVersion) {
  const auto f = clean_copy("version.sid.h5");
  edit(f, [](hid_t h) {
    const std::int64_t v = kFormatVersion + 1;
    set_root_attr(h, "format_version", H5T_NATIVE_INT64, &v);
  });
  expect_refused(f, "/@format_version", "unsupported format_version " + std::to_string(kFormatVersion + 1));
}

TEST(BadFiles, WrongFormatAttribute) {
  const auto f = clean_copy("format.sid.h5");
  edit(f, [](hid_t h) {
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, 7);
    set_root_attr(h, "format", t, "ffr-res");
    H5Tclose(t);
  });
  expect_refused(f, "/@format", "not a SID file");
}

TEST(BadFiles, NotHdf5AtAll) {
  const auto f = dir() / "text.sid.h5";
  std::ofstream(f) << "this is not an HDF5 file\n";
  expect_refused(f, "", "not an HDF5 file");
}

TEST(BadFiles, EmptyFile) {
  const auto f = dir() / "empty.sid.h5";
  std::ofstream{f};
  expect_refused(f, "", "not an HDF5 file");
}

TEST(BadFiles, DirectoryInsteadOfFile) {
  const auto d = dir() / "a_directory.sid.h5";
  fs::create_directories(d);
  expect_refused(d, "", "is a directory");
}

TEST(BadFiles, NonexistentFile) { expect_refused(dir() / "nowhere.sid.h5", "", "no such file"); }

TEST(BadFiles, MissingNodeNames) {
  const auto f = clean_copy("nonames.sid.h5");
  edit(f, [](hid_t h) { H5Ldelete(h, "/nodes/name", H5P_DEFAULT); });
  expect_refused(f, "/nodes/name", "missing dataset");
}

TEST(BadFiles, InterfacePointsToNonexistentNode) {
  const auto f = clean_copy("iface.sid.h5");
  edit(f, [](hid_t h) {
    const std::vector<std::int64_t> v = {0, 5};
    replace(h, "/interfaces/node", H5T_NATIVE_INT64, {2}, v.data());
  });
  expect_refused(f, "/interfaces/node", "refers to node 5");
}

TEST(BadFiles, RepeatedOrEmptyNodeNames) {
  // Model files name nodes: a repeated name bound silently to the first node of that name.
  auto f = clean_copy("samenames.sid.h5");
  edit(f, [](hid_t h) { replace_strings(h, "/nodes/name", {"A", "A"}); });
  expect_refused(f, "/nodes/name", "node name 'A' appears twice");
  f = clean_copy("emptyname.sid.h5");
  edit(f, [](hid_t h) { replace_strings(h, "/nodes/name", {"A", ""}); });
  expect_refused(f, "/nodes/name", "node 1 has an empty name");
}

TEST(BadFiles, UnknownInterfaceCoupling) {
  const auto f = clean_copy("coupling.sid.h5");
  edit(f, [](hid_t h) { replace_strings(h, "/interfaces/coupling", {"rigid", "weird"}); });
  expect_refused(f, "/interfaces/coupling", "coupling 'weird' (rigid or averaged)");
}

TEST(BadFiles, UnknownModeType) {
  const auto f = clean_copy("modetype.sid.h5");
  edit(f, [](hid_t h) { replace_strings(h, "/refmod/mode_type", {"normal", "bending", "normal", "normal"}); });
  expect_refused(f, "/refmod/mode_type", "unknown mode type 'bending'");
}

TEST(BadFiles, NegativeMass) {
  const auto f = clean_copy("mass.sid.h5");
  edit(f, [](hid_t h) {
    const double m = -1;
    replace(h, "/refmod/mass", H5T_NATIVE_DOUBLE, {}, &m);
  });
  expect_refused(f, "/refmod/mass", "mass must be positive");
}

TEST(BadFiles, InconsistentNumberOfModes) {
  const auto f = clean_copy("nq.sid.h5");
  edit(f, [](hid_t h) { replace_doubles(h, "/sid/Cr/M1", {5, 5, 3}); });
  expect_refused(f, "/sid/Cr/M1", "expected [4,4,3]");
}

TEST(BadFiles, DamagedStiffeningInterfaceMember) {
  const auto f = clean_copy("stiff.sid.h5");
  edit(f, [](hid_t h) { H5Ldelete(h, "/stiffening/interfaces/B/K0M", H5P_DEFAULT); });
  expect_refused(f, "/stiffening/interfaces/B/K0M", "missing dataset");
}

// /sid/Ke/M1 is optional, but when present it must be [nq,nq,nq] and finite.
TEST(BadFiles, KeM1WrongShape) {
  const auto f = clean_copy("kem1shape.sid.h5");
  ASSERT_FALSE(read_sid(f).KeM1.empty());
  edit(f, [](hid_t h) { replace_doubles(h, "/sid/Ke/M1", {4, 4}); });
  expect_refused(f, "/sid/Ke/M1", "wrong shape: expected [4,4,4], found [4,4]");
  edit(f, [](hid_t h) { replace_doubles(h, "/sid/Ke/M1", {3, 4, 4}); });
  expect_refused(f, "/sid/Ke/M1", "expected [4,4,4]");
}

TEST(BadFiles, KeM1NaN) {
  const auto f = clean_copy("kem1nan.sid.h5");
  edit(f, [](hid_t h) {
    std::vector<double> v(64, 1.0);
    v[17] = std::numeric_limits<double>::quiet_NaN();
    replace(h, "/sid/Ke/M1", H5T_NATIVE_DOUBLE, {4, 4, 4}, v.data());
  });
  expect_refused(f, "/sid/Ke/M1", "");
}

// Written without it (deleting it from a written file is damage: the root checksum refuses it).
TEST(BadFiles, KeM1AbsentIsFine) {
  const fs::path f = dir() / "kem1absent.sid.h5";
  synthetic::ChainParams p;
  p.stiffening = true;
  Sid sid = synthetic::spring_chain(p).sid;
  sid.KeM1.clear();
  write_sid(sid, f);
  EXPECT_TRUE(read_sid(f).KeM1.empty());
}

// ---- content checksums (format_version 2, SPEC.md section 4) ------------------------------

namespace {
std::string dataset_checksum(hid_t file, const char* path) {
  const hid_t a = H5Aopen_by_name(file, path, kChecksumAttribute, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t t = H5Aget_type(a);
  std::string s(H5Tget_size(t), '\0');
  H5Aread(a, t, s.data());
  H5Tclose(t);
  H5Aclose(a);
  return s.substr(0, s.find('\0'));
}
}  // namespace

TEST(BadFiles, ContentChecksumsMatchAnIndependentSha256OfTheValues) {
  // The checksum of /refmod/frequency_hz recomputed here from SPEC.md section 4 with the
  // system's sha256sum (an implementation other than formats/src/sha256.cpp).
  const auto f = clean_copy("sums.sid.h5");
  const Sid s = read_sid(f);
  std::string canon("ffr-content-1\0f64\0", 18);
  auto u64 = [&](std::uint64_t v) {
    for (int i = 0; i < 8; ++i) canon.push_back(static_cast<char>(v >> (8 * i)));
  };
  u64(1);
  u64(static_cast<std::uint64_t>(s.nq()));
  for (Eigen::Index k = 0; k < s.nq(); ++k) {
    std::uint64_t bits;
    std::memcpy(&bits, &s.refmod.frequency_hz[k], 8);
    u64(bits);
  }
  const fs::path c = dir() / "canon.bin";
  std::ofstream(c, std::ios::binary).write(canon.data(), static_cast<std::streamsize>(canon.size()));
  const std::string cmd = "sha256sum " + c.string() + " > " + (dir() / "canon.sum").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(dir() / "canon.sum");
  std::string expected;
  in >> expected;
  std::string stored;
  edit(f, [&](hid_t h) { stored = dataset_checksum(h, "/refmod/frequency_hz"); });
  EXPECT_EQ(stored, expected);
}

TEST(BadFiles, ValuesReadBackAsFillValuesAreRefused) {
  // What a damaged chunk key does (issue: one bit in the key of /sid/Gr/M0 read as zeros): the
  // chunk is taken as never written and reads as the fill value. Made here by recreating the
  // dataset without writing it, keeping its checksum attribute.
  const auto f = clean_copy("fill.sid.h5");
  edit(f, [](hid_t h) {
    const std::string sum = dataset_checksum(h, "/sid/Gr/M0");
    H5Ldelete(h, "/sid/Gr/M0", H5P_DEFAULT);
    const hsize_t dims[3] = {4, 3, 3}, chunk[3] = {4, 3, 3};
    const hid_t space = H5Screate_simple(3, dims, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 3, chunk);
    const hid_t ds = H5Dcreate2(h, "/sid/Gr/M0", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, sum.size());
    const hid_t s = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(ds, kChecksumAttribute, t, s, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, t, sum.data());
    H5Aclose(a);
    H5Sclose(s);
    H5Tclose(t);
    H5Dclose(ds);
    H5Pclose(dcpl);
    H5Sclose(space);
  });
  expect_refused(f, "/sid/Gr/M0", "content checksum mismatch");
}

TEST(BadFiles, AChangedValueIsRefusedNamingTheDataset) {
  const auto f = clean_copy("changed.sid.h5");
  edit(f, [](hid_t h) { poke(h, "/sid/Ke/M0", 1234.5); });
  expect_refused(f, "/sid/Ke/M0", "content checksum mismatch");
}

TEST(BadFiles, ADatasetWithoutChecksumIsRefusedAfterTheContentChecks) {
  const auto f = clean_copy("unsealed.sid.h5");
  edit(f, [](hid_t h) { H5Adelete_by_name(h, "/sid/J/M1", kChecksumAttribute, H5P_DEFAULT); });
  expect_refused(f, "/sid/J/M1", "no content checksum");
}

TEST(BadFiles, ARemovedOptionalGroupOrAnExtraDatasetIsRefused) {
  // /stiffening is optional: only the root's checksum of the list of datasets notices.
  auto f = clean_copy("nostiff.sid.h5");
  edit(f, [](hid_t h) { H5Ldelete(h, "/stiffening", H5P_DEFAULT); });
  expect_refused(f, "/@content_sha256", "differ from those written");
  f = clean_copy("extra.sid.h5");
  edit(f, [](hid_t h) { replace_doubles(h, "/sid/extra", {3}); });
  expect_refused(f, "/sid/extra", "no content checksum");
}

TEST(BadFiles, Version1FilesAreReadWithAWarning) {
  // A version 1 file: the same layout without the checksums.
  const auto f = clean_copy("v1.sid.h5");
  edit(f, [](hid_t h) {
    const std::int64_t v = 1;
    set_root_attr(h, "format_version", H5T_NATIVE_INT64, &v);
    H5Adelete(h, kManifestAttribute);
  });
  std::vector<std::string> warnings;
  const Sid s = read_sid(f, &warnings);
  EXPECT_EQ(s.nq(), 4);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find(f.string() + ": format_version 1 has no content checksums"), std::string::npos) << warnings[0];
  // A version 2 file gives no warning.
  warnings.clear();
  read_sid(clean_copy("v2.sid.h5"), &warnings);
  EXPECT_TRUE(warnings.empty());
}

TEST(BadFiles, DamagedChunkSizesInTheChunkIndexAreRefusedNotACrash) {
  // Every bit of the two low bytes of the first key's chunk size in every chunk-index node ("TREE"): a
  // 6-byte chunk whose size read as 2 made libhdf5 run Fletcher-32 over fewer than 4 bytes and
  // crash (found by the damaged-file corpus).
  const auto clean = clean_copy("chunksize.sid.h5");
  std::string bytes;
  {
    std::ifstream in(clean, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  int nodes = 0, refused = 0, runs = 0;
  for (std::size_t at = bytes.find("TREE"); at != std::string::npos; at = bytes.find("TREE", at + 4)) {
    if (at + 32 > bytes.size() || bytes[at + 4] != 1) continue;
    ++nodes;
    for (std::size_t b = at + 24; b < at + 26; ++b)
      for (int bit = 0; bit < 8; ++bit) {
        std::string d = bytes;
        d[b] = static_cast<char>(d[b] ^ (1 << bit));
        const fs::path f = dir() / "chunksize_damaged.sid.h5";
        std::ofstream(f, std::ios::binary | std::ios::trunc).write(d.data(), static_cast<std::streamsize>(d.size()));
        ++runs;
        try {
          read_sid(f);
        } catch (const FormatError& e) {
          ++refused;
          EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
        }
      }
  }
  EXPECT_GE(nodes, 40);
  EXPECT_EQ(refused, runs);
}

// The fuzzing of the SID reader opens its inputs as file images in memory (read_sid_image,
// tools/fuzz/): the same reading as from a file. A clean image gives the file's content, and
// damaged images are refused with the file's message (the display name in place of the path).
TEST(BadFiles, AFileImageInMemoryReadsAndIsRefusedAsTheFile) {
  const auto slurp = [](const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const auto clean = clean_copy("image.sid.h5");
  const std::string bytes = slurp(clean);
  const Sid from_file = read_sid(clean);
  const Sid from_image = read_sid_image(bytes.data(), bytes.size(), "image");
  EXPECT_EQ(from_image.refmod.frequency_hz, from_file.refmod.frequency_hz);
  EXPECT_EQ(from_image.refmod.mass, from_file.refmod.mass);
  EXPECT_EQ(from_image.nodes.size(), from_file.nodes.size());

  const auto damaged = [&](const std::string& name, const std::function<void(const fs::path&)>& damage) {
    const auto f = clean_copy(name);
    damage(f);
    const std::string b = slurp(f);
    std::string file_msg, image_msg;
    try { read_sid(f); } catch (const FormatError& e) { file_msg = e.what(); }
    try { read_sid_image(b.data(), b.size(), f.string()); } catch (const FormatError& e) { image_msg = e.what(); }
    EXPECT_FALSE(file_msg.empty()) << name;
    EXPECT_EQ(image_msg, file_msg) << name;
  };
  damaged("img_data.sid.h5", [](const fs::path& f) { flip_byte(f, chunk_address(f, "/sid/Gr/M0")); });
  damaged("img_meta.sid.h5", [](const fs::path& f) { flip_byte(f, object_address(f, "/sid/Cr/M1") + 12); });
  damaged("img_root.sid.h5", [](const fs::path& f) { flip_byte(f, object_address(f, "/") + 12); });
  damaged("img_trunc.sid.h5", [](const fs::path& f) { fs::resize_file(f, fs::file_size(f) / 2); });
  damaged("img_nan.sid.h5", [](const fs::path& f) {
    edit(f, [](hid_t h) {
      const double v = std::nan("");
      replace(h, "/refmod/mass", H5T_IEEE_F64LE, {}, &v);
    });
  });
  std::string msg;
  try { read_sid_image("\x89HDF", 4, "tiny"); } catch (const FormatError& e) { msg = e.what(); }
  EXPECT_NE(msg.find("tiny"), std::string::npos) << msg;
}
