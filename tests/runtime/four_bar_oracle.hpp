#pragma once
// An independent oracle for the four-bar of tools/bench/formulations (formulation_models.hpp):
// the mechanism as one degree of freedom, the crank angle theta, with its closed-form loop
// closure, and Lagrange's equation m(theta) theta'' + m'(theta) theta'^2 / 2 = -V'(theta),
// integrated by classical RK4 at a step far below the runtime's.
#include "formulation_models.hpp"  // tools/bench/formulations

#include <vector>

namespace ffr::runtime::test::four_bar_oracle {

using namespace formulations::four_bar;

/// Generalised mass m(theta) = sum m |dG/dth|^2 + I (dphi/dth)^2.
inline double gmass(double th) {
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
/// Potential V(theta) of gravity (along -y).
inline double potential(double th) {
  const Config k = config(th);
  double V = 0;
  for (int i = 0; i < 3; ++i) V += mass[i] * g * k.G[i](1);
  return V;
}
inline double accel(double th, double w) {
  const double e = 1e-5;
  const double dM = (gmass(th + e) - gmass(th - e)) / (2 * e), dV = (potential(th + e) - potential(th - e)) / (2 * e);
  return (-dV - 0.5 * dM * w * w) / gmass(th);
}

/// The crank angle after each of `steps` steps of h from kTheta0 at kOmega0 (RK4 at 1e-5 s).
inline std::vector<double> crank_angles(double h, int steps) {
  double th = kTheta0, wv = kOmega0;
  const double hr = 1e-5;
  std::vector<double> ref;
  for (int s = 0; s < steps; ++s) {
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
  return ref;
}

}  // namespace ffr::runtime::test::four_bar_oracle
