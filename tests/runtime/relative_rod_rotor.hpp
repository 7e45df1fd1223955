#pragma once
// A rotor in a bearing housing welded to the tip node of Simeon's rod (the IVP Test Set
// slider-crank's elastic rod): the relative formulation places the housing at the node's point
// and the rotor on the housing by its joint angle (FORMULATION.md 18). Used by the washing tests
// (against the absolute formulation) and the tangent tests.
#include "simeon_rod.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace ffr::runtime::test {

inline std::string rod_rotor_num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

// Simeon's rod with its tip node's small rotations: the lateral shapes sin(pi x / L) and
// sin(2 pi x / L) of the SID (simeon_rod.cpp: the node slices phi(1, 0), phi(1, 1)) turn the
// section at x = L about z by their slopes, pi / L cos(pi) and 2 pi / L cos(2 pi); the axial
// shapes turn nothing. Without them the housing would not follow the rod's bending.
inline ffr::formats::Sid rod_with_tip_rotations() {
  ffr::formats::Sid s = simeon_rod_sid();
  const double L = SimeonData::L2;
  auto& B = s.nodes[2];
  B.psi = Eigen::Matrix3Xd::Zero(3, 4);
  B.psi(2, 0) = M_PI / L * std::cos(M_PI);
  B.psi(2, 1) = 2 * M_PI / L * std::cos(2 * M_PI);
  return s;
}

// The rod (hinged about z at its frame origin, along x, in gravity -y), a 20 g housing welded to
// its tip node B, and a 50 g rotor turning in the housing about the rod's axis x, its centre of
// mass 2 mm off the axis (an unbalance whose centrifugal force bends the rod), driven by a speed
// ramp to `speed` rad/s over `ramp` s, then held to `end`.
inline std::string rod_rotor_json(double h, const char* formulation, double speed = 400, double ramp = 0.2, double end = 0.2) {
  const double L = SimeonData::L2;
  const std::string tip = "[" + rod_rotor_num(L) + ", 0, 0]";
  return std::string(R"({"gravity": [0, -9.81, 0],
    "bodies": [{"name": "rod", "type": "flexible", "sid": "rod.sid.h5"},
      {"name": "housing", "type": "rigid", "mass": 0.02, "com": )") + tip + R"(, "inertia": [[2e-6, 0, 0], [0, 1.2e-6, 0], [0, 0, 1.2e-6]]},
      {"name": "rotor", "type": "rigid", "mass": 0.05, "com": [)" + rod_rotor_num(L + 0.01) + R"(, 0.002, 0], "inertia": [[1e-5, 0, 0], [0, 6e-6, 0], [0, 0, 6e-6]]}],
    "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "rod", "at": [0, 0, 0], "axis": [0, 0, 1]},
               {"name": "mount", "type": "fixed", "body1": "rod", "node1": "B", "body2": "housing"},
               {"name": "shaft", "type": "revolute", "body1": "housing", "body2": "rotor", "at": )" + tip + R"(, "axis": [1, 0, 0]}],
    "motions": [{"joint": "shaft", "speed": {"t": [0, )" + rod_rotor_num(ramp) + ", " + rod_rotor_num(std::max(end, ramp) + 1) + R"(], "value": [0, )" + rod_rotor_num(speed) + ", " + rod_rotor_num(speed) + R"(], "interpolation": "linear"}}],
    "solver": {"formulation": ")" + formulation + R"(", "end": )" + rod_rotor_num(end) + R"(, "step": )" + rod_rotor_num(h) + R"(},
    "outputs": [{"name": "tip", "type": "node_position", "body": "rod", "node": "B"},
                {"name": "mass", "type": "node_position", "body": "rotor", "at": [)" + rod_rotor_num(L + 0.01) + R"(, 0.002, 0]}]})";
}

}  // namespace ffr::runtime::test
