// The connecting rod of Simeon's slider-crank as a user builds it: a 6 mm round steel rod of
// 0.3 m, meshed with beam elements and reduced by ffr-reduce with "stiffening": true, once as a
// Craig-Bampton body (pins A and B, frame at A) and once with free-free modes; run by the
// runtime over the first crank revolution (crank 0.15 m at 150 rad/s) and compared with the
// independent geometrically exact beam (reissner_beam.hpp) on the same time grid.
// Source of the mechanism: B. Simeon, "Computational Flexible Multibody Dynamics", Springer
// 2013 (and "Modelling a flexible slider crank mechanism by a mixed system of DAEs and PDEs",
// Math. Modelling of Systems 2 (1996) 1-18), with the rod of GitHub issue 37 of this project:
// its axial force reaches 10-30 % of the Euler load.
#include "crank_runs.hpp"
#include "support.hpp"

#include "ffr/formats/sid_io.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <sys/wait.h>

using namespace ffr::runtime;

namespace {

constexpr double kE = 2.0e11, kNu = 0.3, kRho = 7870, kD = 0.006, kL = 0.3, kOmega = 150;
constexpr double kArea = M_PI * kD * kD / 4, kI = M_PI * kD * kD * kD * kD / 64;
constexpr double kRodMass = kRho * kArea * kL;

int run(const std::string& cmd, std::string* out) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), p)) *out += buf.data();
  const int st = pclose(p);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// The rod reduced by ffr-reduce into dir/<name>.sid.h5.
std::string reduce_rod(const test::TempDir& dir, const std::string& name, const std::string& reduction) {
  test::write_text(dir / "rod.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.3, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("rod") = {1}; Physical Point("A") = {1}; Physical Point("B") = {2};
)");
  char part[2048];
  std::snprintf(part, sizeof part, R"({"geometry": "rod.geo", "mesh": {"order": 1},
  "beams": [{"group": "rod", "E": %.17g, "nu": %.17g, "rho": %.17g, "y_axis": [0, 1, 0],
             "section": {"A": %.17g, "Iy": %.17g, "Iz": %.17g, "J": %.17g}}],
  "interfaces": [{"name": "A", "group": "A"}, {"name": "B", "group": "B"}],
  "output_nodes": [{"name": "mid", "at": [0.15, 0, 0]}],
  "reduction": %s,
  "stiffening": true, "visual": false})",
                kE, kNu, kRho, kArea, kI, kI, 2 * kI, reduction.c_str());
  test::write_text(dir / (name + ".json"), part);
  std::string out;
  const int st = run(std::string(FFR_BINARY_DIR) + "/bin/ffr-reduce " + (dir / (name + ".json")).string() + " -o " +
                         (dir / (name + ".sid.h5")).string() + " --quiet",
                     &out);
  if (st != 0) throw std::runtime_error("ffr-reduce failed: " + out);
  return name + ".sid.h5";
}

test::ReissnerBeam round_rod(int n) {
  test::ReissnerBeam b;
  b.EA = kE * kArea;
  b.GA = 100 * b.EA;  // the reducer's beams are shear-rigid without shear factors
  b.EI = kE * kI;
  b.rhoA = kRho * kArea;
  b.rhoI = kRho * kI;
  b.L = kL;
  b.n = n;
  return b;
}

void compare(const std::string& label, const test::TempDir& dir, const std::string& sid, double tolerance) {
  const double h = 1e-5, end = 2 * M_PI / kOmega;
  const bool has_m1 = !ffr::formats::read_sid(dir / sid).KeM1.empty();
  for (const double ms : {kRodMass / 2, 1e-3 * kRodMass}) {
    const test::CrankTrace ref = test::oracle_crank(round_rod(40), ms, h, end);
    test::CrankTrace on, off;
    std::string failure;
    try {
      on = test::runtime_crank(dir.path, sid, ms, true, h, end);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    off = test::runtime_crank(dir.path, sid, ms, false, h, end);
    const double e_on = failure.empty() ? test::worst_relative(on, ref) : NAN;
    std::printf("%s (Ke/M1 %s), slider %.4g kg: oracle peak %.4e m; runtime stiffened peak %.4e (worst difference "
                "%.2f %% of the peak)%s%s; unstiffened peak %.4e (%.2f %%)\n",
                label.c_str(), has_m1 ? "present" : "absent", ms, ref.peak(), failure.empty() ? on.peak() : NAN,
                100 * e_on, failure.empty() ? "" : " FAILED: ", failure.c_str(), off.peak(),
                100 * test::worst_relative(off, ref));
    EXPECT_TRUE(failure.empty()) << failure;
    EXPECT_LT(e_on, tolerance) << label << ", slider " << ms << " kg";
  }
}

}  // namespace

TEST(StiffeningRod, CraigBamptonRodMatchesTheGeometricallyExactBeam) {
  test::TempDir dir("rod_cb");
  const std::string sid =
      reduce_rod(dir, "cb", R"({"method": "craig-bampton", "interfaces": ["A", "B"], "frame": "A", "modes": 6})");
  compare("Craig-Bampton", dir, sid, 0.05);
}

TEST(StiffeningRod, FreeFreeRodMatchesTheGeometricallyExactBeam) {
  test::TempDir dir("rod_free");
  const std::string sid = reduce_rod(dir, "free", R"({"method": "free", "modes": 8})");
  compare("free-free", dir, sid, 0.05);
}
