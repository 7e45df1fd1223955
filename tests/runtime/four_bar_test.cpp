// A planar four-bar of four revolute joints modelled in 3-D: three of its twenty joint
// conditions are redundant (the out-of-plane ones of the closed loop), so Phi_q is
// rank-deficient and the multipliers are not unique. The augmented Lagrangian must run it
// without the user removing anything. Oracle: an independent one-degree-of-freedom model of
// the same mechanism (crank angle theta as the only coordinate, closed-form loop closure,
// Lagrange's equation m(theta) theta'' + m'(theta) theta'^2 / 2 = -V'(theta)) integrated with
// classical RK4 at a much smaller step.
#include "support.hpp"

#include <Eigen/QR>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace ffr::runtime;

namespace {

// Geometry: ground pivots O = (0,0) and C = (d,0); crank a, coupler b, rocker c (crank-rocker).
constexpr double a = 0.2, b = 0.5, c = 0.4, d = 0.45, g = 9.81;
constexpr double ma = 1.0, mb = 2.0, mc = 1.5;

struct Pose {
  Eigen::Vector2d A, B;
  double phi_b, phi_c;  // coupler and rocker angles
};

// Loop closure: B at distance b from A and c from C (the branch with B above the line A-C).
Pose pose(double th) {
  Pose p;
  p.A = Eigen::Vector2d(a * std::cos(th), a * std::sin(th));
  const Eigen::Vector2d C(d, 0);
  const Eigen::Vector2d AC = C - p.A;
  const double L = AC.norm();
  const double x = (b * b - c * c + L * L) / (2 * L), y = std::sqrt(b * b - x * x);
  const Eigen::Vector2d e = AC / L, n(-e(1), e(0));
  p.B = p.A + x * e + y * n;
  p.phi_b = std::atan2(p.B(1) - p.A(1), p.B(0) - p.A(0));
  p.phi_c = std::atan2(p.B(1) - C(1), p.B(0) - C(0));
  return p;
}

// Centres of mass (mid-points) and angles of the three bars as functions of theta.
struct Config {
  Eigen::Vector2d G[3];
  double phi[3];
};
Config config(double th) {
  const Pose p = pose(th);
  Config k;
  k.G[0] = 0.5 * p.A;
  k.G[1] = 0.5 * (p.A + p.B);
  k.G[2] = 0.5 * (Eigen::Vector2d(d, 0) + p.B);
  k.phi[0] = th;
  k.phi[1] = p.phi_b;
  k.phi[2] = p.phi_c;
  return k;
}

const double mass[3] = {ma, mb, mc}, len[3] = {a, b, c};
double inertia(int i) { return mass[i] * len[i] * len[i] / 12; }

// Generalised mass m(theta) = sum m |dG/dth|^2 + I (dphi/dth)^2 and potential V(theta).
double gmass(double th) {
  const double e = 1e-6;
  const Config p = config(th + e), m = config(th - e);
  double M = 0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d dG = (p.G[i] - m.G[i]) / (2 * e);
    const double dphi = (p.phi[i] - m.phi[i]) / (2 * e);
    M += mass[i] * dG.squaredNorm() + inertia(i) * dphi * dphi;
  }
  return M;
}
double potential(double th) {
  const Config k = config(th);
  double V = 0;
  for (int i = 0; i < 3; ++i) V += mass[i] * g * k.G[i](1);
  return V;
}
double accel(double th, double w) {
  const double e = 1e-5;
  const double dM = (gmass(th + e) - gmass(th - e)) / (2 * e), dV = (potential(th + e) - potential(th - e)) / (2 * e);
  return (-dV - 0.5 * dM * w * w) / gmass(th);
}

// Rigid-bar JSON: frame at the bar's first joint, x axis along the bar, COM at mid-length.
std::string bar(const char* name, int i, const Eigen::Vector2d& origin, double phi, const Eigen::Vector2d& vG, double w) {
  const double m = mass[i], L = len[i], I = inertia(i);
  Eigen::Matrix3d R = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Ig = R * Eigen::Vector3d(1e-5, I, I).asDiagonal() * R.transpose();
  const Eigen::Vector3d com = Eigen::Vector3d(origin(0), origin(1), 0) + R * Eigen::Vector3d(L / 2, 0, 0);
  // Velocity of the frame origin from the COM velocity: v_O = v_G - w x (G - O).
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

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

struct Outcome {
  double worst, violation, dE, E0;
  std::size_t notes;
};

constexpr double th0 = 0.3, w0 = 6.0;

// The four-bar started at crank angle th0 with crank rate w0 (consistent velocities from the
// one-DOF model).
std::string four_bar_json(double h) {
  // Consistent initial velocities from the one-DOF model.
  const double e = 1e-7;
  const Config kp = config(th0 + e), km = config(th0 - e);
  Eigen::Vector2d vG[3];
  double w[3];
  for (int i = 0; i < 3; ++i) {
    vG[i] = (kp.G[i] - km.G[i]) / (2 * e) * w0;
    w[i] = (kp.phi[i] - km.phi[i]) / (2 * e) * w0;
  }
  const Pose p0 = pose(th0);
  std::string json = R"({"gravity": [0, -9.81, 0], "bodies": [)" + bar("crank", 0, {0, 0}, th0, vG[0], w[0]) + ",\n" +
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
  "solver": {"end": 1.0, "step": )" + num(h) + R"(}
})";
  return json;
}

