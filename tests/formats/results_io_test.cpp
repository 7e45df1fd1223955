// The ffr-sim results file (SPEC.md section 13): bit-exact round trip, refusal of
// inconsistent data before writing, strict reading with messages naming file and dataset.
#include "ffr/formats/results_io.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <limits>
#include <vector>

using namespace ffr::formats;
namespace fs = std::filesystem;

namespace {

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("ffr_results_" + std::to_string(::getpid()) + "_" + name);
}

Results sample() {
  Results r;
  r.time = Eigen::VectorXd::LinSpaced(5, 0.0, 0.4);
  r.outputs.push_back({"q", "modal_coordinates", Eigen::MatrixXd::Random(5, 4)});
  r.outputs.push_back({"angle", "joint_coordinate", Eigen::MatrixXd::Random(5, 1)});
  r.steps = 4;
  r.newton_iterations = 9;
  r.integration_seconds = 0.125;
  return r;
}

}  // namespace

TEST(ResultsIo, RoundTripBitExact) {
  const Results a = sample();
  const auto f = temp("ok.h5");
  write_results(a, f);
  const Results b = read_results(f);
  fs::remove(f);
  EXPECT_EQ(b.time, a.time);
  ASSERT_EQ(b.outputs.size(), 2u);
  ASSERT_NE(b.find("q"), nullptr);
  EXPECT_EQ(b.find("q")->values, a.outputs[0].values);
  EXPECT_EQ(b.find("q")->type, "modal_coordinates");
  EXPECT_EQ(b.find("angle")->values, a.outputs[1].values);
  EXPECT_EQ(b.steps, 4);
  EXPECT_EQ(b.newton_iterations, 9);
  EXPECT_EQ(b.integration_seconds, 0.125);
  EXPECT_FALSE(b.generator.empty());
}

TEST(ResultsIo, InconsistentDataIsRefusedBeforeWriting) {
  const auto f = temp("bad.h5");
  Results r = sample();
  r.outputs[0].values.conservativeResize(4, 4);
  EXPECT_THROW(write_results(r, f), std::invalid_argument);
  r = sample();
  r.time[3] = 0.0;
  EXPECT_THROW(write_results(r, f), std::invalid_argument);
  r = sample();
  r.outputs[1].name = "a/b";
  EXPECT_THROW(write_results(r, f), std::invalid_argument);
  EXPECT_FALSE(fs::exists(f));
}

TEST(ResultsIo, StrictReading) {
  const auto f = temp("shape.h5");
  write_results(sample(), f);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t h = H5Fopen(f.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Ldelete(h, "/outputs/q", H5P_DEFAULT);
  const hsize_t dims[2] = {3, 4};
  const hid_t sp = H5Screate_simple(2, dims, nullptr);
  const hid_t ds = H5Dcreate2(h, "/outputs/q", H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const std::vector<double> v(12, 1.0);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(ds);
  H5Sclose(sp);
  H5Fclose(h);
  try {
    read_results(f);
    ADD_FAILURE() << "read a results file with a wrong output shape";
  } catch (const FormatError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(f.string()), std::string::npos) << m;
    EXPECT_NE(m.find("/outputs/q: wrong shape: expected [5,k], found [3,4]"), std::string::npos) << m;
  }
  fs::remove(f);
}

TEST(ResultsIo, DamagedValuesAreRefusedAndVersion1IsReadWithAWarning) {
  // A value changed in place keeps the dataset's checksum attribute: refused naming it.
  const auto f = temp("changed.h5");
  write_results(sample(), f);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  hid_t h = H5Fopen(f.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t ds = H5Dopen2(h, "/time", H5P_DEFAULT);
  std::vector<double> t(5);
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.data());
  t[4] += 1.0;  // still increasing: only the checksum can tell
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.data());
  H5Dclose(ds);
  H5Fclose(h);
  try {
    read_results(f);
    ADD_FAILURE() << "read a damaged results file";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(f.string() + ": /time: content checksum mismatch"), std::string::npos) << e.what();
  }
  // The same file as version 1 (no checksums promised, root list removed): read, with a warning.
  h = H5Fopen(f.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Adelete(h, "content_sha256");
  H5Adelete_by_name(h, "/time", "sha256", H5P_DEFAULT);
  const hid_t a = H5Aopen(h, "format_version", H5P_DEFAULT);
  const std::int64_t one = 1;
  H5Awrite(a, H5T_NATIVE_INT64, &one);
  H5Aclose(a);
  H5Fclose(h);
  std::vector<std::string> warnings;
  const Results r = read_results(f, &warnings);
  EXPECT_EQ(r.time.size(), 5);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("format_version 1 has no content checksums"), std::string::npos) << warnings[0];
  fs::remove(f);
}

// A file that no checksum covers (version 1, or written by the user's own tools) is still
// refused when it holds a value the writer never writes: a NaN time or output value (the HDF5
// layer's reading of every float dataset refuses it).
TEST(ResultsIo, NonFiniteValuesAreRefusedNamingTheDataset) {
  const auto write_v1_with = [](const fs::path& f, const char* dataset, hsize_t index) {
    write_results(sample(), f);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const hid_t h = H5Fopen(f.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    H5Adelete(h, "content_sha256");
    const hid_t a = H5Aopen(h, "format_version", H5P_DEFAULT);
    const std::int64_t one = 1;
    H5Awrite(a, H5T_NATIVE_INT64, &one);
    H5Aclose(a);
    const hid_t ds = H5Dopen2(h, dataset, H5P_DEFAULT);
    const hid_t space = H5Dget_space(ds);
    std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    v[index] = std::numeric_limits<double>::quiet_NaN();
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Sclose(space);
    H5Dclose(ds);
    H5Fclose(h);
  };
  const auto expect_refused = [](const fs::path& f, const std::string& what) {
    try {
      read_results(f);
      ADD_FAILURE() << "read a results file with a NaN: " << what;
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(f.string() + ": " + what), std::string::npos) << e.what();
    }
  };
  const auto f = temp("nan.h5");
  write_v1_with(f, "/time", 4);  // the last time: no decrease is seen before it
  expect_refused(f, "/time: non-finite value nan at flat index 4");
  write_v1_with(f, "/outputs/q", 9);  // row 2, column 1 of the 5x4 modal coordinates
  expect_refused(f, "/outputs/q: non-finite value nan at flat index 9");
  fs::remove(f);
}

// The file of a run that stopped with a solver error carries where and why (SPEC.md section 13);
// a complete run's file carries neither.
TEST(ResultsIo, AStoppedRunKeepsItsStopTimeAndReason) {
  const auto f = temp("stopped.h5");
  write_results(sample(), f);
  EXPECT_FALSE(read_results(f).stopped_at.has_value());
  Results r = sample();
  r.stopped_at = 0.41;
  r.stop_reason = "Newton did not converge at t = 0.41 s";
  write_results(r, f);
  const Results back = read_results(f);
  ASSERT_TRUE(back.stopped_at.has_value());
  EXPECT_EQ(*back.stopped_at, 0.41);
  EXPECT_EQ(back.stop_reason, r.stop_reason);
  r.stopped_at = std::numeric_limits<double>::infinity();
  EXPECT_THROW(write_results(r, f), std::invalid_argument);
  fs::remove(f);
}
