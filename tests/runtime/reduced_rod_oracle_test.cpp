// Simeon's slider-crank with its connecting rod reduced by ffr-reduce from beam elements (the
// part file of preproc/PART_FILE.md, run through the reducer's own pipeline), run by the
// runtime, against the independent geometrically exact beam of reissner_beam.hpp over the first
// crank revolution: the rod midpoint's deflection from the chord AB.
//
// Sources: the mechanism of B. Simeon, "Computational Flexible Multibody Dynamics", Springer 2013
// (crank 0.15 m at 150 rad/s, rod 0.3 m, slider on the crank's axis), here with the 6 mm round
// steel rod of GitHub issue 37 (E = 200 GPa, rho = 7870 kg/m^3: 0.0668 kg, Euler load 1.4 kN, its
// axial force reaching 10-30 % of it); the oracle is the planar Reissner/Simo beam (E. Reissner,
// ZAMP 23 (1972); J. C. Simo, L. Vu-Quoc, J. Appl. Mech. 53 (1986)) written in the tests.
#include "crank_runs.hpp"
#include "reissner_beam.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/preproc/pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>

using namespace ffr::runtime;

namespace {

constexpr double kE = 2.0e11, kRho = 7870, kD = 0.006, kL = 0.3;
const double kA = M_PI * kD * kD / 4, kI = M_PI * std::pow(kD, 4) / 64, kMass = kRho * kA * kL;

// The rod as a part: 40 shear-rigid 2-node beam elements along x, interfaces A (x = 0) and
// B (x = L) on the end points, the midpoint as output node "M".
ffr::formats::Sid reduce_rod(const std::string& reduction) {
  test::TempDir dir("reduced_rod");
  test::write_text(dir / "rod.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.3, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("rod") = {1}; Physical Point("a") = {1}; Physical Point("b") = {2};
)");
  char json[2048];
  std::snprintf(json, sizeof json, R"({"geometry": "rod.geo", "mesh": {"order": 1},
  "beams": [{"group": "rod", "E": %.17g, "nu": 0.3, "rho": %.17g, "y_axis": [0, 1, 0],
             "section": {"A": %.17g, "Iy": %.17g, "Iz": %.17g, "J": %.17g}}],
  "interfaces": [{"name": "A", "group": "a"}, {"name": "B", "group": "b"}],
  "output_nodes": [{"name": "M", "at": [0.15, 0, 0]}],
  "reduction": %s,
  "stiffening": true, "visual": false})",
                kE, kRho, kA, kI, kI, 2 * kI, reduction.c_str());
  test::write_text(dir / "rod.json", json);
  return ffr::preproc::run_pipeline(ffr::preproc::load_part(dir / "rod.json"));
}

test::ReissnerBeam round_beam() {
  test::ReissnerBeam b;
  b.EA = kE * kA;
  b.GA = 100 * b.EA;  // shear-rigid in effect, as the reduced beam elements
  b.EI = kE * kI;
  b.rhoA = kRho * kA;
  b.rhoI = kRho * kI;
  b.L = kL;
  b.n = 40;
  return b;
}

struct Agreement {
  double with = 0, without = 0;
};

// Worst difference of the midpoint deflection over the first revolution, in percent of the
// oracle's peak, for each slider mass.
void compare(const ffr::formats::Sid& sid, const char* what, double h, double limit, std::initializer_list<double> sliders) {
  test::TempDir dir("reduced_rod_run");
  test::write_sid_file(sid, dir / "rod.sid.h5");
  const double end = std::round(2 * M_PI / 150.0 / h) * h;
  for (const double ms : sliders) {
    const test::CrankTrace ref = test::oracle_crank(round_beam(), ms, h, end);
    const test::CrankTrace on = test::runtime_crank(dir.path, "rod.sid.h5", ms, true, h, end);
    const test::CrankTrace off = test::runtime_crank(dir.path, "rod.sid.h5", ms, false, h, end);
    const double e_on = test::worst_relative(on, ref), e_off = test::worst_relative(off, ref);
    std::printf("%s, slider %.4g kg: oracle peak %.4e m; runtime stiffened %.4e (worst difference %.2f %% of the "
                "peak), unstiffened %.4e (%.2f %%)\n",
                what, ms, ref.peak(), on.peak(), 100 * e_on, off.peak(), 100 * e_off);
    EXPECT_LT(e_on, limit) << what << ", slider " << ms << " kg";
  }
}

}  // namespace

// Craig-Bampton with pins A and B, frame at A (12 modes: B's six constraint modes, six
// fixed-interface modes), its Ke/M1 and the inertial load cases with A and B held; the slider of
// half the rod's mass and a nearly massless one. (With the frame's own spin in the centrifugal
// cases instead of the body's mean spin, FORMULATION.md 7, the massless slider stalled Newton at
// t = 0.039 s: the frame at A turns with every bending vibration there.)
TEST(ReducedRodOracle, CraigBamptonRodSliderCrankMatchesTheGeometricallyExactBeam) {
  const ffr::formats::Sid sid =
      reduce_rod(R"({"method": "craig-bampton", "interfaces": ["A", "B"], "frame": "A", "modes": 6})");
  std::printf("Craig-Bampton rod: %lld modes, Ke/M1 %s\n", static_cast<long long>(sid.nq()), sid.KeM1.empty() ? "absent" : "present");
  compare(sid, "Craig-Bampton rod", 2e-5, 0.05, {kMass / 2, 1e-3 * kMass});
}

// Free-free modes (the lowest 16: seven bending pairs, torsion, the first axial mode), Ke/M1 and
// the interface-load members at A and B with the joints' loads; both slider masses.
TEST(ReducedRodOracle, FreeFreeRodSliderCrankMatchesTheGeometricallyExactBeam) {
  const ffr::formats::Sid sid = reduce_rod(R"({"method": "free", "modes": 16})");
  std::printf("free-free rod: %lld modes, Ke/M1 %s, %zu stiffening interfaces\n", static_cast<long long>(sid.nq()),
              sid.KeM1.empty() ? "absent" : "present", sid.stiffening ? sid.stiffening->interfaces.size() : 0u);
  compare(sid, "free-free rod", 2e-5, 0.05, {kMass / 2, 1e-3 * kMass});
}
