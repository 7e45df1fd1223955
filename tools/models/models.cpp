#include "models.hpp"

#include "ffr/formats/sid_io.hpp"

#include <chrono>
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
  // The member built from rrdm follows (formats/SPEC.md section 8: J.M0 = tr(rrdm) I - rrdm + rotary.I), so
  // the SID stays consistent (the runtime reads rrdm; the SID's validation checks both).
  const auto& rr = sid.integrals.rrdm;
  sid.J.M0 = rr.trace() * Eigen::Matrix3d::Identity() - rr + sid.rotary.I;
}

namespace {

std::string numbers(const std::vector<double>& v) {
  std::string out;
  char buf[32];
  for (std::size_t i = 0; i < v.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%.17g", i ? ", " : "", v[i]);
    out += buf;
  }
  return out;
}

}  // namespace

std::string slider_crank_json(const SliderCrank& s) {
  std::string modal;
  if (!s.modal_coordinates.empty()) modal += ", \"modal_coordinates\": [" + numbers(s.modal_coordinates) + "]";
  if (!s.modal_velocities.empty()) modal += ", \"modal_velocities\": [" + numbers(s.modal_velocities) + "]";
  char penalty[64] = "";
  if (s.penalty > 0) std::snprintf(penalty, sizeof penalty, ", \"penalty\": %.17g", s.penalty);
  char buf[4096];
  std::snprintf(buf, sizeof buf, R"({
  "bodies": [
    {"name": "crank", "type": "rigid", "mass": %.17g, "com": [%.17g, 0, 0],
     "inertia": [[%.17g, 0, 0], [0, %.17g, 0], [0, 0, %.17g]]},
    {"name": "rod", "type": "flexible", "sid": "%s", "position": [%.17g, 0, 0], "velocity": [0, %.17g, 0],
     "angular_velocity": [0, 0, %.17g]%s},
    {"name": "slider", "type": "rigid", "mass": %.17g, "com": [%.17g, 0, 0],
     "inertia": [[1e-6, 0, 0], [0, 1e-6, 0], [0, 0, 1e-6]], "velocity": [%.17g, 0, 0]}
  ],
  "joints": [
    {"name": "hub", "type": "revolute", "body1": "ground", "body2": "crank", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "pin", "type": "revolute", "body1": "crank", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "wrist", "type": "revolute", "body1": "rod", "body2": "slider", "node1": "B", "axis": [0, 0, 1]},
    {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "at": [%.17g, 0, 0], "axis": [1, 0, 0]}
  ],
  "motions": [{"joint": "hub", "table": {"t": [0, 1], "value": [0, %.17g]}}],
  "solver": {"end": %.17g, "step": %.17g%s},
  "outputs": [{"name": "q", "type": "modal_coordinates", "body": "rod"}]
})",
                s.crank_mass, s.crank_com, s.crank_inertia(0), s.crank_inertia(1), s.crank_inertia(2), s.sid_file.c_str(),
                s.rod_x, s.rod_vy, s.rod_omega, modal.c_str(), s.slider_mass, s.slider_x, s.slider_vx, s.slider_x,
                s.omega, s.end, s.step, penalty);
  return buf;
}

std::string slider_crank_json(const std::string& sid_file, double step, double end, double omega) {
  SliderCrank s;
  s.sid_file = sid_file;
  s.rod_vy = 0.15 * omega;
  s.rod_omega = -0.5 * omega;
  s.omega = omega;
  s.step = step;
  s.end = end;
  return slider_crank_json(s);
}

StepTiming run_timed(const ffr::runtime::Model& model, ffr::runtime::Data& data, std::vector<double>* trace) {
  const auto n = ffr::runtime::step_count(model);
  const int last = model.bodies.back().offset;
  if (trace) trace->reserve(trace->size() + static_cast<std::size_t>(n));
  const auto t0 = std::chrono::steady_clock::now();
  for (std::int64_t i = 0; i < n; ++i) {
    ffr::runtime::step(model, data);
    if (trace) trace->push_back(data.state.q(last));
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto per_step = [n](double x) { return x / static_cast<double>(n); };
  return {per_step(1e6 * s), per_step(static_cast<double>(data.stats.newton_iterations)),
          per_step(static_cast<double>(data.stats.factorizations)), per_step(static_cast<double>(data.stats.solves))};
}

std::filesystem::path temp_dir(const std::string& tag) {
  std::random_device rd;
  auto p = std::filesystem::temp_directory_path() / ("ffr_bench_" + tag + "_" + std::to_string(rd()));
  std::filesystem::create_directories(p);
  return p;
}

}  // namespace bench
