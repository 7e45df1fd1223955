// The same thin cantilever plate (0.4 m x 0.2 m x 5 mm, clamped along x = 0) as QUAD4 shells
// and as HEX20 solids (extruded, two layers): the rigid properties (m, first moment, inertia
// about O, thickness terms included) agree exactly, and the first modes' frequencies and
// participation factors Ct.M0, Cr.M0 agree within the difference of the discretizations.
#include "ffr/preproc/pipeline.hpp"
#include "../reduce/support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

namespace {
formats::Sid shells(const test::TempDir& dir) {
  test::write_text(dir / "shell.geo", R"(
Point(1) = {0, 0, 0.0025}; Point(2) = {0.4, 0, 0.0025}; Point(3) = {0.4, 0.2, 0.0025}; Point(4) = {0, 0.2, 0.0025};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 41; Transfinite Curve{2, 4} = 21; Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1}; Physical Curve("clamp") = {4};
)");
  test::write_text(dir / "shell.json", R"({"geometry": "shell.geo", "mesh": {"order": 1},
    "shells": [{"group": "plate", "thickness": 0.005, "E": 7e10, "nu": 0.3, "rho": 2700}],
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 4}, "visual": false})");
  return preproc::run_pipeline(preproc::load_part(dir / "shell.json"));
}

formats::Sid solids(const test::TempDir& dir) {
  test::write_text(dir / "solid.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {0.4, 0, 0}; Point(3) = {0.4, 0.2, 0}; Point(4) = {0, 0.2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 41; Transfinite Curve{2, 4} = 21; Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude {0, 0, 0.005} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("plate") = {out[1]};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
  test::write_text(dir / "solid.json", R"({"geometry": "solid.geo", "mesh": {"order": 2},
    "materials": [{"group": "plate", "E": 7e10, "nu": 0.3, "rho": 2700}],
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 4}, "visual": false})");
  return preproc::run_pipeline(preproc::load_part(dir / "solid.json"));
}
}  // namespace

TEST(ShellVsSolid, SamePlateSameInvariants) {
  test::TempDir dir("plate");
  const formats::Sid s = shells(dir), v = solids(dir);
  // Rigid properties: exact for both (the shell integrates its thickness).
  EXPECT_NEAR(s.refmod.mass / v.refmod.mass, 1.0, 1e-12);
  EXPECT_LT((s.mdCM.M0 - v.mdCM.M0).norm(), 1e-12 * v.mdCM.M0.norm());
  // The shell's J.M0 also holds its drilling inertia rho t^3/12 per area (the rotary part that
  // keeps M definite, consistent with the modes' normalisation): the material part is exact,
  // the whole within discretisation error.
  EXPECT_LT((s.J.M0 - s.rotary.I - v.J.M0).cwiseAbs().maxCoeff(), 1e-12 * v.J.M0.norm()) << s.J.M0 << "\nvs\n" << v.J.M0;
  EXPECT_LT((s.J.M0 - v.J.M0).cwiseAbs().maxCoeff(), 1e-4 * v.J.M0.norm());
  // First three modes (bending, torsion, bending): frequencies and participation factors.
  for (Eigen::Index k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.refmod.frequency_hz(k) / v.refmod.frequency_hz(k), 1.0, 0.02) << "mode " << k + 1;
    const Eigen::RowVector3d ts = s.Ct.M0.row(k), tv = v.Ct.M0.row(k), rs = s.Cr.M0.row(k), rv = v.Cr.M0.row(k);
    const double sign = ts.dot(tv) + rs.dot(rv) >= 0 ? 1 : -1;
    EXPECT_LT((sign * ts - tv).norm(), 0.02 * std::max(tv.norm(), 1e-3 * std::sqrt(v.refmod.mass))) << "Ct.M0 mode " << k + 1;
    EXPECT_LT((sign * rs - rv).norm(), 0.02 * std::max(rv.norm(), 1e-3 * std::sqrt(v.J.M0.trace()))) << "Cr.M0 mode " << k + 1;
  }
}
