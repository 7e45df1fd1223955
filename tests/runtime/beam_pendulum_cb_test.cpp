// The flexible pendulum at small deflection: the ANCF beam (FORMULATION.md 15) against a chain of
// Craig-Bampton bodies, the classical floating-frame model of the same beam, which nobody here
// wrote for this comparison: four segments, each a part of shear-rigid 2-node beam elements
// reduced by ffr-reduce's own pipeline (Craig-Bampton with interfaces A and B, frame at A, six
// fixed-interface modes; R. R. Craig & M. C. C. Bampton, "Coupling of substructures for dynamic
// analyses", AIAA J. 6 (1968)), joined end to end by fixed joints and run as flexible bodies
// (FORMULATION.md 2-9). At small elastic deflection (here under 1 % of the length) the two
// models describe the same Euler-Bernoulli beam, so they must agree where the deflection is
// resolved: the tip's path and the midpoint's bending deflection from the chord pin-tip.
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/preproc/pipeline.hpp"
#include "ffr/runtime/dynamics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

// A 1 m beam of 10 x 10 mm, E = 21 GPa: under its own weight while swinging it bends by a few
// millimetres (its first pinned-free bending frequency 73 rad/s, far above the swing's 3 rad/s).
constexpr double kL = 1.0, kSide = 0.01, kE = 2.1e10, kRho = 7850;
constexpr double kA = kSide * kSide, kI = kSide * kSide * kSide * kSide / 12;
constexpr int kSegments = 4;

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// One segment (L / 4 along x, 10 beam elements), interfaces A (x = 0) and B (x = L / 4).
ffr::formats::Sid reduce_segment() {
  test::TempDir dir("pendulum_segment");
  const double l = kL / kSegments;
  test::write_text(dir / "seg.geo", "Point(1) = {0, 0, 0}; Point(2) = {" + num(l) + R"(, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 11; Physical Curve("seg") = {1}; Physical Point("a") = {1}; Physical Point("b") = {2};
)");
  test::write_text(dir / "seg.json", R"({"geometry": "seg.geo", "mesh": {"order": 1},
  "beams": [{"group": "seg", "E": )" + num(kE) + R"(, "nu": 0.3, "rho": )" + num(kRho) + R"(, "y_axis": [0, 1, 0],
             "section": {"A": )" + num(kA) + R"(, "Iy": )" + num(kI) + R"(, "Iz": )" + num(kI) + R"(, "J": )" + num(2 * kI) + R"(}}],
  "interfaces": [{"name": "A", "group": "a"}, {"name": "B", "group": "b"}],
  "reduction": {"method": "craig-bampton", "interfaces": ["A", "B"], "frame": "A", "modes": 6},
  "stiffening": true, "visual": false})");
  return ffr::preproc::run_pipeline(ffr::preproc::load_part(dir / "seg.json"));
}

struct Trace {
  std::vector<double> tx, tz, d;  // tip x, z; midpoint's deflection from the chord pin-tip
  double peak() const {
    double p = 0;
    for (const double v : d) p = std::max(p, std::abs(v));
    return p;
  }
};

// Deflection of m from the chord a-b in the x-z plane (positive to the chord's left).
double chord_deflection(const std::vector<double>& a, const std::vector<double>& m, const std::vector<double>& b) {
  const Eigen::Vector2d pa(a[0], a[2]), pm(m[0], m[2]), pb(b[0], b[2]);
  const Eigen::Vector2d c = (pb - pa).normalized(), rel = pm - 0.5 * (pa + pb);
  return c.x() * rel.y() - c.y() * rel.x();
}

Trace run(const Model& m, double end) {
  Data d(m);
  initialize(m, d);
  Trace t;
  while (d.state.t < end - 1e-9) {
    step(m, d);
    const auto pin = test::output(m, d, "pin"), mid = test::output(m, d, "mid"), tip = test::output(m, d, "tip");
    t.tx.push_back(tip[0]);
    t.tz.push_back(tip[2]);
    t.d.push_back(chord_deflection(pin, mid, tip));
  }
  return t;
}

}  // namespace

