// ffr-reduce as a user runs it: the examples reduce and validate; bad inputs get exit 2, one
// clear message naming the file and the field, and no output file; Spectra and ARPACK give the
// same modes (compared with ffr-diff, which ignores signs and rotations in repeated pairs).
#include "support.hpp"

#include "ffr/formats/sid_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

using namespace ffr;

namespace {
const std::string kGeoBar = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)";

// The clamped bar of kGeoBar reduced to 5 modes, with `extra` keys appended to its reduction.
std::string clamped_bar_part(const std::string& extra) {
  return R"({"geometry": "bar.geo", "mesh": {"size": 0.006},
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "interfaces": [{"name": "root", "group": "clamp"}], "visual": false,
    "reduction": {"method": "clamped", "interface": "root", "modes": 5)" + extra + "}}";
}

test::RunResult reduce(const test::TempDir& dir, const std::string& part_json, const std::string& extra = "") {
  test::write_text(dir / "bar.geo", kGeoBar);
  test::write_text(dir / "part.json", part_json);
  return test::run(test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " -o " +
                   (dir / "out.sid.h5").string() + " --quiet " + extra);
}
// A tetrahedral mesh file of a small box written by gmsh (format option as for gmsh -format).
void write_box_mesh(const test::TempDir& dir, const std::string& format) {
  test::write_text(dir / "box.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0,0,0,0.1,0.02,0.02};\nPhysical Volume(\"body\") = {1};\n");
  ASSERT_EQ(test::run("gmsh -3 -clmax 0.02 " + format + " " + (dir / "box.geo").string() + " -o " + (dir / "box.msh").string()).status, 0);
}

// ffr-reduce on a (damaged) box.msh, free-free, steel.
test::RunResult reduce_box_mesh(const test::TempDir& dir, const std::string& msh) {
  test::write_text(dir / "box.msh", msh);
  test::write_text(dir / "part.json", R"({"geometry": "box.msh",
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}], "reduction": {"method": "free", "modes": 4}})");
  return test::run(test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " -o " +
                   (dir / "out.sid.h5").string() + " --quiet");
}
}  // namespace

TEST(ReduceCli, HelpAndVersion) {
  const auto h = test::run(test::bin("ffr-reduce").string() + " --help");
  EXPECT_EQ(h.status, 0);
  EXPECT_NE(h.output.find("usage: ffr-reduce"), std::string::npos);
  const auto v = test::run(test::bin("ffr-reduce").string() + " --version");
  EXPECT_EQ(v.status, 0);
  EXPECT_NE(v.output.find("ffr"), std::string::npos);
}

