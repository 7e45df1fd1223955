#include "support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <fstream>
#include <random>

#include <sys/wait.h>

namespace ffr::runtime::test {

TempDir::TempDir(const std::string& tag) {
  std::random_device rd;
  path = std::filesystem::temp_directory_path() / ("ffr_rt_" + tag + "_" + std::to_string(rd()));
  std::filesystem::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
}

Model model_from(const std::string& json, const std::filesystem::path& dir) {
  return parse_model(json, dir.empty() ? std::filesystem::current_path() : dir, "test-model.json");
}

std::string error_of(const std::string& json, const std::filesystem::path& dir) {
  try {
    model_from(json, dir);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& json, const std::string& field, const std::string& what,
                  const std::filesystem::path& dir) {
  const std::string msg = error_of(json, dir);
  EXPECT_NE(msg.find("test-model.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find(field), std::string::npos) << "field '" << field << "' not in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "'" << what << "' not in: " << msg;
}

std::string compound_pendulum_json(const std::string& solver, double rate) {
  char buf[256];
  std::snprintf(buf, sizeof buf, R"(, "angular_velocity": [0, %.17g, 0])", rate);
  return std::string(R"({
  "gravity": [0, 0, -9.81],
  "bodies": [{"name": "bar", "type": "rigid", "mass": 1.0, "com": [0.5, 0, 0],
              "inertia": [[6.6666666666666667e-5, 0, 0], [0, 0.08336666666666667, 0], [0, 0, 0.08336666666666667]],
              "position": [0, 0, 0])") +
         buf + R"(}],
  "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bar", "at": [0, 0, 0], "axis": [0, 1, 0]}],
  "solver": )" + solver + R"(,
  "outputs": [{"name": "angle", "type": "joint_coordinate", "joint": "hinge"}]
})";
}

double compound_pendulum_oracle(double end, double rate, double* theta_dot) {
  const double w2 = kPendulumMass * kPendulumG * kPendulumD / (kPendulumIyy + kPendulumMass * kPendulumD * kPendulumD);
  const int n = 200000;
  const double h = end / n;
  double th = 0, om = rate;
  const auto f = [&](double t) { return w2 * std::cos(t); };
  for (int i = 0; i < n; ++i) {
    const double k1t = om, k1o = f(th);
    const double k2t = om + 0.5 * h * k1o, k2o = f(th + 0.5 * h * k1t);
    const double k3t = om + 0.5 * h * k2o, k3o = f(th + 0.5 * h * k2t);
    const double k4t = om + h * k3o, k4o = f(th + h * k3t);
    th += h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
    om += h / 6 * (k1o + 2 * k2o + 2 * k3o + k4o);
  }
  if (theta_dot) *theta_dot = om;
  return th;
}

SimRun run_ffr_sim(const std::string& args) {
  const std::string cmd = std::string(FFR_BINARY_DIR) + "/bin/ffr-sim " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  SimRun r;
  if (!p) return r;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::vector<double> output(const Model& model, Data& data, const std::string& name) {
  const int i = model.find_output(name);
  EXPECT_GE(i, 0) << name;
  if (i < 0) return {};
  std::vector<double> v(static_cast<std::size_t>(model.outputs[static_cast<std::size_t>(i)].size));
  evaluate_output(model, data, model.outputs[static_cast<std::size_t>(i)], v.data());
  return v;
}

std::string initialize_refusal(const Model& model) {
  Data data(model);
  try {
    initialize(model, data);
  } catch (const SolverError& e) {
    return e.what();
  }
  return "";
}

SideBySide step_side_by_side(const Model& a, const Model& b) {
  Data da(a), db(b);
  initialize(a, da);
  initialize(b, db);
  SideBySide r;
  const VectorXd q_start = da.state.q;
  const std::int64_t n = step_count(a);
  for (std::int64_t i = 0; i < n; ++i) {
    step(a, da);
    step(b, db);
    r.apart = std::max(r.apart, scaled_norm(a, da.state.q - db.state.q));
    r.motion = std::max(r.motion, scaled_norm(a, da.state.q - q_start));
    r.violation = std::max(r.violation, da.stats.last_violation);
  }
  r.iterations_a = static_cast<double>(da.stats.newton_iterations) / static_cast<double>(std::max<std::int64_t>(n, 1));
  r.iterations_b = static_cast<double>(db.stats.newton_iterations) / static_cast<double>(std::max<std::int64_t>(n, 1));
  return r;
}

}  // namespace ffr::runtime::test
