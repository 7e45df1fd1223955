// The shell obstacle course on structured meshes (problem definitions in obstacle_course.hpp).
// References:
//   Scordelis–Lo roof 0.3024 and pinched cylinder 1.8248e-5: Belytschko, Stolarski, Liu,
//     Carpenter & Ong, CMAME 51 (1985) 221–258 (deep-shell solutions).
//   Pinched hemisphere with an 18 deg hole 0.094 and twisted beam 5.424e-3 / 1.754e-3 (load along
//     the tip's width / thickness): MacNeal & Harder, Finite Elem. Anal. Des. 1 (1985) 3–20.
//     (0.0924 is Belytschko et al.'s value for the full hemisphere without a hole; the hole
//     variant modelled here converges to about 0.0935 with these elements, between the two.)
// Acceptance: within 2 % at 16 x 16 (quarter/octant models), the cylinder within 5 % at 32 x 32,
// the twisted beam within 2 % on MacNeal–Harder's 2 x 12 mesh.

#include "obstacle_course.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using ffr::preproc::ElementType;
using namespace ffr::test;

namespace {

void report(const char* what, ElementType t, const char* mesh, double value, double ref) {
  std::printf("  %-18s %-5s %-6s %.5e  ref %.5e  error %+6.2f %%\n", what, ffr::preproc::name(t), mesh, value, ref,
              100 * (value / ref - 1));
}

void expect_within(double value, double ref, double tol) { EXPECT_LT(std::abs(value / ref - 1), tol) << value; }

}  // namespace

class ObstacleCourse : public ::testing::TestWithParam<ElementType> {};

TEST_P(ObstacleCourse, ScordelisLoRoof) {
  const double v = scordelis_lo(16, GetParam());
  report("Scordelis-Lo", GetParam(), "16x16", v, 0.3024);
  expect_within(v, 0.3024, 0.02);
}

TEST_P(ObstacleCourse, PinchedCylinder) {
  const double v = pinched_cylinder(32, GetParam());
  report("pinched cylinder", GetParam(), "32x32", v, 1.8248e-5);
  expect_within(v, 1.8248e-5, 0.05);
}

TEST_P(ObstacleCourse, PinchedHemisphere) {
  // QUAD4 meets 2 % at 16 x 16; the OPT/DKT triangles need 32 x 32 (see the report below).
  const int n = GetParam() == ElementType::Quad4 ? 16 : 32;
  const double v = pinched_hemisphere(n, GetParam());
  report("hemisphere (hole)", GetParam(), n == 16 ? "16x16" : "32x32", v, 0.094);
  expect_within(v, 0.094, 0.02);
  if (GetParam() == ElementType::Tri3) report("hemisphere (hole)", GetParam(), "16x16", pinched_hemisphere(16, GetParam()), 0.094);
}

TEST_P(ObstacleCourse, TwistedBeam) {
  const double a = twisted_beam(2, 12, true, GetParam());
  const double b = twisted_beam(2, 12, false, GetParam());
  report("twisted (width)", GetParam(), "2x12", a, 5.424e-3);
  report("twisted (thick)", GetParam(), "2x12", b, 1.754e-3);
  expect_within(a, 5.424e-3, 0.02);
  expect_within(b, 1.754e-3, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Shells, ObstacleCourse, ::testing::Values(ElementType::Quad4, ElementType::Tri3),
                         [](const auto& info) { return std::string(ffr::preproc::name(info.param)); });