TEST(ReduceCli, BadInputsExitTwoWithoutOutput) {
  struct Case { std::string name, json, expect; };
  const std::string mat = R"("materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}])";
  const std::vector<Case> cases = {
      {"missing geometry", R"({"geometry": "nothere.geo", )" + mat + R"(, "reduction": {"method": "free", "modes": 4}})", "nothere.geo"},
      {"unknown group", R"({"geometry": "bar.geo", "materials": [{"group": "bodee", "E": 2.1e11, "nu": 0.3, "rho": 7850}], "reduction": {"method": "free", "modes": 4}})", "no group 'bodee'"},
      {"no material", R"({"geometry": "bar.geo", "reduction": {"method": "free", "modes": 4}})", "no material"},
      {"clamped interface does not exist", R"({"geometry": "bar.geo", )" + mat + R"(, "reduction": {"method": "clamped", "interface": "root", "modes": 4}})", "no interface named 'root'"},
      {"material on a surface group", R"({"geometry": "bar.geo", "materials": [{"group": "clamp", "E": 2.1e11, "nu": 0.3, "rho": 7850}], "reduction": {"method": "free", "modes": 4}})", "surface group"},
      // Held at one point: the body can still rotate about it.
      {"mechanism", R"({"geometry": "bar.geo", )" + mat + R"(, "groups": [{"name": "corner", "dim": 0, "box": [-1e-6, -1e-6, -1e-6, 1e-6, 1e-6, 1e-6]}],
          "interfaces": [{"name": "pin", "group": "corner"}], "reduction": {"method": "clamped", "interface": "pin", "modes": 4}})", "mechanism"},
      // Found by fuzzing: these reached the eigen-solver or the SID's validation (exit 1, no field).
      {"no mass anywhere", R"({"geometry": "bar.geo", "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 0}], "reduction": {"method": "free", "modes": 4}})",
       "degrees of freedom carry no mass"},
      {"massless structure with a point mass", R"({"geometry": "bar.geo", "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 0}],
          "point_masses": [{"name": "m", "at": [0.2, 0.02, 0.012], "mass": 1}], "reduction": {"method": "free", "modes": 4}})",
       "degrees of freedom carry no mass"},
      {"empty node name", R"({"geometry": "bar.geo", )" + mat + R"(, "output_nodes": [{"name": "", "at": [0.2, 0, 0]}], "reduction": {"method": "free", "modes": 4}})",
       "output_nodes[0].name: must not be empty"},
      // gmsh took memory at 200 MB/s until killed (5e-11 on a 1 m beam); refused before meshing.
      {"mesh size far too small", R"({"geometry": "bar.geo", "mesh": {"size": 1e-7}, )" + mat + R"(, "reduction": {"method": "free", "modes": 4}})",
       "mesh.size: 1e-07 gives about 4.1e+17 elements"},  // 6 sqrt(2) * 0.2 * 0.02 * 0.012 / 1e-21
      {"dimension beyond long long", R"({"geometry": "bar.geo", )" + mat + R"(, "groups": [{"name": "g", "dim": 1e19, "box": [0, 0, 0, 1, 1, 1]}], "reduction": {"method": "free", "modes": 4}})",
       "groups[0].dim: integer out of range"},
  };
  for (const auto& c : cases) {
    test::TempDir dir("cli");
    const auto r = reduce(dir, c.json);
    EXPECT_EQ(r.status, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find("part.json"), std::string::npos) << c.name << " names the file: " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5")) << c.name;
    for (const auto& f : std::filesystem::directory_iterator(dir.path()))
      EXPECT_EQ(f.path().filename().string().find(".tmp"), std::string::npos) << c.name << " left " << f.path();
  }
}

// An output that names an input or the other output, or lies in no folder: refused before the
// reduction, the inputs untouched (ffr-reduce part.json -o part.json replaced the part file
// by the SID, exit 0; a missing folder failed after the reduction with HDF5's message).
TEST(ReduceCli, OutputsThatWouldOverwriteAnInputOrEachOtherAreRefused) {
  test::TempDir dir("cli");
  test::write_text(dir / "bar.geo", kGeoBar);
  test::write_text(dir / "part.json", clamped_bar_part(""));
  const std::string reduce = test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " --quiet ";
  const std::string part = (dir / "part.json").string(), geo = (dir / "bar.geo").string();
  struct Case { std::string args, expect; };
  const std::vector<Case> cases = {
      {"-o " + part, "-o " + part + " would overwrite the part file " + part},
      {"-o " + (dir / "." / "bar.geo").string(), "would overwrite the part's geometry " + geo},
      {"-o " + (dir / "out.sid.h5").string() + " --vtk " + (dir / "out.sid.h5").string(), "--vtk " + (dir / "out.sid.h5").string() + " names the same file as -o"},
      {"-o " + (dir / "nowhere" / "out.sid.h5").string(), "no directory " + (dir / "nowhere").string() + " to write it in"},
  };
  for (const auto& c : cases) {
    const auto r = test::run(reduce + c.args);
    EXPECT_EQ(r.status, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << ": " << r.output;
  }
  const auto text = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  EXPECT_EQ(text(dir / "part.json"), clamped_bar_part(""));
  EXPECT_EQ(text(dir / "bar.geo"), kGeoBar);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
}

TEST(ReduceCli, TwoDisconnectedSolidsInAFreeBodyAreRefused) {
  test::TempDir dir("cli");
  test::write_text(dir / "two.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.02, 0.02};
Box(2) = {0.2, 0, 0, 0.1, 0.02, 0.02};
Physical Volume("body") = {1, 2};
)");
  test::write_text(dir / "part.json", R"({"geometry": "two.geo", "mesh": {"size": 0.01},
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}], "reduction": {"method": "free", "modes": 4}})");
  const auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " -o " +
                           (dir / "out.sid.h5").string() + " --quiet");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("not one connected piece"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
}

