#pragma once
// The models both the formulation benchmark (main.cpp) and the runtime's tests (the relative
// formulation's, the four-bar's and the reactions') run, as model-file text with a chosen
// "formulation" (FORMULATION.md 18): a planar pendulum chain of rigid links and the four-bar of
// four_bar_test.cpp (crank-rocker, started at a consistent state).
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <string>

namespace formulations {

inline std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

/// n rigid links of 0.1 m and 0.1 kg (thin bars), hinged end to end about z (the first to the
/// ground at the origin), horizontal along x and at rest at the start, gravity along -y.
inline std::string pendulum_chain_json(int n, double h, double end, const std::string& formulation) {
  const double l = 0.1, m = 0.1, I = m * l * l / 12;
  std::string bodies, joints;
  for (int i = 0; i < n; ++i) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  R"(%s{"name": "link%d", "type": "rigid", "mass": %.17g, "com": [%.17g, 0, 0], "position": [%.17g, 0, 0],
      "inertia": [[1e-7, 0, 0], [0, %.17g, 0], [0, 0, %.17g]]})",
                  i ? ",\n" : "", i, m, (i + 0.5) * l, i * l, I, I);
    bodies += buf;
    const std::string parent = i ? "link" + std::to_string(i - 1) : std::string("ground");
    std::snprintf(buf, sizeof buf, R"(%s{"name": "j%d", "type": "revolute", "body1": "%s", "body2": "link%d", "at": [%.17g, 0, 0], "axis": [0, 0, 1]})",
                  i ? ",\n" : "", i, parent.c_str(), i, i * l);
    joints += buf;
  }
  return R"({"gravity": [0, -9.81, 0], "bodies": [)" + bodies + R"(], "joints": [)" + joints +
         R"(], "solver": {"formulation": ")" + formulation + R"(", "end": )" + num(end) + R"(, "step": )" + num(h) + "}}";
}

// ---- the four-bar: ground pivots O = (0,0) and C = (d,0); crank a, coupler b, rocker c ----------
namespace four_bar {
constexpr double a = 0.2, b = 0.5, c = 0.4, d = 0.45, g = 9.81;
constexpr double mass[3] = {1.0, 2.0, 1.5}, len[3] = {a, b, c};
constexpr double kTheta0 = 0.3, kOmega0 = 6.0;  ///< the crank's initial angle and rate
inline double inertia(int i) { return mass[i] * len[i] * len[i] / 12; }

struct Pose {
  Eigen::Vector2d A, B;
  double phi_b, phi_c;  ///< coupler and rocker angles
};
/// Loop closure: B at distance b from A and c from C (the branch with B above the line A-C).
inline Pose pose(double th) {
  Pose p;
  p.A = Eigen::Vector2d(a * std::cos(th), a * std::sin(th));
  const Eigen::Vector2d C(d, 0), AC = C - p.A;
  const double L = AC.norm(), x = (b * b - c * c + L * L) / (2 * L), y = std::sqrt(b * b - x * x);
  const Eigen::Vector2d e = AC / L, n(-e(1), e(0));
  p.B = p.A + x * e + y * n;
  p.phi_b = std::atan2(p.B(1) - p.A(1), p.B(0) - p.A(0));
  p.phi_c = std::atan2(p.B(1) - C(1), p.B(0) - C(0));
  return p;
}
/// Centres of mass (mid-points) and angles of the three bars as functions of the crank angle.
struct Config {
  Eigen::Vector2d G[3];
  double phi[3];
};
inline Config config(double th) {
  const Pose p = pose(th);
  return Config{{0.5 * p.A, 0.5 * (p.A + p.B), 0.5 * (Eigen::Vector2d(d, 0) + p.B)}, {th, p.phi_b, p.phi_c}};
}

/// A bar: frame at its first joint, x along it, centre of mass at mid-length.
inline std::string bar(const char* name, int i, const Eigen::Vector2d& origin, double phi, const Eigen::Vector2d& vG, double w) {
  const double m = mass[i], L = len[i], I = inertia(i);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Ig = R * Eigen::Vector3d(1e-5, I, I).asDiagonal() * R.transpose();
  const Eigen::Vector3d com = Eigen::Vector3d(origin(0), origin(1), 0) + R * Eigen::Vector3d(L / 2, 0, 0);
  const Eigen::Vector3d vO = Eigen::Vector3d(vG(0), vG(1), 0) - Eigen::Vector3d(0, 0, w).cross(R * Eigen::Vector3d(L / 2, 0, 0));
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                R"({"name": "%s", "type": "rigid", "mass": %.17g, "com": [%.17g, %.17g, 0], "position": [%.17g, %.17g, 0],
     "orientation": [[%.17g, %.17g, 0], [%.17g, %.17g, 0], [0, 0, 1]],
     "inertia": [[%.17g, %.17g, 0], [%.17g, %.17g, 0], [0, 0, %.17g]],
     "velocity": [%.17g, %.17g, 0], "angular_velocity": [0, 0, %.17g]})",
                name, m, com(0), com(1), origin(0), origin(1), R(0, 0), R(0, 1), R(1, 0), R(1, 1), Ig(0, 0), Ig(0, 1), Ig(1, 0),
                Ig(1, 1), Ig(2, 2), vO(0), vO(1), w);
  return buf;
}

