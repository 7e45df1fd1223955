// Rigid compound pendulum released from 90 degrees: period against the exact large-amplitude
// period T = 4 K(k) / omega0, k = sin(theta0/2), omega0^2 = m g d / I_O (complete elliptic integral
// of the first kind; e.g. L. D. Landau & E. M. Lifshitz, Mechanics, section 11, problem 1, or any
// text on the simple pendulum); energy drift over 1e5 steps.
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

// The compound pendulum of support.hpp, released horizontally.
const std::string kPendulum = test::compound_pendulum_json(R"({"end": 1.0, "step": 1e-3})");

}  // namespace

TEST(RigidPendulum, LargeAmplitudePeriodMatchesEllipticIntegral) {
  const Model model = test::model_from(kPendulum);
  Data data(model);
  initialize(model, data);
  const double m = 1.0, d = 0.5, g = 9.81, IO = 0.08336666666666667 + m * d * d;
  const double theta0 = M_PI / 2;
  const double T_exact = 4.0 * std::comp_ellint_1(std::sin(theta0 / 2)) / std::sqrt(m * g * d / IO);

  // The bar swings down (angle about +y goes positive when x tips down: -z); it passes the bottom
  // (angle = +pi/2) every half period. Record the crossing times with linear interpolation.
  std::vector<double> crossings;
  double prev = joint_coordinate(model, data, 0, JointCoordinate::Angle), tprev = data.state.t;
  double worst_violation = 0;
  while (crossings.size() < 21) {
    step(model, data);
    worst_violation = std::max(worst_violation, data.stats.last_violation);
    const double a = joint_coordinate(model, data, 0, JointCoordinate::Angle);
    const double bottom = theta0;
    if ((prev - bottom) * (a - bottom) < 0) crossings.push_back(tprev + (bottom - prev) / (a - prev) * (data.state.t - tprev));
    prev = a;
    tprev = data.state.t;
    ASSERT_LT(data.state.t, 60.0);
  }
  const double T = (crossings.back() - crossings.front()) / 10.0;
  EXPECT_NEAR(T / T_exact - 1.0, 0.0, 2e-5) << "T = " << T << " exact " << T_exact;
  EXPECT_LT(worst_violation, 1e-10);
}

TEST(RigidPendulum, EnergyDriftBoundedOver1e5Steps) {
  const Model model = test::model_from(kPendulum);
  Data data(model);
  initialize(model, data);
  const double E0 = energy(model, data).total();
  const double scale = 1.0 * 9.81 * 0.5;  // m g d: the swing's energy scale
  double worst = 0, worst_first_half = 0;
  for (int i = 1; i <= 100000; ++i) {
    step(model, data);
    if (i % 100 == 0) {
      const double dE = std::abs(energy(model, data).total() - E0) / scale;
      worst = std::max(worst, dE);
      if (i <= 50000) worst_first_half = std::max(worst_first_half, dE);
    }
  }
  RecordProperty("energy_drift", std::to_string(worst));
  EXPECT_LT(worst, 1e-4);
  // Bounded, not growing: the second half adds little to the first half's excursion.
  EXPECT_LT(worst, 2 * worst_first_half + 1e-9);
}
