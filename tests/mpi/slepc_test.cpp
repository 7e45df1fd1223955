// The slepc backend of ffr-reduce (reduction.backend "slepc": SLEPc's Krylov-Schur over MPI,
// shift-invert factorized by MUMPS) under `mpirun -np 2` gives the SID of the serial path (the
// default: the own block Lanczos on the own supernodal Cholesky, itself checked against CalculiX
// in tests/reduce) on a solid and a shell part, free (by count and up to a frequency), clamped
// and Craig-Bampton, a shell with an attached mass, free, and a beam part, free. Reference: the serial path; the two share no eigen-solver or factorization
// code (SLEPc and MUMPS are code nobody here wrote). Compared by ffr-diff, which aligns mode
// signs and rotations within degenerate subspaces, at rtol 1e-6 over every member of the SID,
// and the frequencies at 1e-8 relative.
// And its refusals: the backend where it is not built in, ffr-reduce under mpirun with a serial
// backend, a PETSc failure on every rank and a failure of one rank alone; each a clear message
// and no SID.
#include "ffr/formats/sid_io.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace ffr;
namespace fs = std::filesystem;

namespace {

const char* kSolidGeo = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("left") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("right") = Surface In BoundingBox{0.2 - 1e-6, -1, -1, 0.2 + 1e-6, 1, 1};
)";
const char* kShellGeo = R"(Point(1) = {0, 0, 0}; Point(2) = {0.5, 0, 0}; Point(3) = {0.5, 0.1, 0}; Point(4) = {0, 0.1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 26; Transfinite Curve{2, 4} = 6;
Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1}; Physical Curve("left") = {4}; Physical Curve("right") = {2};
)";
const char* kBeamGeo = R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("beam") = {1}; Physical Point("left") = {1}; Physical Point("right") = {2};
)";

enum class Body { Solid, Shell, ShellWithMass, Beam };
enum class Method { Free, FreeUpTo, Clamped, CraigBampton };

std::string part_json(Body b, Method m, const std::string& backend) {
  std::string s = b == Body::Solid ? R"({"geometry": "part.geo", "mesh": {"size": 0.008, "order": 1},
        "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],)"
                   : b == Body::Shell ? R"({"geometry": "part.geo", "mesh": {"order": 1},
        "shells": [{"group": "plate", "thickness": 0.002, "E": 7e10, "nu": 0.3, "rho": 2700}],)"
                   : b == Body::ShellWithMass ? R"({"geometry": "part.geo", "mesh": {"order": 1},
        "shells": [{"group": "plate", "thickness": 0.002, "E": 7e10, "nu": 0.3, "rho": 2700}],
        "point_masses": [{"name": "tip", "at": [0.5, 0.04, 0], "mass": 0.05, "com_offset": [0, 0, 0.01],
                          "inertia": [[1e-5, 0, 0], [0, 1e-5, 0], [0, 0, 2e-5]]}],)"
                                      : R"({"geometry": "part.geo", "mesh": {"order": 1},
        "beams": [{"group": "beam", "E": 2.1e11, "nu": 0.3, "rho": 7850, "y_axis": [0, 1, 0],
                   "section": {"A": 1.2e-3, "Iy": 4e-8, "Iz": 3.6e-7, "J": 1.5e-7}}],)";
  s += R"( "interfaces": [{"name": "L", "group": "left"}, {"name": "R", "group": "right"}], "visual": false,
    "reduction": {)";
  switch (m) {
    case Method::Free: s += R"("method": "free", "modes": 8)"; break;
    // Every mode up to 20 kHz: nev grows over several solves until one lies above (the solid
    // part's first eight lie between 2.7 and 17 kHz).
    case Method::FreeUpTo: s += R"("method": "free", "max_frequency_hz": 20000)"; break;
    case Method::Clamped: s += R"("method": "clamped", "interface": "L", "modes": 8)"; break;
    case Method::CraigBampton: s += R"("method": "craig-bampton", "interfaces": ["L", "R"], "frame": "L", "modes": 6)"; break;
  }
  return s + R"(, "backend": ")" + backend + R"("}})";
}