TEST(ReduceCli, SpectraArpackAndBlockGiveTheSameModes) {
  test::TempDir dir("backends");
  const std::string part = R"({"geometry": "bar.geo", "mesh": {"size": 0.005, "order": 2},
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 8}, "output_nodes": [{"name": "tip", "at": [0.2, 0, 0]}]})";
  auto r = reduce(dir, part, "--backend spectra");
  ASSERT_EQ(r.status, 0) << r.output;
  std::filesystem::rename(dir / "out.sid.h5", dir / "spectra.sid.h5");
  r = reduce(dir, part, "--backend arpack");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto d = test::run(test::bin("ffr-diff").string() + " " + (dir / "spectra.sid.h5").string() + " " +
                           (dir / "out.sid.h5").string() + " --rtol 1e-6");
  EXPECT_EQ(d.status, 0) << d.output;
  r = reduce(dir, part, "--backend block");  // the default: block Lanczos
  ASSERT_EQ(r.status, 0) << r.output;
  const auto db = test::run(test::bin("ffr-diff").string() + " " + (dir / "spectra.sid.h5").string() + " " +
                            (dir / "out.sid.h5").string() + " --rtol 1e-6");
  EXPECT_EQ(db.status, 0) << db.output;
  // And the file is valid per ffr-info.
  const auto info = test::run(test::bin("ffr-info").string() + " " + (dir / "out.sid.h5").string());
  EXPECT_EQ(info.status, 0) << info.output;
}

TEST(ReduceCli, ExamplesReduce) {
  for (const char* ex : {"meshes/cantilever/cantilever.json", "meshes/link/link.json"}) {
    test::TempDir dir("examples");
    const auto r = test::run(test::bin("ffr-reduce").string() + " " + test::source(ex).string() + " -o " +
                             (dir / "out.sid.h5").string() + " --quiet --vtk " + (dir / "modes.vtk").string());
    EXPECT_EQ(r.status, 0) << ex << ": " << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "out.sid.h5")) << ex;
    EXPECT_TRUE(std::filesystem::exists(dir / "modes.vtk")) << ex;
  }
}

