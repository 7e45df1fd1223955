// A mixed part: a shell plate stiffened by a beam along its centre line, sharing the nodes
// of that line (shells and beams join by sharing all six DOFs), clamped at one end. The
// reduction runs, validates, its mass is exactly the sum of the parts, and the stiffener
// raises the first bending frequency of the plate.
#include "ffr/formats/validate.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "../reduce/support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

namespace {
const char* kGeo = R"(
Point(1) = {0, 0, 0}; Point(2) = {0.5, 0, 0}; Point(3) = {0.5, 0.1, 0}; Point(4) = {0, 0.1, 0};
Point(5) = {0, 0.05, 0}; Point(6) = {0.5, 0.05, 0};
Line(1) = {1, 2}; Line(2) = {2, 6}; Line(3) = {6, 3}; Line(4) = {3, 4}; Line(5) = {4, 5}; Line(6) = {5, 1};
Line(7) = {5, 6};
Curve Loop(1) = {1, 2, -7, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {7, 3, 4, 5}; Plane Surface(2) = {2};
Transfinite Curve{1, 4, 7} = 26; Transfinite Curve{2, 3, 5, 6} = 4;
Transfinite Surface{1}; Transfinite Surface{2}; Recombine Surface{1, 2};
Physical Surface("plate") = {1, 2}; Physical Curve("stiffener") = {7}; Physical Curve("clamp") = {5, 6};
)";
formats::Sid reduce(const test::TempDir& dir, bool stiffener) {
  test::write_text(dir / "mixed.geo", kGeo);
  std::string beams = stiffener ? R"("beams": [{"group": "stiffener", "E": 7e10, "nu": 0.3, "rho": 2700, "y_axis": [0, 1, 0],
      "section": {"A": 1e-4, "Iy": 8.33e-10, "Iz": 8.33e-10, "J": 1.4e-9}}],)" : "";
  test::write_text(dir / "mixed.json", R"({"geometry": "mixed.geo", "mesh": {"order": 1},
    "shells": [{"group": "plate", "thickness": 0.002, "E": 7e10, "nu": 0.3, "rho": 2700}], )" + beams + R"(
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 4}, "visual": false})");
  return preproc::run_pipeline(preproc::load_part(dir / "mixed.json"));
}
}  // namespace

TEST(Mixed, ShellPlateWithBeamStiffener) {
  test::TempDir dir("mixed");
  const formats::Sid plain = reduce(dir, false), stiff = reduce(dir, true);
  const auto report = formats::validate(stiff);
  for (const auto& c : report.checks)
    EXPECT_TRUE(!c.applicable || c.pass) << c.name << ": violation " << c.rel << " > " << c.tol << " " << c.note;
  EXPECT_NEAR(plain.refmod.mass, 2700 * 0.5 * 0.1 * 0.002, 1e-12);
  EXPECT_NEAR(stiff.refmod.mass, plain.refmod.mass + 2700 * 1e-4 * 0.5, 1e-12);
  // A 10 x 10 mm bar on a 2 mm plate stiffens the first bending mode a lot.
  EXPECT_GT(stiff.refmod.frequency_hz(0), 1.5 * plain.refmod.frequency_hz(0));
}