/// Four revolute joints about z, the crank at kTheta0 turning at kOmega0 (the other bars'
/// velocities from the loop closure: a consistent start), gravity along -y. `extra`: further
/// members of the model object (e.g. `"outputs": [...]`), appended as given.
inline std::string json(double h, double end, const std::string& formulation, const std::string& extra = "") {
  const double e = 1e-7;
  const Config kp = config(kTheta0 + e), km = config(kTheta0 - e);
  Eigen::Vector2d vG[3];
  double w[3];
  for (int i = 0; i < 3; ++i) {
    vG[i] = (kp.G[i] - km.G[i]) / (2 * e) * kOmega0;
    w[i] = (kp.phi[i] - km.phi[i]) / (2 * e) * kOmega0;
  }
  const Pose p0 = pose(kTheta0);
  return R"({"gravity": [0, -9.81, 0], "bodies": [)" + bar("crank", 0, {0, 0}, kTheta0, vG[0], w[0]) + ",\n" +
         bar("coupler", 1, p0.A, p0.phi_b, vG[1], w[1]) + ",\n" + bar("rocker", 2, {d, 0}, p0.phi_c, vG[2], w[2]) +
         R"(],
  "joints": [
    {"name": "O", "type": "revolute", "body1": "ground", "body2": "crank", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "A", "type": "revolute", "body1": "crank", "body2": "coupler", "at": [)" +
         num(p0.A(0)) + ", " + num(p0.A(1)) + R"(, 0], "axis": [0, 0, 1]},
    {"name": "B", "type": "revolute", "body1": "coupler", "body2": "rocker", "at": [)" +
         num(p0.B(0)) + ", " + num(p0.B(1)) + R"(, 0], "axis": [0, 0, 1]},
    {"name": "C", "type": "revolute", "body1": "rocker", "body2": "ground", "at": [0.45, 0, 0], "axis": [0, 0, 1]}
  ],
  "solver": {"formulation": ")" + formulation + R"(", "end": )" + num(end) + R"(, "step": )" + num(h) + "}" +
         (extra.empty() ? std::string() : ",\n  " + extra) + "\n}";
}
}  // namespace four_bar

/// The model text with "formulation" set in its "solver" object.
inline std::string with_formulation(std::string json, const std::string& formulation) {
  const std::string key = "\"solver\": {";
  const auto at = json.find(key);
  if (at != std::string::npos) json.insert(at + key.size(), "\"formulation\": \"" + formulation + "\", ");
  return json;
}

}  // namespace formulations
