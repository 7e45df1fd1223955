// A free flexible body spinning and vibrating without gravity.
//
// Linear and angular momentum are computed from the invariants (energy.hpp). The continuous
// equations conserve them and the energy; the trapezoidal ALI3-P scheme does so up to its
// second-order error on a nonlinear system (it is not a momentum-conserving scheme: the
// constraint forces enter at t_n+1 only), so the checks are: the drift falls as h^2 (which an
// error in any inertia term would break: it would not vanish with h), and, for a body about its
// mean axes, where the frame origin's equation decouples (md = 0, Pdm = 0), the linear momentum
// m r0_dot stays constant to round-off.
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace ffr::runtime;

namespace {

std::string free_body(double step, int nq) {
  std::string y = nq == 3 ? "[0.01, -0.02, 0.005]" : "[0.01, -0.02, 0.005, 0.01]";
  std::string yd = nq == 3 ? "[0.5, 0.3, -0.4]" : "[0.5, 0.3, -0.4, 0.2]";
  return R"({
  "bodies": [{"name": "flex", "type": "flexible", "sid": "body.sid.h5", "position": [0.1, -0.2, 0.3],
              "velocity": [0.3, -0.1, 0.2], "angular_velocity": [2.0, -3.0, 5.0],
              "modal_coordinates": )" + y + R"(, "modal_velocities": )" + yd + R"(}],
  "solver": {"end": 1.0, "step": )" + std::to_string(step) + R"(}
})";
}

struct Drift {
  double p = 0, H = 0, E = 0;
};

Drift run(const ffr::formats::Sid& sid, double h, double duration) {
  test::TempDir dir("mom");
  test::write_sid_file(sid, dir / "body.sid.h5");
  const Model model = test::model_from(free_body(h, static_cast<int>(sid.nq())), dir.path);
  Data data(model);
  initialize(model, data);
  const Vector3d p0 = linear_momentum(model, data), H0 = angular_momentum(model, data);
  const double E0 = energy(model, data).total();
  Drift d;
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int i = 0; i < steps; ++i) {
    step(model, data);
    d.p = std::max(d.p, (linear_momentum(model, data) - p0).norm() / p0.norm());
    d.H = std::max(d.H, (angular_momentum(model, data) - H0).norm() / H0.norm());
    d.E = std::max(d.E, std::abs(energy(model, data).total() - E0) / E0);
  }
  return d;
}

}  // namespace

TEST(FreeFlexibleBody, MeanAxesLinearMomentumToRoundOff) {
  const Drift d = run(test::mean_axis_body(3), 1e-3, 1.0);
  std::printf("mean axes, h = 1e-3, 1 s: dp %.2e dH %.2e dE %.2e\n", d.p, d.H, d.E);
  EXPECT_LT(d.p, 1e-10);  // round-off: eight orders below the O(h^2) drift of the general case
}

TEST(FreeFlexibleBody, MomentaAndEnergyDriftAreSecondOrder) {
  const auto sid = test::lumpy_body(3, 11, true, 0.0);  // frame not on mean axes: all couplings
  const Drift a = run(sid, 1e-3, 1.0), b = run(sid, 5e-4, 1.0);
  std::printf("h = 1e-3: dp %.2e dH %.2e dE %.2e\nh = 5e-4: dp %.2e dH %.2e dE %.2e\n", a.p, a.H, a.E, b.p, b.H, b.E);
  // Second order: halving the step divides the drift by ~4.
  EXPECT_GT(a.p / b.p, 3.5);
  EXPECT_LT(a.p / b.p, 4.5);
  EXPECT_GT(a.H / b.H, 3.5);
  EXPECT_LT(a.H / b.H, 4.5);
  EXPECT_GT(a.E / b.E, 3.0);
  EXPECT_LT(a.E / b.E, 5.0);
  EXPECT_LT(a.H, 5e-4);
  EXPECT_LT(a.E, 5e-4);
}
