#pragma once
// Simeon's slider-crank (B. Simeon, "Computational Flexible Multibody Dynamics", Springer 2013;
// crank 0.15 m turning at 150 rad/s from the outer dead centre, rod 0.3 m, slider on the x axis)
// run two ways over the same time grid: by the Reissner-beam oracle (reissner_beam.hpp) and by
// the runtime with the rod as a flexible body from a SID. The quantity compared is the rod
// midpoint's deflection from the chord AB.
#include "reissner_beam.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ffr::runtime::test {

struct CrankTrace {
  std::vector<double> t, d;  ///< time, midpoint deflection from the chord (to its left) [m]
  double peak() const;
};

/// The oracle: `beam` (its L the rod's length; x0, y0, phi0 are set here) with the crank pin A
/// prescribed on the circle, B held on the x axis carrying `slider_mass`; the rod starts straight
/// at the dead centre with the rigid mechanism's velocities.
CrankTrace oracle_crank(ReissnerBeam beam, double slider_mass, double h, double end);

/// The runtime: rigid crank driven at 150 rad/s, the rod from `sid_file` (in `dir`; nodes "A",
/// "B" and a midpoint node "M" or "mid"; frame at A, x along AB), rigid slider on a prismatic
/// guide; revolute joints about z. Same initial state as the oracle.
CrankTrace runtime_crank(const std::filesystem::path& dir, const std::string& sid_file, double slider_mass,
                         bool stiffening, double h, double end, double rod_length = 0.3);

/// Worst |a - ref| over the common steps, relative to ref's peak.
double worst_relative(const CrankTrace& a, const CrankTrace& ref);

}  // namespace ffr::runtime::test
