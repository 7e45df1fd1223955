#include "models.hpp"

#include "ffr/formats/sid_io.hpp"

#include <cstdio>
#include <random>

namespace bench {

ffr::formats::synthetic::ChainParams rod_params(int points, int modes) {
  ffr::formats::synthetic::ChainParams p;
  p.points = points;
  p.length = 0.3;
  p.mass = 7870.0 * 0.008 * 0.008 * 0.3;
  p.EA = 2.0e11 * 0.008 * 0.008;
  p.EIy = p.EIz = 2.0e11 * 0.008 * 0.008 * 0.008 * 0.008 / 12;
  p.clamped = false;
  p.modes = modes;
  return p;
}

void add_section_inertia(ffr::formats::Sid& sid, double b, double h) {
  const double m = sid.refmod.mass;
  sid.integrals.rrdm(1, 1) += m * h * h / 12;
  sid.integrals.rrdm(2, 2) += m * b * b / 12;
}

std::string slider_crank_json(const std::string& sid_file, double step, double end, double omega) {
  char buf[4096];
  std::snprintf(buf, sizeof buf, R"({
  "bodies": [
    {"name": "crank", "type": "rigid", "mass": 0.36, "com": [0.075, 0, 0],
     "inertia": [[1e-5, 0, 0], [0, 7.02e-4, 0], [0, 0, 7.02e-4]]},
    {"name": "rod", "type": "flexible", "sid": "%s", "position": [0.15, 0, 0], "velocity": [0, %.17g, 0],
     "angular_velocity": [0, 0, %.17g]},
    {"name": "slider", "type": "rigid", "mass": 0.075552, "com": [0.45, 0, 0],
     "inertia": [[1e-6, 0, 0], [0, 1e-6, 0], [0, 0, 1e-6]]}
  ],
  "joints": [
    {"name": "hub", "type": "revolute", "body1": "ground", "body2": "crank", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "pin", "type": "revolute", "body1": "crank", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "wrist", "type": "revolute", "body1": "rod", "body2": "slider", "node1": "B", "axis": [0, 0, 1]},
    {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "at": [0.45, 0, 0], "axis": [1, 0, 0]}
  ],
  "motions": [{"joint": "hub", "table": {"t": [0, 1], "value": [0, %.17g]}}],
  "solver": {"end": %.17g, "step": %.17g},
  "outputs": [{"name": "q", "type": "modal_coordinates", "body": "rod"}]
})",
                sid_file.c_str(), 0.15 * omega, -0.5 * omega, omega, end, step);
  return buf;
}

std::filesystem::path temp_dir(const std::string& tag) {
  std::random_device rd;
  auto p = std::filesystem::temp_directory_path() / ("ffr_bench_" + tag + "_" + std::to_string(rd()));
  std::filesystem::create_directories(p);
  return p;
}

}  // namespace bench
