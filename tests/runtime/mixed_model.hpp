#pragma once
// The runtime's "every kind of element" test model, shared by the allocation test and the
// tangent-blocks test: a driven crank, a flexible rod (rod.sid.h5: Simeon's rod with Ke/M1), a
// slider, a flexible flap (lumpy.sid.h5: every stiffening member, an interface at its hinge node
// A) on a spherical joint. Each test adds its own force elements and solver/outputs.
#include "simeon_rod.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <string>

namespace ffr::runtime::test {

// Every stiffening member (FORMULATION.md 7): the rod's Ke/M1, the flap's load cases with the
// interface loads at its hinge, prestress, and Ke/M1.
inline void write_mixed_sids(const TempDir& dir) {
  ffr::formats::Sid rod = simeon_rod_sid();
  rod.KeM1 = simeon_rod_ke_m1();
  write_sid_file(rod, dir / "rod.sid.h5");
  ffr::formats::Sid flap = lumpy_body(3, 4, true, 0.01);
  const double k = flap.Ke.cwiseAbs().maxCoeff();
  for (int m = 0; m < 3; ++m) flap.KeM1.push_back(0.1 * k * Eigen::Matrix3d::Identity() * (m + 1));
  flap.ksigma.M0 = Eigen::Vector3d(1e-3, 0, 0) * k;
  flap.ksigma.M1 = 0.01 * k * Eigen::Matrix3d::Identity();
  // Load cases of a realistic size (a unit acceleration changes the stiffness by 1e-5): they
  // are evaluated at the iterate's accelerations, which carry 4/h^2 times the predictor's error.
  flap.stiffening.emplace();
  flap.stiffening->K0t.assign(3, ffr::formats::MatX3::Constant(3, 3, 1e-5 * k));
  flap.stiffening->K0r.assign(3, ffr::formats::MatX3::Constant(3, 3, 1e-5 * k));
  flap.stiffening->K0om.assign(3, ffr::formats::MatX6::Constant(3, 6, 1e-5 * k));
  ffr::formats::Stiffening::Interface itf;
  itf.name = "A";
  itf.K0F.assign(3, ffr::formats::MatX3::Constant(3, 3, 1e-5 * k));
  itf.K0M.assign(3, ffr::formats::MatX3::Constant(3, 3, 1e-5 * k));
  flap.stiffening->interfaces.push_back(itf);
  write_sid_file(flap, dir / "lumpy.sid.h5");
}

// The model text: the bodies, joints and motion above, then `forces` (a JSON array) and `rest`
// (the remaining members, e.g. `"solver": {...}, "outputs": [...]`).
inline std::string mixed_model_json(const std::string& forces, const std::string& rest) {
  return R"({
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "crank", "type": "rigid", "mass": 0.36, "com": [0.075, 0, 0], "inertia": [[1e-6, 0, 0], [0, 7e-4, 0], [0, 0, 7e-4]]},
    {"name": "rod", "type": "flexible", "sid": "rod.sid.h5", "position": [0.15, 0, 0], "damping": {"ratio": 0.01}},
    {"name": "slider", "type": "rigid", "mass": 0.075, "com": [0.45, 0, 0], "inertia": [[1e-6, 0, 0], [0, 1e-6, 0], [0, 0, 1e-6]]},
    {"name": "flap", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0, 0.5, 0]}
  ],
  "joints": [
    {"name": "hub", "type": "revolute", "body1": "ground", "body2": "crank", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "pin", "type": "revolute", "body1": "crank", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "wrist", "type": "revolute", "body1": "rod", "body2": "slider", "node1": "B", "axis": [0, 0, 1]},
    {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "at": [0.45, 0, 0], "axis": [1, 0, 0]},
    {"name": "hinge", "type": "spherical", "body1": "ground", "body2": "flap", "node2": "A"}
  ],
  "motions": [{"joint": "hub", "table": {"t": [0, 0.1, 1], "value": [0, 1, 30]}}],
  "forces": )" + forces + ",\n  " + rest + "\n}";
}

}  // namespace ffr::runtime::test
