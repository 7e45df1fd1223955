#pragma once
// Models of relative_assembly_test.cpp and relative_allocation_test.cpp: bodies placed at a
// joint's point by the relative formulation (FORMULATION.md 18, "placed at a point").
#include "formulation_models.hpp"  // tools/bench/formulations: num

#include <string>

namespace relative_assembly {

using formulations::num;

/// A 3-D spherical double pendulum: two bars of unequal principal inertias, spherical joints
/// ground-bar1 at the origin and bar1-bar2 at (0.4, 0, 0), started horizontal and spinning about
/// tilted axes so that the motion leaves every plane. `universal`: the elbow a universal joint
/// (axis1 z on bar1, axis2 y on bar2) instead.
inline std::string spherical_double_pendulum_json(double h, double end, const std::string& formulation, bool universal = false) {
  return R"({"gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "bar1", "type": "rigid", "mass": 1.0, "com": [0.2, 0, 0], "position": [0, 0, 0],
     "inertia": [[2e-3, 0, 0], [0, 1.4e-2, 0], [0, 0, 1.5e-2]], "angular_velocity": [1.0, 0.5, 3.0]},
    {"name": "bar2", "type": "rigid", "mass": 0.7, "com": [0.6, 0, 0], "position": [0.4, 0, 0],
     "inertia": [[1e-3, 0, 0], [0, 8e-3, 0], [0, 0, 8.5e-3]], "angular_velocity": [-2.0, 1.0, 1.0]}],
  "joints": [
    {"name": "shoulder", "type": "spherical", "body1": "ground", "body2": "bar1", "at": [0, 0, 0]},
    {"name": "elbow", "type": )" + std::string(universal ? R"("universal", "axis1": [0, 0, 1], "axis2": [0, 1, 0])" : R"("spherical")") +
         R"(, "body1": "bar1", "body2": "bar2", "at": [0.4, 0, 0]}],
  "solver": {"formulation": ")" + formulation + R"(", "end": )" + num(end) + R"(, "step": )" + num(h) + R"(},
  "outputs": [{"name": "tip", "type": "node_position", "body": "bar2", "at": [0.8, 0, 0]}]})";
}

/// A cantilever (ANCF or geometrically exact beam, 1 m, 16 elements, steel 10 mm square) clamped
/// at its start with a 0.5 kg bob hung on its end node by a spherical joint "hang"; a torsion
/// spring about z (a bushing) holds the bob's free spin about the vertical. `solver` is the
/// solver object's text.
inline std::string hung_bob_json(const std::string& beam_formulation, const std::string& solver, bool bob = true) {
  std::string beam = R"({"name": "beam", "type": "beam", "formulation": ")" + beam_formulation +
                     R"(", "start": [0, 0, 0], "end": [1, 0, 0], "elements": 16, "E": 2.1e11, "rho": 7850,
      "section": {"A": 1e-4, "Iy": 8.333333333333334e-10, "Iz": 8.333333333333334e-10)";
  if (beam_formulation == "geometrically_exact") beam += R"(, "J": 1.4e-9}, "nu": 0.3)";
  else beam += "}";
  beam += R"(, "damping": {"strain_rate": 2e-3}})";
  const std::string tail = R"(, "solver": )" + solver + R"(,
    "outputs": [{"name": "tip", "type": "node_position", "body": "beam", "node": "end"}]})";
  if (!bob)
    return R"({"gravity": [0, 0, -9.81], "bodies": [)" + beam + R"(],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "beam", "node2": "start"}],
    "forces": [{"name": "W", "type": "point_force", "body": "beam", "node": "end",
                "table": {"t": [0, 100], "value": [[0, 0, -4.905], [0, 0, -4.905]]}}])" + tail;
  return R"({"gravity": [0, 0, -9.81], "bodies": [)" + beam + R"(,
      {"name": "bob", "type": "rigid", "mass": 0.5, "com": [1, 0, -0.1], "inertia": [[1e-4, 0, 0], [0, 1e-4, 0], [0, 0, 1e-4]]}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "beam", "node2": "start"},
               {"name": "hang", "type": "spherical", "body1": "beam", "node1": "end", "body2": "bob"}],
    "forces": [{"name": "spin", "type": "bushing", "body1": "ground", "body2": "bob", "at": [1, 0, -0.1],
                "stiffness": [0, 0, 0, 0, 0, 1]}])" + tail;
}

/// hung_bob_json's geometrically exact cantilever with the 0.5 kg body welded (a fixed joint
/// "weld") to its end node, its centre of mass at the node.
inline std::string welded_bob_json(const std::string& solver) {
  std::string json = hung_bob_json("geometrically_exact", solver);
  const auto replace = [&](const std::string& from, const std::string& to) { json.replace(json.find(from), from.size(), to); };
  replace(R"("com": [1, 0, -0.1])", R"("com": [1, 0, 0])");
  replace(R"({"name": "hang", "type": "spherical")", R"({"name": "weld", "type": "fixed")");
  replace(R"(,
    "forces": [{"name": "spin", "type": "bushing", "body1": "ground", "body2": "bob", "at": [1, 0, -0.1],
                "stiffness": [0, 0, 0, 0, 0, 1]}])", "");
  return json;
}

/// A clamped square steel plate (1 m, 10 mm, 4 x 4 elements) with a 50 kg bob hung on its centre
/// node n2_2 by a spherical joint "hang" (or, without the bob, its weight as a point force there).
inline std::string plate_bob_json(const std::string& solver, bool bob = true) {
  const std::string plate = R"({"name": "plate", "type": "plate", "corners": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
      "elements": [4, 4], "thickness": 0.01, "E": 2.1e11, "nu": 0.3, "rho": 7850, "damping": {"strain_rate": 1e-3},
      "supports": {"x0": "clamped", "x1": "clamped", "y0": "clamped", "y1": "clamped"}})";
  const std::string tail = R"(, "solver": )" + solver + R"(,
    "outputs": [{"name": "tip", "type": "node_position", "body": "plate", "node": "n2_2"}]})";
  if (!bob)
    return R"({"gravity": [0, 0, -9.81], "bodies": [)" + plate + R"(],
    "forces": [{"name": "W", "type": "point_force", "body": "plate", "node": "n2_2",
                "table": {"t": [0, 100], "value": [[0, 0, -490.5], [0, 0, -490.5]]}}])" + tail;
  return R"({"gravity": [0, 0, -9.81], "bodies": [)" + plate + R"(,
      {"name": "bob", "type": "rigid", "mass": 50, "com": [0.5, 0.5, -0.1], "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}],
    "joints": [{"name": "hang", "type": "spherical", "body1": "plate", "node1": "n2_2", "body2": "bob"}],
    "forces": [{"name": "spin", "type": "bushing", "body1": "ground", "body2": "bob", "at": [0.5, 0.5, -0.1],
                "stiffness": [0, 0, 0, 0, 0, 1]}])" + tail;
}

}  // namespace relative_assembly