void write_part(const test::TempDir& dir, Body b, Method m, const std::string& backend) {
  test::write_text(dir / "part.geo", b == Body::Solid ? kSolidGeo : b == Body::Beam ? kBeamGeo : kShellGeo);
  test::write_text(dir / "part.json", part_json(b, m, backend));
}

std::string reduce_command(const test::TempDir& dir, const std::string& out) {
  return test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " -o " + (dir / out).string() + " --quiet";
}

#if FFR_TEST_SLEPC
// Open MPI refuses to start ranks as root unless told twice; the permission is the test's, given
// to this one command only. Its ranks poll for messages without yielding the core unless told
// to: beside the other tests ctest runs at the same time they would take turns with them at
// the scheduler's pace, not the messages'.
#define FFR_TEST_MPI_ENV " OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1 "
std::string mpirun(int ranks, const std::string& command, const std::string& env = "") {
  return env + FFR_TEST_MPI_ENV FFR_MPIEXEC " -np " + std::to_string(ranks) + " --oversubscribe " + command;
}
#endif

// The files of `dir` other than the part's own (a partial or temporary SID would show here).
std::string stray_files(const test::TempDir& dir) {
  std::string s;
  for (const auto& e : fs::directory_iterator(dir.path())) {
    const std::string name = e.path().filename().string();
    if (name != "part.json" && name != "part.geo" && name != "bad.json" && name != "bad.geo" && name != "serial.json")
      s += " " + name;
  }
  return s;
}

}  // namespace

#if FFR_TEST_SLEPC

class SlepcOnTwoRanks : public ::testing::TestWithParam<std::tuple<Body, Method>> {};

TEST_P(SlepcOnTwoRanks, GivesTheSidOfTheSerialPath) {
  const auto [body, method] = GetParam();
  test::TempDir dir("slepc");
  write_part(dir, body, method, "block");
  const auto serial = test::run(reduce_command(dir, "serial.sid.h5"));
  ASSERT_EQ(serial.status, 0) << serial.output;
  const auto mpi = test::run(mpirun(2, reduce_command(dir, "mpi.sid.h5") + " --backend slepc"));
  ASSERT_EQ(mpi.status, 0) << mpi.output;

  const auto diff = test::run(test::bin("ffr-diff").string() + " " + (dir / "serial.sid.h5").string() + " " +
                              (dir / "mpi.sid.h5").string() + " --rtol 1e-6");
  EXPECT_EQ(diff.status, 0) << diff.output;
  EXPECT_NE(diff.output.find("EQUIVALENT"), std::string::npos) << diff.output;

  const formats::Sid a = formats::read_sid(dir / "serial.sid.h5");
  const formats::Sid b = formats::read_sid(dir / "mpi.sid.h5");
  EXPECT_EQ(b.provenance.extra.at("eigen_backend"), "SLEPc Krylov-Schur");
  ASSERT_EQ(a.nq(), b.nq());
  ASSERT_GE(a.nq(), 6);
  for (formats::Index k = 0; k < a.nq(); ++k) {
    const double fa = a.refmod.frequency_hz(k), fb = b.refmod.frequency_hz(k);
    EXPECT_LE(std::abs(fa - fb), 1e-8 * std::abs(fa)) << "mode " << k << ": " << fa << " vs " << fb << " Hz";
  }
}

INSTANTIATE_TEST_SUITE_P(PartTypes, SlepcOnTwoRanks,
                         ::testing::Values(std::make_tuple(Body::Solid, Method::Free),
                                           std::make_tuple(Body::Solid, Method::FreeUpTo),
                                           std::make_tuple(Body::Solid, Method::Clamped),
                                           std::make_tuple(Body::Solid, Method::CraigBampton),
                                           std::make_tuple(Body::Shell, Method::Free),
                                           std::make_tuple(Body::Shell, Method::Clamped),
                                           // The rotary part and the samples of an attached mass, summed over the ranks.
                                           std::make_tuple(Body::ShellWithMass, Method::Free),
                                           std::make_tuple(Body::Beam, Method::Free)),
                         [](const auto& info) {
                           const Body b = std::get<0>(info.param);
                           const Method m = std::get<1>(info.param);
                           return std::string(b == Body::Solid           ? "solid"
                                              : b == Body::Shell         ? "shell"
                                              : b == Body::ShellWithMass ? "shell_with_mass"
                                                                         : "beam") +
                                  "_" +
                                  (m == Method::Free       ? "free"
                                   : m == Method::FreeUpTo ? "free_up_to_20kHz"
                                   : m == Method::Clamped  ? "clamped"
                                                           : "craig_bampton");
                         });

