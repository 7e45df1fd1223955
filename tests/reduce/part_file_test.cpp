// Part-file validation: every bad input is a FormatError that names the file and the field.
#include "ffr/formats/h5.hpp"
#include "ffr/preproc/part/part.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

namespace {

// Loads a part file with the given text; returns the error message ("" if it loaded).
std::string error_of(const std::string& json) {
  test::TempDir dir("part");
  test::write_text(dir / "g.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0,0,0,1,1,1};\n");
  test::write_text(dir / "p.json", json);
  std::filesystem::create_symlink("/dev/zero", dir / "zero.msh");
  try {
    preproc::load_part(dir / "p.json");
  } catch (const formats::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("p.json"), std::string::npos) << "message names the file: " << e.what();
    return e.what();
  }
  return "";
}

const std::string kOk = R"("geometry": "g.geo", "materials": [{"group": "all", "E": 7e10, "nu": 0.3, "rho": 2700}])";

}  // namespace

TEST(PartFile, AValidFileLoads) {
  EXPECT_EQ(error_of("{" + kOk + R"(, "reduction": {"method": "free", "modes": 6}})"), "");
}

TEST(PartFile, BadInputsNameTheField) {
  struct Case { std::string json, expect; };
  const std::vector<Case> cases = {
      {R"({"geometry": "g.geo", )", "malformed JSON"},
      {R"({"geometry": "g.geo", "reduction": {"method": "free", "modes": 6}})", "no material"},
      {R"({"geometry": "missing.step", "materials": [], "reduction": {"method": "free", "modes": 6}})", "geometry"},
      {R"({"geometry": "g.iges", "reduction": {"method": "free", "modes": 6}})", "unsupported geometry"},
      // Not a regular file: a device would be read without end (a link to /dev/zero).
      {R"({"geometry": "zero.msh", "materials": [], "reduction": {"method": "free", "modes": 6}})", "geometry: not a regular file"},
      {"{" + kOk + R"(, "reduction": {"method": "free"}})", "modes"},
      {"{" + kOk + R"(, "reduction": {"method": "wobbly", "modes": 6}})", "reduction.method"},
      {"{" + kOk + R"(, "reduction": {"method": "clamped", "interface": "root", "modes": 6}})", "no interface named 'root'"},
      {R"({"geometry": "g.geo", "materials": [{"group": "all", "E": -7e10, "nu": 0.3, "rho": 2700}], "reduction": {"method": "free", "modes": 6}})", "materials[0].E"},
      {R"({"geometry": "g.geo", "materials": [{"group": "all", "E": 7e10, "nu": 0.5, "rho": 2700}], "reduction": {"method": "free", "modes": 6}})", "materials[0].nu"},
      {R"({"geometry": "g.geo", "materials": [{"group": "all", "E": 7e10, "nu": 0.3, "rho": "heavy"}], "reduction": {"method": "free", "modes": 6}})", "materials[0].rho"},
      {"{" + kOk + R"(, "reduction": {"method": "free", "modes": 6}, "thikness": 1})", "thikness"},
      {"{" + kOk + R"(, "units": {"length": "furlong"}, "reduction": {"method": "free", "modes": 6}})", "units.length"},
      {"{" + kOk + R"(, "mesh": {"order": 3}, "reduction": {"method": "free", "modes": 6}})", "mesh.order"},
      {"{" + kOk + R"(, "interfaces": [{"name": "a", "group": "g", "coupling": "glued"}], "reduction": {"method": "free", "modes": 6}})", "interfaces[0].coupling"},
      {"{" + kOk + R"(, "point_masses": [{"name": "m", "at": [0,0,0], "mass": 1, "inertia": [[1,0,0],[0,1,0],[0,0,5]]}], "reduction": {"method": "free", "modes": 6}})", "triangle inequality"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of(c.json);
    EXPECT_NE(e.find(c.expect), std::string::npos) << "input: " << c.json << "\nmessage: " << e;
  }
}

// E and rho in another unit system than the part's: sqrt(E / rho) leaves the range of solids
// (20 m/s for soft rubber to 18 km/s for diamond; refused outside 10 m/s .. 1e5 m/s).
TEST(PartFile, UnitMistakesAreRefused) {
  const auto part = [](const std::string& units, const std::string& block, const std::string& mat) {
    return R"({"geometry": "g.geo", "units": )" + units + ", \"" + block + R"(": [{"group": "all", )" + mat +
           R"(}], "reduction": {"method": "free", "modes": 6}})";
  };
  const std::string si = R"({"length": "m", "mass": "kg", "time": "s"})";
  const std::string mm = R"({"length": "mm", "mass": "t", "time": "s"})";
  // Aluminium: 5.09 km/s in every consistent system.
  EXPECT_EQ(error_of(part(si, "materials", R"("E": 7e10, "nu": 0.33, "rho": 2700)")), "");
  EXPECT_EQ(error_of(part(mm, "materials", R"("E": 70000, "nu": 0.33, "rho": 2.7e-9)")), "");
  // Soft rubber, 42.6 m/s: a material, not a mistake.
  EXPECT_EQ(error_of(part(si, "materials", R"("E": 2e6, "nu": 0.45, "rho": 1100)")), "");
  struct Case { std::string json, expect; };
  const std::vector<Case> cases = {
      // E in MPa with rho in kg/m^3 and lengths in mm: 5.09 mm/s.
      {part(mm, "materials", R"("E": 70000, "nu": 0.33, "rho": 2700)"), "materials[0]: sqrt(E / rho) = 5.09 mm/s (0.00509 m/s)"},
      // E in GPa in SI: 0.161 m/s.
      {part(si, "materials", R"("E": 70, "nu": 0.33, "rho": 2700)"), "(0.161 m/s)"},
      // E in Pa with lengths in mm: 5.09e6 m/s.
      {part(mm, "materials", R"("E": 7e10, "nu": 0.33, "rho": 2.7e-9)"), "E and rho are not in the part's units (length mm, mass t, time s"},
      // The SI values in a part declared in mm and t: 5.09 m/s.
      {part(mm, "materials", R"("E": 7e10, "nu": 0.33, "rho": 2700)"), "(5.09 m/s)"},
      // rho in g/cm^3 in SI, on a shell.
      {part(si, "shells", R"("thickness": 0.002, "E": 7e10, "nu": 0.33, "rho": 2.7)"), "shells[0]: sqrt(E / rho)"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of(c.json);
    EXPECT_NE(e.find(c.expect), std::string::npos) << "input: " << c.json << "\nmessage: " << e;
  }
}

// Keys that contradict each other or belong to another reduction method were ignored without a
// word (both "modes" and "max_frequency_hz" gave 74 modes for 4 asked); each is refused naming
// the field, and the meaningful combinations still load.
TEST(PartFile, ContradictoryOrForeignReductionKeysAreRefused) {
  const std::string itf = R"("interfaces": [{"name": "a", "group": "all"}, {"name": "b", "group": "all"}], )";
  const auto part = [&](const std::string& reduction) { return "{" + kOk + ", " + itf + R"("reduction": )" + reduction + "}"; };
  EXPECT_EQ(error_of(part(R"({"method": "free", "max_frequency_hz": 500})")), "");
  EXPECT_EQ(error_of(part(R"({"method": "clamped", "interface": "a", "modes": 4})")), "");
  EXPECT_EQ(error_of(part(R"({"method": "craig-bampton", "interfaces": ["a", "b"], "frame": "b", "modes": 4, "orthonormalize": true})")), "");
  EXPECT_EQ(error_of(part(R"({"method": "craig-bampton", "interfaces": ["a", "b"], "max_frequency_hz": 900})")), "");
  struct Case { std::string reduction, expect; };
  const std::vector<Case> cases = {
      {R"({"method": "free", "modes": 4, "max_frequency_hz": 500})", "reduction.max_frequency_hz: give either \"modes\" (a count) or \"max_frequency_hz\", not both"},
      {R"({"method": "clamped", "interface": "a", "modes": 0, "max_frequency_hz": 500})", "reduction.max_frequency_hz: give either"},
      {R"({"method": "free", "modes": 4, "interface": "a"})", "reduction.interface: not a key of method \"free\" (it belongs to \"clamped\")"},
      {R"({"method": "free", "modes": 4, "frame": "a"})", "reduction.frame: not a key of method \"free\" (it belongs to \"craig-bampton\")"},
      {R"({"method": "free", "modes": 4, "interfaces": ["a"]})", "reduction.interfaces: not a key of method \"free\""},
      {R"({"method": "free", "modes": 4, "orthonormalize": false})", "reduction.orthonormalize: not a key of method \"free\""},
      {R"({"method": "clamped", "interface": "a", "modes": 4, "frame": "a"})", "reduction.frame: not a key of method \"clamped\""},
      {R"({"method": "craig-bampton", "interfaces": ["a", "b"], "interface": "a", "modes": 4})", "reduction.interface: not a key of method \"craig-bampton\""},
  };
  for (const auto& c : cases) {
    const std::string e = error_of(part(c.reduction));
    EXPECT_NE(e.find(c.expect), std::string::npos) << "input: " << c.reduction << "\nmessage: " << e;
  }
}

TEST(PartFile, MeshTimeLimitIsAPositiveNumberOfSeconds) {
  const auto with = [](const std::string& mesh) {
    return "{" + kOk + R"(, "mesh": )" + mesh + R"(, "reduction": {"method": "free", "modes": 6}})";
  };
  EXPECT_EQ(error_of(with(R"({"time_limit_s": 30})")), "");
  EXPECT_NE(error_of(with(R"({"time_limit_s": 0})")).find("mesh.time_limit_s"), std::string::npos);
  EXPECT_NE(error_of(with(R"({"time_limit_s": -5})")).find("mesh.time_limit_s"), std::string::npos);
  EXPECT_NE(error_of(with(R"({"time_limit_s": "long"})")).find("mesh.time_limit_s"), std::string::npos);
}
