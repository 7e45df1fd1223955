#include "crank_runs.hpp"

#include "support.hpp"

#include <cmath>
#include <cstdio>

namespace ffr::runtime::test {
namespace {

constexpr double kCrank = 0.15, kOmega = 150.0;

double chord_deflection(const Eigen::Vector2d& a, const Eigen::Vector2d& m, const Eigen::Vector2d& b) {
  const Eigen::Vector2d c = (b - a).normalized();
  const Eigen::Vector2d rel = m - 0.5 * (a + b);
  return c.x() * rel.y() - c.y() * rel.x();
}

}  // namespace

double CrankTrace::peak() const {
  double p = 0;
  for (double v : d) p = std::max(p, std::abs(v));
  return p;
}

CrankTrace oracle_crank(ReissnerBeam b, double slider_mass, double h, double end) {
  b.x0 = kCrank;
  b.y0 = 0;
  b.phi0 = 0;
  BeamIntegrator in(b);
  const int N = b.n;
  const double r = kCrank, w = kOmega;
  in.prescribed = {
      {0, [=](double t) { return Eigen::Vector3d(r * std::cos(w * t), -r * w * std::sin(w * t), -r * w * w * std::cos(w * t)); }},
      {1, [=](double t) { return Eigen::Vector3d(r * std::sin(w * t), r * w * std::cos(w * t), -r * w * w * std::sin(w * t)); }},
      {3 * N + 1, [](double) { return Eigen::Vector3d::Zero(); }}};
  in.M(3 * N, 3 * N) += slider_mass;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(b.ndof());
  for (int i = 0; i <= N; ++i) {
    const double s = b.L * i / N;
    v(3 * i + 1) = r * w * (1 - s / b.L);
    v(3 * i + 2) = -r * w / b.L;
  }
  in.start(0, b.reference(), v);
  CrankTrace tr;
  const auto steps = static_cast<int>(std::lround(end / h));
  for (int k = 0; k < steps; ++k) {
    in.step(h);
    tr.t.push_back(in.t);
    tr.d.push_back(chord_deflection(in.u.segment<2>(0), in.u.segment<2>(3 * (N / 2)), in.u.segment<2>(3 * N)));
  }
  return tr;
}

CrankTrace runtime_crank(const std::filesystem::path& dir, const std::string& sid_file, double slider_mass,
                         bool stiffening, double h, double end, double L) {
  char json[4096];
  std::snprintf(json, sizeof json, R"({
  "bodies": [
    {"name": "crank", "type": "rigid", "mass": 0.36, "com": [0.075, 0, 0],
     "inertia": [[1e-5, 0, 0], [0, 7.02e-4, 0], [0, 0, 7.02e-4]]},
    {"name": "rod", "type": "flexible", "sid": "%s", "stiffening": %s, "position": [%.17g, 0, 0],
     "velocity": [0, %.17g, 0], "angular_velocity": [0, 0, %.17g]},
    {"name": "slider", "type": "rigid", "mass": %.17g, "com": [%.17g, 0, 0],
     "inertia": [[1e-6, 0, 0], [0, 1e-6, 0], [0, 0, 1e-6]]}
  ],
  "joints": [
    {"name": "hub", "type": "revolute", "body1": "ground", "body2": "crank", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "pin", "type": "revolute", "body1": "crank", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "wrist", "type": "revolute", "body1": "rod", "body2": "slider", "node1": "B", "axis": [0, 0, 1]},
    {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "at": [%.17g, 0, 0], "axis": [1, 0, 0]}
  ],
  "motions": [{"joint": "hub", "table": {"t": [0, 1], "value": [0, %.17g]}}],
  "solver": {"end": %.17g, "step": %.17g}
})",
                sid_file.c_str(), stiffening ? "true" : "false", kCrank, kCrank * kOmega, -kCrank * kOmega / L, slider_mass,
                kCrank + L, kCrank + L, kOmega, end, h);
  const Model model = model_from(json, dir);
  Data data(model);
  initialize(model, data);
  const Body& rod = model.bodies[1];
  const int iA = rod.find_node("A"), iB = rod.find_node("B");
  const int iM = rod.find_node("M") >= 0 ? rod.find_node("M") : rod.find_node("mid");
  auto at = [&](int node) {
    const NodeSlice& s = rod.nodes[static_cast<std::size_t>(node)];
    const Eigen::Vector3d r0 = data.state.q.segment<3>(rod.offset);
    Eigen::Matrix3d A;
    for (int a = 0; a < 3; ++a) A.col(a) = data.state.q.segment<3>(rod.offset + 3 + 3 * a);
    const Eigen::Vector3d p = r0 + A * (s.origin + s.phi * data.state.q.segment(rod.offset + 12, rod.nq));
    return Eigen::Vector2d(p.x(), p.y());
  };
  CrankTrace tr;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    tr.t.push_back(data.state.t);
    tr.d.push_back(chord_deflection(at(iA), at(iM), at(iB)));
  }
  return tr;
}

double worst_relative(const CrankTrace& a, const CrankTrace& ref) {
  double w = 0;
  for (std::size_t i = 0; i < std::min(a.d.size(), ref.d.size()); ++i) w = std::max(w, std::abs(a.d[i] - ref.d[i]));
  return w / ref.peak();
}

}  // namespace ffr::runtime::test