// What each rank reports of its share (the distributed path's log, one line a rank): its
// elements, the entries of K and M it assembled and those of its rows of the summed K and M.
struct RankShare {
  long long elements = 0, assembled = 0, rows = 0, rss_mib = 0;
};
std::vector<RankShare> rank_shares(const std::string& log, int ranks) {
  std::vector<RankShare> v(static_cast<std::size_t>(ranks));
  int seen = 0;
  for (int r = 0; r < ranks; ++r) {
    const std::string key = "rank " + std::to_string(r) + " of " + std::to_string(ranks) + ": ";
    const auto at = log.find(key);
    if (at == std::string::npos) continue;
    RankShare& s = v[static_cast<std::size_t>(r)];
    if (std::sscanf(log.c_str() + at + key.size(),
                    "%lld elements, %lld assembled entries of K and M, %lld entries in its rows of K and M, peak RSS %lld MiB",
                    &s.elements, &s.assembled, &s.rows, &s.rss_mib) == 4)
      ++seen;
  }
  if (seen != ranks) v.clear();
  return v;
}

// No rank holds K and M whole: on two ranks each assembles about half of the elements, and
// stores about half of the rows of the summed matrices. Reference: the same part on one rank,
// where the one rank assembles every element (the count gmsh's mesh has) and stores all rows.
// The halves overlap by the entries of the elements on the cut and the rows' coupling to it
// (some percent on this bar), so the bound is 0.75 of the whole; and the SID is the serial one.
TEST(Slepc, EachRankAssemblesAndStoresItsShareOnly) {
  test::TempDir dir("slepc_share");
  write_part(dir, Body::Solid, Method::Free, "slepc");
  // With its log (reduce_command's --quiet left out): rank 0 prints every rank's line.
  auto logged = [&](const std::string& out) {
    return test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " -o " + (dir / out).string();
  };
  const auto one = test::run(mpirun(1, logged("one.sid.h5")));
  ASSERT_EQ(one.status, 0) << one.output;
  const auto two = test::run(mpirun(2, logged("two.sid.h5")));
  ASSERT_EQ(two.status, 0) << two.output;
  const auto whole = rank_shares(one.output, 1);
  const auto half = rank_shares(two.output, 2);
  ASSERT_EQ(whole.size(), 1u) << one.output;
  ASSERT_EQ(half.size(), 2u) << two.output;
  EXPECT_EQ(half[0].elements + half[1].elements, whole[0].elements);
  for (int r = 0; r < 2; ++r) {
    const RankShare& s = half[static_cast<std::size_t>(r)];
    EXPECT_GT(s.elements, 0) << "rank " << r;
    EXPECT_LT(s.assembled, 0.75 * static_cast<double>(whole[0].assembled)) << "rank " << r << "\n" << two.output;
    EXPECT_LT(s.rows, 0.75 * static_cast<double>(whole[0].rows)) << "rank " << r << "\n" << two.output;
  }
  // The summed rows are the whole matrices: every entry of one rank's K and M is in one rank's rows.
  EXPECT_EQ(half[0].rows + half[1].rows, whole[0].rows);
  const auto diff = test::run(test::bin("ffr-diff").string() + " " + (dir / "one.sid.h5").string() + " " +
                              (dir / "two.sid.h5").string() + " --rtol 1e-6");
  EXPECT_EQ(diff.status, 0) << diff.output;
}

