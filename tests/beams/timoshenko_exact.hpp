#pragma once
// Independent solutions of the continuous Timoshenko beam (bending in one plane, with shear
// deformation and rotary inertia) for the modal tests, from its frequency equations.
//
// Equations (Timoshenko 1921; the form of Huang, J. Appl. Mech. 28 (1961) 579–584), with the
// section rotation theta, M = EI theta', V = kGA (v' - theta):
//     kGA (v'' - theta') + rho A omega^2 v = 0
//     EI theta'' + kGA (v' - theta) + rho I omega^2 theta = 0.
// For omega below the cut-off sqrt(kGA / rho I), v = e^{s x} gives
//     EI kGA s^4 + (EI rho A + rho I kGA) omega^2 s^2 - rho A omega^2 (kGA - rho I omega^2) = 0,
// one positive root s^2 = l1^2 and one negative s^2 = -l2^2, hence four real basis solutions
// (cosh, sinh, cos, sin) with theta = (s + c/s) v-companion, c = rho A omega^2 / kGA.

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <vector>

namespace ffr::test {

struct TimoshenkoBeam {
  double EI, kGA, rhoA, rhoI;
};

/// Values at x of the four basis solutions: rows v, v', theta, theta'.
inline Eigen::Matrix4d timoshenko_basis(const TimoshenkoBeam& b, double omega, double x) {
  const double w2 = omega * omega;
  const double a = b.EI * b.kGA, bb = (b.EI * b.rhoA + b.rhoI * b.kGA) * w2, c0 = -b.rhoA * w2 * (b.kGA - b.rhoI * w2);
  const double disc = std::sqrt(bb * bb - 4 * a * c0);
  const double l1 = std::sqrt((-bb + disc) / (2 * a)), l2 = std::sqrt((bb + disc) / (2 * a));
  const double c = b.rhoA * w2 / b.kGA;
  const double p = l1 + c / l1, q = l2 - c / l2;
  const double ch = std::cosh(l1 * x), sh = std::sinh(l1 * x), co = std::cos(l2 * x), si = std::sin(l2 * x);
  Eigen::Matrix4d B;
  // columns: cosh, sinh, cos, sin
  B << ch, sh, co, si,                                   // v
      l1 * sh, l1 * ch, -l2 * si, l2 * co,               // v'
      p * sh, p * ch, -q * si, q * co,                   // theta
      p * l1 * ch, p * l1 * sh, -q * l2 * co, -q * l2 * si;  // theta'
  return B;
}

/// Roots of det(omega) = 0 on (lo, hi), scanned with `steps` steps and refined by bisection.
inline std::vector<double> roots(const std::function<double(double)>& det, double lo, double hi, int steps = 20000) {
  std::vector<double> out;
  double x0 = lo, f0 = det(lo);
  for (int i = 1; i <= steps; ++i) {
    const double x1 = lo + (hi - lo) * i / steps, f1 = det(x1);
    if (f0 == 0 || (f0 < 0) != (f1 < 0)) {
      double a = x0, b = x1, fa = f0;
      for (int k = 0; k < 200; ++k) {
        const double m = 0.5 * (a + b), fm = det(m);
        if ((fa < 0) == (fm < 0)) a = m, fa = fm;
        else b = m;
      }
      out.push_back(0.5 * (a + b));
    }
    x0 = x1, f0 = f1;
  }
  return out;
}

}  // namespace ffr::test
