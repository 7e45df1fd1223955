// The power-series reference itself against published values (so the FE tests compare with
// something that was checked against the literature, not only against itself).
#include "beam_series.hpp"

#include <gtest/gtest.h>

using namespace ffr::test;

TEST(BeamSeries, NonRotatingCantileverMatchesBlevins) {
  // beta L = 1.87510407, 4.69409113, 7.85475744 -> omega_bar = (beta L)^2 (Blevins 1979, Table 8-1).
  const auto w = cantilever_frequencies({}, 3);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_NEAR(w[0], 1.87510407 * 1.87510407, 1e-6);
  EXPECT_NEAR(w[1], 4.69409113 * 4.69409113, 1e-5);
  EXPECT_NEAR(w[2], 7.85475744 * 7.85475744, 1e-5);
}

TEST(BeamSeries, RotatingCantileverMatchesPublishedTable) {
  // First flapwise frequency of a uniform rotating cantilever, hub radius 0:
  // Wright, Smith, Thresher & Wang, J. Appl. Mech. 49 (1982) 197-202, Table 1; the same values
  // in Hodges & Rutkowski, AIAA J. 19 (1981) 1459-1466.
  const double speed[] = {1, 2, 3, 4, 5, 6, 8, 10};
  const double first[] = {3.6816, 4.1373, 4.7973, 5.5850, 6.4495, 7.3604, 9.2568, 11.2023};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(cantilever_frequencies(rotating(speed[i]), 1)[0], first[i], 2e-4) << "speed " << speed[i];
  // Second flapwise at speed 10: 33.6404 (same tables).
  EXPECT_NEAR(cantilever_frequencies(rotating(10), 2)[1], 33.6404, 1e-3);
}

TEST(BeamSeries, SelfWeightBucklingIsGreenhills) {
  // A standing column buckles under its own weight at gamma = 7.837 (Greenhill 1881;
  // Timoshenko & Gere, Theory of Elastic Stability, 2nd ed., sec. 2.13): the first
  // frequency vanishes there.
  // Find the gamma at which lambda = 0 is a root of the free-end determinant.
  double lo = -7.0, hi = -8.5;
  const double d_lo = detail::free_end_det(self_weight(lo), 0.0);
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    if ((detail::free_end_det(self_weight(mid), 0.0) > 0) == (d_lo > 0)) lo = mid;
    else hi = mid;
  }
  EXPECT_NEAR(0.5 * (lo + hi), -7.837, 2e-3);
}