Outcome run(double h) {
  const double T = 1.0;
  const Model model = test::model_from(four_bar_json(h));
  EXPECT_EQ(model.nconstraints, 3 * 6 + 4 * 5);
  Data data(model);
  const auto notes = initialize(model, data);
  for (const auto& n : notes) std::printf("note: %s\n", n.c_str());

  // Oracle: RK4 on the one-DOF equation.
  double th = th0, wv = w0;
  const double hr = 1e-5;
  std::vector<double> ref;  // theta at every runtime step
  for (int s = 0; s < static_cast<int>(T / h); ++s) {
    for (int k = 0; k < static_cast<int>(h / hr + 0.5); ++k) {
      const double k1 = wv, l1 = accel(th, wv);
      const double k2 = wv + 0.5 * hr * l1, l2 = accel(th + 0.5 * hr * k1, k2);
      const double k3 = wv + 0.5 * hr * l2, l3 = accel(th + 0.5 * hr * k2, k3);
      const double k4 = wv + hr * l3, l4 = accel(th + hr * k3, k4);
      th += hr / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      wv += hr / 6 * (l1 + 2 * l2 + 2 * l3 + l4);
    }
    ref.push_back(th);
  }
  double worst = 0, worst_violation = 0;
  const double E0 = energy(model, data).total();
  double worst_dE = 0;
  for (std::size_t s = 0; s < ref.size(); ++s) {
    step(model, data);
    const double theta = th0 + joint_coordinate(model, data, 0, JointCoordinate::Angle);
    worst = std::max(worst, std::abs(theta - ref[s]));
    worst_violation = std::max(worst_violation, data.stats.last_violation);
    worst_dE = std::max(worst_dE, std::abs(energy(model, data).total() - E0));
  }
  std::printf("four-bar h = %g: theta(1 s) = %.9f (oracle %.9f), worst |dtheta| %.2e rad, violation %.2e, energy drift %.2e J of %.3f\n",
              h, th0 + joint_coordinate(model, data, 0, JointCoordinate::Angle), ref.back(), worst, worst_violation, worst_dE, E0);
  return {worst, worst_violation, worst_dE, E0, notes.size()};
}

}  // namespace

TEST(FourBar, RedundantRevolutesMatchOneDofModel) {
  const Outcome a = run(1e-3), b = run(5e-4);
  EXPECT_EQ(a.notes, 0u);  // consistent initial state given: nothing to adjust
  EXPECT_LT(b.worst, 1e-4);
  EXPECT_NEAR(a.worst / b.worst, 4.0, 0.6);  // second order
  EXPECT_LT(a.violation, 1e-11);
  EXPECT_LT(a.dE, 2e-4 * std::abs(a.E0));
}

// The exact multipliers (exact_multipliers.cpp: the projections' and Newton's fallback when their passes stall) with the
// three redundant rows: the correction Y mu it gives for a consistent right-hand side
// c = Phi_a v must be the one of the KKT system [T Phi_a^T; Phi_a 0] [dx; mu] = [0; c] (dx is
// unique although mu is not), solved independently by Eigen's complete orthogonal decomposition
// of the whole singular KKT matrix; and the three redundant rows must be the ones it leaves out.
TEST(FourBar, ExactMultipliersMatchTheKktSolutionWithRedundantRows) {
  const Model model = test::model_from(four_bar_json(1e-3));
  Data data(model);
  initialize(model, data);
  for (int i = 0; i < 10; ++i) step(model, data);
  refresh_tangent(model, data, data.state.t, data.state.lambda);
  const int nf = data.nf, na = data.na;
  ASSERT_TRUE(data.unknowns.empty());
  Eigen::VectorXd v(data.state.q.size());
  for (int i = 0; i < v.size(); ++i) v(i) = std::sin(1.0 + 0.7 * i);
  const Eigen::VectorXd c = data.Phiq.topLeftCorner(na, nf) * v.head(nf);
  const int rank = factor_exact_multipliers(data);
  solve_exact_multipliers(data, c);
  const Eigen::VectorXd dx = data.projY.topLeftCorner(nf, na) * data.proj_mu.head(na);

  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(nf + na, nf + na);
  kkt.topLeftCorner(nf, nf) = data.T.topLeftCorner(nf, nf);
  kkt.bottomLeftCorner(na, nf) = data.Phiq.topLeftCorner(na, nf);
  kkt.topRightCorner(nf, na) = data.Phiq.topLeftCorner(na, nf).transpose();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nf + na);
  rhs.tail(na) = c;
  const Eigen::VectorXd ref = kkt.completeOrthogonalDecomposition().solve(rhs);
  const double diff = (dx - ref.head(nf)).cwiseAbs().maxCoeff(), size = ref.head(nf).cwiseAbs().maxCoeff();
  const double residual = (data.Phiq.topLeftCorner(na, nf) * dx - c).cwiseAbs().maxCoeff();
  std::printf("exact multipliers: rank %d of %d rows; correction against the KKT solution %.3e (of %.3e); "
              "constraint residual %.3e (of %.3e)\n",
              rank, na, diff, size, residual, c.cwiseAbs().maxCoeff());
  EXPECT_EQ(rank, na - 3);
  EXPECT_LT(diff, 1e-9 * size);
  EXPECT_LT(residual, 1e-10 * c.cwiseAbs().maxCoeff());
}
