// NAFEMS FV12, free square plate (NAFEMS, "Selected Benchmarks for Natural Frequency
// Analysis", test FV12): 10 m x 10 m x 0.05 m, E = 200 GPa, nu = 0.3, rho = 8000 kg/m^3, no
// support. Target: six rigid-body modes, then 1.622, 2.360, 2.922, 4.190, 4.190, 7.356, 7.356,
// 7.668 Hz. Through the whole pipeline: a gmsh .geo, 32 x 32 QUAD4 shells, ffr-reduce's free
// reduction (which deflates exactly six rigid-body modes and refuses any further zero mode).
#include "ffr/preproc/pipeline.hpp"
#include "../reduce/support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

TEST(FV12, FreeSquarePlateOfShells) {
  test::TempDir dir("fv12");
  test::write_text(dir / "plate.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {10, 0, 0}; Point(3) = {10, 10, 0}; Point(4) = {0, 10, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 33; Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1};
)");
  test::write_text(dir / "plate.json", R"({"geometry": "plate.geo", "mesh": {"order": 1},
    "shells": [{"group": "plate", "thickness": 0.05, "E": 2.0e11, "nu": 0.3, "rho": 8000}],
    "reduction": {"method": "free", "modes": 8}, "visual": false})");
  const formats::Sid sid = preproc::run_pipeline(preproc::load_part(dir / "plate.json"));
  const double ref[8] = {1.622, 2.360, 2.922, 4.190, 4.190, 7.356, 7.356, 7.668};
  ASSERT_EQ(sid.nq(), 8);
  for (int k = 0; k < 8; ++k)
    EXPECT_NEAR(sid.refmod.frequency_hz(k) / ref[k], 1.0, 0.01) << "mode " << k + 1 << ": " << sid.refmod.frequency_hz(k);
  // The repeated pairs come out as pairs.
  EXPECT_NEAR(sid.refmod.frequency_hz(3) / sid.refmod.frequency_hz(4), 1.0, 1e-6);
  EXPECT_NEAR(sid.refmod.frequency_hz(5) / sid.refmod.frequency_hz(6), 1.0, 1e-6);
  // Mass with thickness: rho * 10 * 10 * 0.05.
  EXPECT_NEAR(sid.refmod.mass, 8000 * 10 * 10 * 0.05, 1e-9 * 40000);
  // Free-free modes carry no momentum (exact deflation of the six rigid-body modes).
  EXPECT_LT(sid.Ct.M0.cwiseAbs().maxCoeff(), 1e-8 * std::sqrt(sid.refmod.mass));
  EXPECT_LT(sid.Cr.M0.cwiseAbs().maxCoeff(), 1e-8 * std::sqrt(sid.J.M0.trace()));
}
