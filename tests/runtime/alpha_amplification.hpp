#pragma once
// The numerical damping of one linear mode per generalized-alpha step, against the amplification
// matrix of Chung & Hulbert ("A time integration algorithm for structural dynamics with improved
// numerical dissipation: the generalized-alpha method", J. Appl. Mech. 60, 1993), built here from
// their equations: Newmark's two relations and the balance
// (1 - alpha_m) a_{n+1} + alpha_m a_n + omega^2 ((1 - alpha_f) d_{n+1} + alpha_f d_n) = 0, with
// alpha_m, alpha_f, beta, gamma from rho_inf (their eq. 25 and 17-19). Shared by the absolute
// (generalized_alpha_test.cpp) and the relative (relative_alpha_test.cpp) formulation's tests.
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <complex>

namespace ffr::runtime::test {

/// Chung & Hulbert's amplification matrix of (d, v, a) for d'' + omega^2 d = 0, one step of h.
inline Eigen::Matrix3d alpha_amplification(double rho, double omega, double h) {
  const double am = (2 * rho - 1) / (rho + 1), af = rho / (rho + 1);
  const double g = 0.5 - am + af, b = 0.25 * (1 - am + af) * (1 - am + af), w2 = omega * omega;
  Eigen::Matrix3d L, R;
  L << 1, 0, -b * h * h, 0, 1, -g * h, (1 - af) * w2, 0, 1 - am;
  R << 1, h, h * h * (0.5 - b), 0, 1, h * (1 - g), -af * w2, 0, -am;
  return L.partialPivLu().solve(R);
}

struct ModeDecay {
  double spectral = 0;  ///< the amplification matrix's spectral radius
  double worst = 0;     ///< the largest | |c_{n+1} / c_n| - spectral | over the steps checked
  int checked = 0;      ///< steps checked (until the component reached the state's round-off)
};

/// Runs `steps` steps (`step()`) and, after each but the first (whose a_0 is the scheme's start),
/// writes the mode's state (d, v, a) of `state()` in the matrix's eigenvectors: its component of
/// the largest eigenvalue (the principal pair for omega h below about 1, either of a complex
/// pair) must shrink by the spectral radius at every step.
template <class Step, class State>
ModeDecay measure_mode_decay(double rho, double omega, double h, long steps, Step&& step, State&& state) {
  Eigen::EigenSolver<Eigen::Matrix3d> es(alpha_amplification(rho, omega, h));
  const Eigen::Matrix3cd Vinv = es.eigenvectors().inverse();
  const Eigen::Vector3cd lam = es.eigenvalues();
  int p = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(lam(k)) > std::abs(lam(p)) + 1e-14) p = k;
  ModeDecay d;
  d.spectral = std::abs(lam(p));
  step();
  const Eigen::Vector3cd c0 = Vinv * state();
  const double size0 = c0.norm();  // the round-off below is relative to the state
  std::complex<double> c_prev = c0(p);
  for (long i = 1; i < steps; ++i) {
    step();
    const std::complex<double> c = (Vinv * state())(p);
    if (std::abs(c_prev) > 1e-8 * size0) {
      d.worst = std::max(d.worst, std::abs(std::abs(c / c_prev) - d.spectral));
      ++d.checked;
    }
    c_prev = c;
  }
  return d;
}

}  // namespace ffr::runtime::test
