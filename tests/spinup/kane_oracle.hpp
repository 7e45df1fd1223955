#pragma once
// An independent reference for the spin-up maneuver of Kane, Ryan & Banerjee, "Dynamics of a
// cantilever beam attached to a moving base", J. Guidance 10 (1987) 139-151: an Euler–Bernoulli
// beam clamped to a hub whose angle follows
//   theta(t) = (W/T) (t^2/2 + (T/2pi)^2 (cos(2 pi t/T) - 1))   for t < T,  W (t - T/2) after.
// Their consistently linearised in-plane equation (hub radius 0, axial stretch neglected):
//   rhoA (v'' - theta'^2 v) + EI v'''' - (N v')' = -rhoA theta'' x,   N = rhoA theta'^2 (L^2 - x^2)/2,
// where the (N v')' term is the geometric stiffening that the "conventional" modal approach
// misses (without it the beam diverges once theta' exceeds its first frequency).
// Solved here by Galerkin on the clamped-free beam's own modes (closed form) and RK4.
#include <Eigen/Dense>

#include <cmath>
#include <vector>

namespace ffr::test {

struct KaneBeam {
  double L = 10, rhoA = 1.2, EI = 14000;
};

struct SpinUp {
  double W = 6, T = 15;
  double theta(double t) const {
    return t < T ? W / T * (t * t / 2 + std::pow(T / (2 * M_PI), 2) * (std::cos(2 * M_PI * t / T) - 1)) : W * (t - T / 2);
  }
  double rate(double t) const { return t < T ? W / T * (t - T / (2 * M_PI) * std::sin(2 * M_PI * t / T)) : W; }
  double accel(double t) const { return t < T ? W / T * (1 - std::cos(2 * M_PI * t / T)) : 0.0; }
};

/// Tip deflection v(L, t) at the times `t` (ascending), with or without stiffening.
inline std::vector<double> kane_tip_deflection(const KaneBeam& b, const SpinUp& s, const std::vector<double>& t,
                                               bool stiffening, int modes = 5) {
  const double betaL[6] = {1.875104068711961, 4.694091132974175, 7.854757438237613, 10.99554073487547,
                           14.13716839104647, 17.27875953208824};
  const int n = modes;
  const int nx = 4000;  // composite Simpson on [0, L]
  const double h = b.L / nx;
  // Mode shapes phi_i and slopes, normalised to int phi_i^2 dx = L.
  Eigen::MatrixXd phi(nx + 1, n), dphi(nx + 1, n);
  for (int i = 0; i < n; ++i) {
    const double be = betaL[i] / b.L;
    const double sg = (std::cosh(betaL[i]) + std::cos(betaL[i])) / (std::sinh(betaL[i]) + std::sin(betaL[i]));
    for (int k = 0; k <= nx; ++k) {
      const double x = be * k * h;
      phi(k, i) = std::cosh(x) - std::cos(x) - sg * (std::sinh(x) - std::sin(x));
      dphi(k, i) = be * (std::sinh(x) + std::sin(x) - sg * (std::cosh(x) - std::cos(x)));
    }
  }
  auto simpson = [&](const Eigen::VectorXd& f) {
    double sum = f(0) + f(nx);
    for (int k = 1; k < nx; ++k) sum += (k % 2 ? 4.0 : 2.0) * f(k);
    return sum * h / 3;
  };
  Eigen::MatrixXd M(n, n), K = Eigen::MatrixXd::Zero(n, n), G(n, n);
  Eigen::VectorXd f(n), x(nx + 1), tension(nx + 1);
  for (int k = 0; k <= nx; ++k) {
    x(k) = k * h;
    tension(k) = b.rhoA * (b.L * b.L - x(k) * x(k)) / 2;  // per unit theta'^2
  }
  for (int i = 0; i < n; ++i) {
    f(i) = b.rhoA * simpson(x.cwiseProduct(phi.col(i)));
    K(i, i) = std::pow(betaL[i] / b.L, 4) * b.EI;  // EI int phi''^2 = EI beta^4 int phi^2, times 1/int phi^2 below
    for (int j = 0; j < n; ++j) {
      M(i, j) = b.rhoA * simpson(phi.col(i).cwiseProduct(phi.col(j)));
      G(i, j) = simpson(tension.cwiseProduct(dphi.col(i)).cwiseProduct(dphi.col(j)));
    }
  }
  for (int i = 0; i < n; ++i) K(i, i) *= M(i, i) / b.rhoA;
  const Eigen::MatrixXd Minv = M.inverse();
  auto rhs = [&](double tt, const Eigen::VectorXd& y) {
    const Eigen::VectorXd eta = y.head(n), deta = y.tail(n);
    const double w = s.rate(tt);
    const Eigen::MatrixXd Keff = K - w * w * M + (stiffening ? Eigen::MatrixXd(w * w * G) : Eigen::MatrixXd::Zero(n, n));
    Eigen::VectorXd out(2 * n);
    out.head(n) = deta;
    out.tail(n) = Minv * (-Keff * eta - s.accel(tt) * f);
    return out;
  };
  std::vector<double> tip;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  double tt = 0;
  const double dt = 5e-4;
  for (double target : t) {
    while (tt < target - 1e-12) {
      const double step = std::min(dt, target - tt);
      const Eigen::VectorXd k1 = rhs(tt, y), k2 = rhs(tt + step / 2, y + step / 2 * k1),
                            k3 = rhs(tt + step / 2, y + step / 2 * k2), k4 = rhs(tt + step, y + step * k3);
      y += step / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      tt += step;
    }
    tip.push_back(phi.row(nx).dot(y.head(n)));
  }
  return tip;
}

}  // namespace ffr::test