TEST(ReduceCli, InvertedElementInAMeshFileIsRefusedWithItsId) {
  test::TempDir dir("inverted");
  write_box_mesh(dir, "-format msh22");
  if (HasFatalFailure()) return;
  // Swap two nodes of the first tetrahedron (MSH 2.2: id type ntags tags... nodes...): it turns inside out.
  std::ifstream in(dir / "box.msh");
  std::stringstream text;
  text << in.rdbuf();
  std::string msh = text.str();
  std::string tag;
  const auto pos = msh.find("\n", msh.find("$Elements") + 10) + 1;  // after the count line
  std::size_t line = pos;
  while (true) {
    const auto end = msh.find('\n', line);
    std::istringstream ls(msh.substr(line, end - line));
    std::vector<long> v;
    long x;
    while (ls >> x) v.push_back(x);
    if (v.size() == 9 && v[1] == 4) {
      std::swap(v[5], v[6]);
      std::string repl;
      for (std::size_t i = 0; i < v.size(); ++i) repl += std::string(i ? " " : "") + std::to_string(v[i]);
      msh.replace(line, end - line, repl);
      tag = std::to_string(v[0]);
      break;
    }
    line = end + 1;
  }
  const auto r = reduce_box_mesh(dir, msh);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("element " + tag), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("inverted"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
}

TEST(ReduceCli, MeshFileThatCrashesGmshIsRefused) {
  // gmsh 4.8 itself dies (SIGSEGV, also as `gmsh bad.msh -0`) on an element node tag of 2^31
  // (found by fuzzing): read in a child process, that is an error naming the file.
  test::TempDir dir("crash");
  write_box_mesh(dir, "");
  if (HasFatalFailure()) return;
  std::ifstream in(dir / "box.msh");
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  // MSH 4.1 $Elements: a count line, then blocks "dim tag type n" of n lines "id node...".
  std::size_t j = static_cast<std::size_t>(std::find(lines.begin(), lines.end(), "$Elements") - lines.begin()) + 2;
  for (;;) {
    ASSERT_LT(j + 1, lines.size());
    std::istringstream h(lines[j]);
    long dim, tag, type, n;
    h >> dim >> tag >> type >> n;
    if (type == 4) break;  // a block of tetrahedra
    j += 1 + static_cast<std::size_t>(n);
  }
  std::istringstream e(lines[j + 1]);
  std::string id, first, rest;
  e >> id >> first;
  std::getline(e, rest);
  lines[j + 1] = id + " 2147483648" + rest;
  std::string msh;
  for (const auto& l : lines) msh += l + "\n";
  const auto r = reduce_box_mesh(dir, msh);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("box.msh: gmsh crashed on this file"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
}

TEST(ReduceCli, FactorAboveTheMemoryLimitIsRefusedBeforeFactorizing) {
  test::TempDir dir("memory");
  const auto r = reduce(dir, R"({"geometry": "bar.geo", "mesh": {"size": 0.004, "order": 2},
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 4}})", "--max-memory 0.001");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("factor"), std::string::npos) << r.output;  // "needs N bytes, M available"
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
}

// The CPU's vendor string (vendor_id of /proc/cpuinfo), empty where there is none.
static std::string cpu_vendor() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("vendor_id", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? std::string() : line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return {};
}

// The factorization's log line names OpenBLAS's kernels, and when they are older than the CPU
// suits, which ones it would run and how to ask for them (ffr-reduce never changes them itself).
TEST(ReduceCli, LogNamesTheBlasKernelsAndAUsersChoiceStands) {
  test::TempDir dir("kernels");
  const std::string json = R"({"geometry": "bar.geo", "mesh": {"size": 0.01},
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "reduction": {"method": "free", "modes": 2}})";
  test::write_text(dir / "bar.geo", kGeoBar);
  test::write_text(dir / "part.json", json);
  const std::string args = ' ' + (dir / "part.json").string() + " -o " + (dir / "out.sid.h5").string();
  const auto own = test::run("env -u OPENBLAS_CORETYPE " + test::bin("ffr-reduce").string() + args);
  ASSERT_EQ(own.status, 0) << own.output;
  if (own.output.find("OpenBLAS") == std::string::npos) GTEST_SKIP() << "the BLAS is not OpenBLAS";

  // With OpenBLAS held to its oldest kernels, "auto" hands the factorization's dense work to
  // Eigen's on a CPU with AVX2 and FMA (the line names both), and keeps the BLAS elsewhere.
  const auto forced = test::run("OPENBLAS_CORETYPE=Prescott " + test::bin("ffr-reduce").string() + args);
  ASSERT_EQ(forced.status, 0) << forced.output;
  const bool eigen = forced.output.find("dense kernels Eigen (x86-64-v") != std::string::npos;
  if (eigen) {
    EXPECT_NE(forced.output.find("(OpenBLAS's: Prescott)"), std::string::npos) << forced.output;
  } else {
    EXPECT_NE(forced.output.find("OpenBLAS Prescott kernels"), std::string::npos) << forced.output;
  }
  EXPECT_EQ(forced.output.find("this CPU runs"), std::string::npos) << forced.output;  // no advice: not the BLAS's work

  // Held to the BLAS (part file), the advice names the variable on a CPU with AVX2 or AVX-512.
  std::string blas_json = json;
  blas_json.replace(blas_json.find("\"modes\": 2"), 10, "\"modes\": 2, \"dense_kernels\": \"blas\"");
  test::write_text(dir / "part.json", blas_json);
  const auto held = test::run("OPENBLAS_CORETYPE=Prescott " + test::bin("ffr-reduce").string() + args);
  ASSERT_EQ(held.status, 0) << held.output;
  EXPECT_NE(held.output.find("OpenBLAS Prescott kernels"), std::string::npos) << held.output;
  // The advice is for Intel CPUs only (blas_kernels.hpp: OpenBLAS picks AMD's kernels by
  // family); the vendor read here from /proc/cpuinfo, not from the library's own check.
  if (eigen && cpu_vendor() == "GenuineIntel") {
    EXPECT_NE(held.output.find("set OPENBLAS_CORETYPE="), std::string::npos) << held.output;
  } else if (cpu_vendor() != "GenuineIntel") {
    EXPECT_EQ(held.output.find("set OPENBLAS_CORETYPE="), std::string::npos) << held.output;
  }
}