// Bad input found after the distributed assembly (no mass at any DOF: a density of 0, seen
// only in the summed M): the serial path's message on every rank, exit status 2, no SID.
TEST(Slepc, MasslessPartRefusedOnTwoRanks) {
  test::TempDir dir("slepc_massless");
  write_part(dir, Body::Solid, Method::Free, "slepc");
  std::string json = part_json(Body::Solid, Method::Free, "slepc");
  json.replace(json.find("\"rho\": 7850"), 11, "\"rho\": 0");
  test::write_text(dir / "part.json", json);
  const auto r = test::run(mpirun(2, reduce_command(dir, "out.sid.h5")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("materials"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("carry no mass"), std::string::npos) << r.output;
  EXPECT_EQ(stray_files(dir), "");
}

// Without mpirun the same program runs the backend on one rank.
TEST(Slepc, RunsWithoutMpirunOnOneRank) {
  test::TempDir dir("slepc1");
  write_part(dir, Body::Solid, Method::Free, "slepc");
  const auto one = test::run(reduce_command(dir, "one.sid.h5"));
  ASSERT_EQ(one.status, 0) << one.output;
  const auto serial = test::run(reduce_command(dir, "serial.sid.h5") + " --backend block");
  ASSERT_EQ(serial.status, 0) << serial.output;
  const auto diff = test::run(test::bin("ffr-diff").string() + " " + (dir / "serial.sid.h5").string() + " " +
                              (dir / "one.sid.h5").string() + " --rtol 1e-6");
  EXPECT_EQ(diff.status, 0) << diff.output;
}

// Under mpirun only the slepc backend divides the work: another one is refused on every rank
// (each would write the same file), naming the field.
TEST(Slepc, RefusesASerialBackendUnderMpirun) {
  test::TempDir dir("slepc_serial_mpi");
  write_part(dir, Body::Solid, Method::Free, "block");
  const auto r = test::run(mpirun(2, reduce_command(dir, "out.sid.h5")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("reduction.backend"), std::string::npos) << r.output;
  EXPECT_EQ(stray_files(dir), "");
}

// A failure inside PETSc on every rank (here a factorization package it does not have, chosen
// through PETSC_OPTIONS): PETSc's message, exit status 1, no SID and no temporary file.
TEST(Slepc, PetscFailureLeavesNoSid) {
  test::TempDir dir("slepc_fail");
  write_part(dir, Body::Solid, Method::Free, "slepc");
  const auto r = test::run(mpirun(2, reduce_command(dir, "out.sid.h5"), "PETSC_OPTIONS='-st_pc_factor_mat_solver_type no_such_package'"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("slepc backend"), std::string::npos) << r.output;
  EXPECT_EQ(stray_files(dir), "");
}

// One rank fails alone while the other goes on into the collective eigen-solve: Open MPI's MPMD
// launch gives rank 1 a part whose geometry gmsh cannot read. The failing rank names itself and
// ends the job with the exit status of its error (2, bad input) instead of leaving rank 0
// waiting; rank 0 is stopped before it writes, so there is no SID and no temporary file.
TEST(Slepc, OneRankFailingEndsTheJobWithoutSid) {
  test::TempDir dir("slepc_rank_fails");
  write_part(dir, Body::Solid, Method::Free, "slepc");
  test::write_text(dir / "bad.geo", "Box(1) = {0, 0, 0, 0.2, 0.02\n");
  std::string bad = part_json(Body::Solid, Method::Free, "slepc");
  bad.replace(bad.find("part.geo"), 8, "bad.geo");
  test::write_text(dir / "bad.json", bad);
  const std::string tool = test::bin("ffr-reduce").string(), out = (dir / "out.sid.h5").string();
  const auto r = test::run(FFR_TEST_MPI_ENV FFR_MPIEXEC " --oversubscribe -np 1 " +
                           tool + " " + (dir / "part.json").string() + " -o " + out + " --quiet : -np 1 " + tool + " " +
                           (dir / "bad.json").string() + " -o " + out + " --quiet");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bad.geo"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(rank 1 of 2)"), std::string::npos) << r.output;
  EXPECT_EQ(stray_files(dir), "");
}

// The solid bar clamped with the part file's MUMPS settings (reduction.mumps_ordering,
// out_of_core), written after the backend: the part's own reduction with `extra` keys; beside
// it serial.json, the same part on the serial path (which refuses MUMPS keys).
void write_mumps_part(const test::TempDir& dir, const std::string& extra) {
  std::string json = part_json(Body::Solid, Method::Clamped, "slepc");
  json.insert(json.rfind("}}"), extra);
  test::write_text(dir / "part.geo", kSolidGeo);
  test::write_text(dir / "part.json", json);
  test::write_text(dir / "serial.json", part_json(Body::Solid, Method::Clamped, "block"));
}

// The serial path's SID of write_mumps_part's part, the reference of the runs with MUMPS keys.
std::string serial_command(const test::TempDir& dir) {
  return test::bin("ffr-reduce").string() + " " + (dir / "serial.json").string() + " -o " +
         (dir / "serial.sid.h5").string() + " --quiet";
}

// MUMPS's other fill-reducing orderings and its out-of-core factors change how the factor is
// computed and stored, not what it is: on two ranks the SID is the serial path's (reference:
// the serial path, as above; ffr-diff at rtol 1e-6). The out-of-core files, written to the
// part's out_of_core_dir, are gone afterwards; the log names the ordering MUMPS used (its
// INFOG(7)) and whether its factor was in core.
TEST(Slepc, MumpsOrderingsAndOutOfCoreGiveTheSerialSid) {
  struct Case {
    const char* extra;
    const char* ordering_used;
    const char* storage;
  };
  for (const Case& c : {Case{R"(, "mumps_ordering": "amd")", "MUMPS: AMD ordering", "factors in core"},
                        Case{R"(, "mumps_ordering": "qamd")", "MUMPS: QAMD ordering", "factors in core"},
                        Case{R"(, "out_of_core": true, "out_of_core_dir": "ooc")", "MUMPS: PORD ordering", "factors out of core"},
                        Case{R"(, "mumps_ordering": "amf", "out_of_core": true, "out_of_core_dir": "ooc")",
                             "MUMPS: AMF ordering", "factors out of core"}}) {
    SCOPED_TRACE(c.extra);
    test::TempDir dir("slepc_mumps");
    write_mumps_part(dir, c.extra);
    fs::create_directory(dir / "ooc");
    const auto serial = test::run(serial_command(dir));
    ASSERT_EQ(serial.status, 0) << serial.output;
    const std::string logged =
        test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " -o " + (dir / "mpi.sid.h5").string();
    const auto mpi = test::run(mpirun(2, logged));
    ASSERT_EQ(mpi.status, 0) << mpi.output;
    EXPECT_NE(mpi.output.find(c.ordering_used), std::string::npos) << mpi.output;
    EXPECT_NE(mpi.output.find(c.storage), std::string::npos) << mpi.output;
    const auto diff = test::run(test::bin("ffr-diff").string() + " " + (dir / "serial.sid.h5").string() + " " +
                                (dir / "mpi.sid.h5").string() + " --rtol 1e-6");
    EXPECT_EQ(diff.status, 0) << diff.output;
    EXPECT_TRUE(fs::is_empty(dir / "ooc"));
  }
}

// MUMPS failing in its factorization (provoked by a limit of 1 MB of working memory per rank,
// ICNTL(23), through PETSC_OPTIONS: MUMPS's code -19): the message names the stage, MUMPS's
// INFOG(1) and what to try; exit status 1 on every rank, no SID and no temporary file.
TEST(Slepc, MumpsFailureNamesStageCodeAndRemedy) {
  test::TempDir dir("slepc_mumps_fail");
  write_mumps_part(dir, "");
  const auto r = test::run(mpirun(2, reduce_command(dir, "out.sid.h5"), "PETSC_OPTIONS='-st_mat_mumps_icntl_23 1'"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("MUMPS's numerical factorization failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("INFOG(1) = -19"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ICNTL(23)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("out_of_core"), std::string::npos) << r.output;
  EXPECT_EQ(stray_files(dir), "");
}

// An ordering this MUMPS may lack (Debian's is built with PORD, AMD, AMF and QAMD only): where
// MUMPS orders by another method, the run is refused naming the field and the ordering used;
// where it has METIS, the SID is the serial path's.
TEST(Slepc, OrderingMumpsLacksIsNamed) {
  test::TempDir dir("slepc_metis");
  write_mumps_part(dir, R"(, "mumps_ordering": "metis")");
  const auto r = test::run(mpirun(2, reduce_command(dir, "mpi.sid.h5")));
  if (r.status == 0) {
    const auto serial = test::run(serial_command(dir));
    ASSERT_EQ(serial.status, 0) << serial.output;
    const auto diff = test::run(test::bin("ffr-diff").string() + " " + (dir / "serial.sid.h5").string() + " " +
                                (dir / "mpi.sid.h5").string() + " --rtol 1e-6");
    EXPECT_EQ(diff.status, 0) << diff.output;
  } else {
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("not by the METIS asked for (reduction.mumps_ordering)"), std::string::npos) << r.output;
    EXPECT_EQ(stray_files(dir), "");
  }
}

// The MUMPS keys checked with the part file: an unknown ordering, a key with a serial backend,
// an out-of-core directory that does not exist or without out_of_core: each names its field,
// exit status 2, no SID.
TEST(Slepc, BadMumpsKeysRefused) {
  struct Case {
    std::string extra, backend, field, text;
  };
  for (const Case& c : {Case{R"(, "mumps_ordering": "nested")", "slepc", "reduction.mumps_ordering", "pord"},
                        Case{R"(, "out_of_core": true, "out_of_core_dir": "no_such_dir")", "slepc",
                             "reduction.out_of_core_dir", "not a directory"},
                        Case{R"(, "out_of_core_dir": ".")", "slepc", "reduction.out_of_core_dir", "\"out_of_core\": true"},
                        Case{R"(, "out_of_core": "yes")", "slepc", "reduction.out_of_core", ""},
                        Case{R"(, "mumps_ordering": "amd")", "block", "reduction.mumps_ordering", "only for backend"}}) {
    SCOPED_TRACE(c.extra);
    test::TempDir dir("slepc_mumps_keys");
    std::string json = part_json(Body::Solid, Method::Clamped, c.backend);
    json.insert(json.rfind("}}"), c.extra);
    test::write_text(dir / "part.geo", kSolidGeo);
    test::write_text(dir / "part.json", json);
    const auto r = test::run(reduce_command(dir, "out.sid.h5"));
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(c.field), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.text), std::string::npos) << r.output;
    EXPECT_EQ(stray_files(dir), "");
  }
}

// A serial backend chosen on the command line for a part with MUMPS keys would ignore them:
// refused naming the option and the first key, exit status 2, no SID.
TEST(Slepc, SerialBackendOnTheCommandLineRefusesMumpsKeys) {
  test::TempDir dir("slepc_mumps_cli");
  write_mumps_part(dir, R"(, "out_of_core": true, "mumps_ordering": "amd")");
  for (const char* backend : {"block", "spectra", "arpack"}) {
    SCOPED_TRACE(backend);
    const auto r = test::run(reduce_command(dir, "out.sid.h5") + " --backend " + backend);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(std::string("--backend ") + backend), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("reduction.mumps_ordering"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("part.json"), std::string::npos) << r.output;
    EXPECT_EQ(stray_files(dir), "");
  }
}

#else

// Built without SLEPc: the backend is refused at the part file, naming the field, exit status 2.
TEST(Slepc, RefusedWhereNotBuiltIn) {
  test::TempDir dir("slepc_absent");
  write_part(dir, Body::Solid, Method::Free, "slepc");
  const auto r = test::run(reduce_command(dir, "out.sid.h5"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("reduction.backend"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not built into"), std::string::npos) << r.output;
  EXPECT_EQ(stray_files(dir), "");
}

#endif

// An unknown backend is refused naming the field, with or without SLEPc.
TEST(Slepc, UnknownBackendRefused) {
  test::TempDir dir("slepc_unknown");
  write_part(dir, Body::Solid, Method::Free, "petsc");
  const auto r = test::run(reduce_command(dir, "out.sid.h5"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("reduction.backend"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("slepc"), std::string::npos) << r.output;
  EXPECT_EQ(stray_files(dir), "");
}
