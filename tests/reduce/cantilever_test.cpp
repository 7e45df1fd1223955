// A slender solid cantilever (TET10) against Euler–Bernoulli beam theory.
//
// References (nobody here computed them):
//  - clamped-free beam eigenvalues beta_n L = 1.87510407, 4.69409113, 7.85475744 and
//    f_n = (beta_n L)^2 / (2 pi L^2) sqrt(EI / (rho A)): R. D. Blevins, "Formulas for Natural
//    Frequency and Mode Shape" (1979), Table 8-1, case "clamped-free".
//  - effective modal mass fractions of the first three bending modes of a uniform
//    cantilever, 0.6131, 0.1883, 0.0647 of the total mass: e.g. A. K. Chopra, "Dynamics of
//    Structures", 4th ed., Sec. 16.8 (cantilever tower, effective modal masses).
// At L/h = 100 shear deformation and rotary inertia change the third frequency by ~0.2 %
// (Timoshenko), below the 1 % tolerance of the issue.
#include "ffr/preproc/pipeline.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ffr;

namespace {

constexpr double L = 1.0, b = 0.015, h = 0.01, E = 7.0e10, nu = 0.3, rho = 2700.0;

formats::Sid reduce_cantilever(const test::TempDir& dir) {
  test::write_text(dir / "beam.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.0, 0.015, 0.01};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
  test::write_text(dir / "beam.json", R"({
    "geometry": "beam.geo", "mesh": {"size": 0.005, "order": 2},
    "materials": [{"group": "body", "E": 7.0e10, "nu": 0.3, "rho": 2700}],
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 8}})");
  return preproc::run_pipeline(preproc::load_part(dir / "beam.json"));
}

}  // namespace

TEST(Cantilever, BendingFrequenciesAndEffectiveMassesMatchEulerBernoulli) {
  test::TempDir dir("cantilever");
  const formats::Sid sid = reduce_cantilever(dir);
  const double m = rho * L * b * h;
  EXPECT_NEAR(sid.refmod.mass, m, 1e-9 * m);

  // Bending in z (about y): I = b h^3 / 12. Pick the modes whose z participation dominates.
  const double I = b * h * h * h / 12, A = b * h;
  const double betaL[3] = {1.87510407, 4.69409113, 7.85475744};
  const double fraction[3] = {0.6131, 0.1883, 0.0647};
  int found = 0;
  for (Eigen::Index k = 0; k < sid.nq() && found < 3; ++k) {
    const Eigen::RowVector3d g = sid.Ct.M0.row(k);  // participation factors (mass-normalised modes)
    if (std::abs(g.z()) < 0.9 * g.norm()) continue;
    const double f_ref = betaL[found] * betaL[found] / (2 * M_PI * L * L) * std::sqrt(E * I / (rho * A));
    const double f = sid.refmod.frequency_hz(k);
    EXPECT_NEAR(f / f_ref, 1.0, 0.01) << "bending mode " << found + 1 << ": " << f << " Hz vs " << f_ref << " Hz";
    const double eff = g.z() * g.z() / m;
    EXPECT_NEAR(eff, fraction[found], 0.01 * fraction[found]) << "effective mass of bending mode " << found + 1;
    ++found;
  }
  EXPECT_EQ(found, 3) << "three z-bending modes among the first " << sid.nq();
}