// reduction.dense_kernels: an unknown value, or one other than "auto" with CHOLMOD's own
// factorization (from the part file or --factorization), is bad input naming the field (exit 2,
// no output); "blas" and "eigen" give SIDs
// that ffr-diff finds equivalent at rtol 1e-9 to CHOLMOD's (the "cholmod" backend, the reference).
TEST(ReduceCli, DenseKernelsAreChosenByThePartFile) {
  test::TempDir dir("dense_kernels");
  const auto part = clamped_bar_part;
  for (const std::string bad : {R"(, "dense_kernels": "mkl")", R"(, "factorization": "cholmod", "dense_kernels": "eigen")"}) {
    const auto r = reduce(dir, part(bad));
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("dense_kernels"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("part.json"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
  }
  const auto overridden = reduce(dir, part(R"(, "dense_kernels": "eigen")"), "--factorization cholmod");
  EXPECT_EQ(overridden.status, 2) << overridden.output;
  EXPECT_NE(overridden.output.find("dense_kernels"), std::string::npos) << overridden.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
  ASSERT_EQ(reduce(dir, part(R"(, "factorization": "cholmod")")).status, 0);
  std::filesystem::rename(dir / "out.sid.h5", dir / "cholmod.sid.h5");
  for (const std::string kernels : {"blas", "eigen"}) {
    const auto r = reduce(dir, part(R"(, "dense_kernels": ")" + kernels + "\""));
    ASSERT_EQ(r.status, 0) << r.output;
    const auto d = test::run(test::bin("ffr-diff").string() + " " + (dir / "cholmod.sid.h5").string() + " " +
                             (dir / "out.sid.h5").string() + " --rtol 1e-9");
    EXPECT_EQ(d.status, 0) << kernels << ": " << d.output;
  }
}

TEST(ReduceCli, FrequencyLimitReturnsEveryModeBelowIt) {
  test::TempDir dir("flimit");
  // The clamped bar's modes below 2500 Hz: bending in both planes (about 250, 410, 1560, 2520
  // Hz...) and torsion; compare with a count-based run.
  const std::string base = R"({"geometry": "bar.geo", "mesh": {"size": 0.005, "order": 2},
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "interfaces": [{"name": "root", "group": "clamp"}], "visual": false, "reduction": )";
  ASSERT_EQ(reduce(dir, base + R"({"method": "clamped", "interface": "root", "modes": 12}})").status, 0);
  std::filesystem::rename(dir / "out.sid.h5", dir / "count.sid.h5");
  const auto many = ffr::formats::read_sid(dir / "count.sid.h5");
  const double limit = 0.5 * (many.refmod.frequency_hz(4) + many.refmod.frequency_hz(5));  // between modes 5 and 6
  ASSERT_EQ(reduce(dir, base + R"({"method": "clamped", "interface": "root", "max_frequency_hz": )" + std::to_string(limit) + "}}").status, 0);
  const auto limited = ffr::formats::read_sid(dir / "out.sid.h5");
  ASSERT_EQ(limited.nq(), 5);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(limited.refmod.frequency_hz(k) / many.refmod.frequency_hz(k), 1.0, 1e-9);
}