// Released horizontal from rest under gravity, 1 s at h = 1 ms (down through the lowest point and
// up the other side): the ANCF beam of 16 elements against the four Craig-Bampton segments.
// Bounds: the tips within 2e-4 L of each other, the midpoint's chord deflection within 2 % of
// its peak (room for both models' discretisation errors of the bending: 16 cubic elements
// against 4 x 6 fixed-interface modes; measured 4.4e-5 L and 0.45 %).
TEST(BeamPendulumCraigBampton, SmallDeflectionPendulumMatchesAChainOfCraigBamptonBodies) {
  test::TempDir dir("pendulum_chain");
  test::write_sid_file(reduce_segment(), dir / "seg.sid.h5");
  const double h = 1e-3, end = 1.0;
  const std::string solver = R"("solver": {"end": )" + num(end) + R"(, "step": )" + num(h) + "}";

  std::string bodies, joints = R"({"name": "pin", "type": "revolute", "body1": "ground", "body2": "s0", "node2": "A", "axis": [0, 1, 0]})";
  for (int s = 0; s < kSegments; ++s) {
    bodies += std::string(s ? ", " : "") + R"({"name": "s)" + std::to_string(s) + R"(", "type": "flexible", "sid": "seg.sid.h5", "stiffening": true, "position": [)" +
              num(kL * s / kSegments) + ", 0, 0]}";
    if (s)
      joints += R"(, {"name": "weld)" + std::to_string(s) + R"(", "type": "fixed", "body1": "s)" + std::to_string(s - 1) +
                R"(", "node1": "B", "body2": "s)" + std::to_string(s) + R"(", "node2": "A"})";
  }
  const Model chain = test::model_from(R"({"gravity": [0, 0, -9.81], "bodies": [)" + bodies + R"(], "joints": [)" + joints + "], " +
                                           solver + R"(,
    "outputs": [{"name": "pin", "type": "node_position", "body": "s0", "node": "A"},
                {"name": "mid", "type": "node_position", "body": "s1", "node": "B"},
                {"name": "tip", "type": "node_position", "body": "s3", "node": "B"}]})",
                                       dir.path);
  const Model ancf = test::model_from(R"({"gravity": [0, 0, -9.81],
    "bodies": [{"name": "beam", "type": "beam", "formulation": "ancf", "start": [0, 0, 0], "end": [1, 0, 0], "elements": 16,
                "E": )" + num(kE) + R"(, "rho": )" + num(kRho) + R"(, "section": {"A": )" + num(kA) + R"(, "Iy": )" + num(kI) +
                                      R"(, "Iz": )" + num(kI) + R"(}}],
    "joints": [{"name": "pin", "type": "spherical", "body1": "ground", "body2": "beam", "node2": "start"}], )" + solver + R"(,
    "outputs": [{"name": "pin", "type": "node_position", "body": "beam", "node": "start"},
                {"name": "mid", "type": "node_position", "body": "beam", "node": "n8"},
                {"name": "tip", "type": "node_position", "body": "beam", "node": "end"}]})");
  const Trace a = run(ancf, end), c = run(chain, end);
  ASSERT_EQ(a.d.size(), c.d.size());
  double tip = 0, def = 0, lowest = 0;
  for (std::size_t i = 0; i < a.d.size(); ++i) {
    tip = std::max(tip, std::hypot(a.tx[i] - c.tx[i], a.tz[i] - c.tz[i]));
    def = std::max(def, std::abs(a.d[i] - c.d[i]));
    lowest = std::min(lowest, a.tz[i]);
  }
  std::printf("small-deflection pendulum over %.1f s: lowest tip z %.4f m; tips apart by at most %.3e m; chord deflection "
              "peak %.4e m (ancf) %.4e m (Craig-Bampton chain), worst difference %.3e m (%.2f %% of the peak)\n",
              end, lowest, tip, a.peak(), c.peak(), def, 100 * def / a.peak());
  EXPECT_LT(lowest, -0.9 * kL);          // it swung through the bottom
  EXPECT_LT(a.peak(), 1e-2 * kL);        // small deflection
  EXPECT_GT(a.peak(), 1e-3 * kL);        // but a resolved one
  EXPECT_LT(tip, 2e-4 * kL);
  EXPECT_LT(def, 2e-2 * a.peak());
}