// reduction.factorization: an unknown value is bad input naming the field (exit 2, no output);
// the two known ones give SIDs that ffr-diff finds equivalent at rtol 1e-9 (reference: CHOLMOD's
// own factorization and solves, the "cholmod" backend).
TEST(ReduceCli, FactorizationBackendIsChosenByThePartFile) {
  test::TempDir dir("factorization");
  const auto part = [](const std::string& factorization) {
    return clamped_bar_part(R"(, "factorization": ")" + factorization + "\"");
  };
  const auto bad = reduce(dir, part("lu"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("factorization"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("part.json"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));

  ASSERT_EQ(reduce(dir, part("cholmod")).status, 0);
  std::filesystem::rename(dir / "out.sid.h5", dir / "cholmod.sid.h5");
  ASSERT_EQ(reduce(dir, part("supernodal")).status, 0);
  const auto d = test::run(test::bin("ffr-diff").string() + " " + (dir / "cholmod.sid.h5").string() + " " +
                           (dir / "out.sid.h5").string() + " --rtol 1e-9");
  EXPECT_EQ(d.status, 0) << d.output;
  // The command line's --factorization overrides the part file.
  const auto over = reduce(dir, part("supernodal"), "--factorization cholmod");
  ASSERT_EQ(over.status, 0) << over.output;
  EXPECT_EQ(ffr::formats::read_sid(dir / "out.sid.h5").provenance.extra.at("factorization"), "cholmod");
  const auto bad_flag = reduce(dir, part("cholmod"), "--factorization lu");
  EXPECT_EQ(bad_flag.status, 2) << bad_flag.output;
}

// An output node is the mesh node nearest to its point; a point farther from every node than the
// diagonal of the part's bounding box (the bar: sqrt(0.2^2 + 0.02^2 + 0.012^2) = 0.2013 m) is
// refused naming the field (an output node 1e6 m away was noted only in the provenance).
TEST(ReduceCli, OutputNodeOrPointMassFarFromThePartIsRefused) {
  const auto part = [](const std::string& at) {
    return R"({"geometry": "bar.geo", "mesh": {"size": 0.01}, "visual": false,
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}], "reduction": {"method": "free", "modes": 4},
      "output_nodes": [{"name": "tip", "at": [0.2, 0, 0]}, {"name": "probe", "at": )" + at + "}]}";
  };
  {
    test::TempDir dir("far");
    const auto r = reduce(dir, part("[0.35, 0, 0]"));  // 0.15 m beyond the end: accepted
    EXPECT_EQ(r.status, 0) << r.output;
  }
  for (const std::string at : {"[1e6, 0, 0]", "[0.45, 0, 0]"}) {  // 1e6 m and 0.25 m from the nearest node
    test::TempDir dir("far");
    const auto r = reduce(dir, part(at));
    EXPECT_EQ(r.status, 2) << at << ": " << r.output;
    EXPECT_NE(r.output.find("part.json: output_nodes[1].at: the nearest mesh node is"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("bounding box (0.201"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
  }
  // A point mass so placed (mm read as m) was put on the nearest node: 1e3 times too far, its
  // mass sat at the bar's end without a word.
  test::TempDir dir("far");
  const auto r = reduce(dir, R"({"geometry": "bar.geo", "mesh": {"size": 0.01}, "visual": false,
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}], "reduction": {"method": "free", "modes": 4},
      "point_masses": [{"name": "motor", "at": [200, 10, 6], "mass": 3}]})");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("part.json: point_masses[0].at: the nearest mesh node is"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
}
