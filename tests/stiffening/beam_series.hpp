#pragma once
// Independent references for axially loaded Euler–Bernoulli cantilevers, clamped at xi = 0
// and free at xi = 1, in the nondimensional form
//     w'''' - [n(xi) w']' - lambda w = 0,   lambda = omega^2 rho A L^4 / (E I),
// with n(xi) = N(x) L^2 / (E I) the axial force (tension positive). The solution is the
// power series w = sum a_k xi^k (Frobenius; the coefficients are polynomials, so the series
// is entire), with a_0 = a_1 = 0 (clamped) and the free-end conditions w''(1) = 0 and
// w'''(1) - n(1) w'(1) = 0. The frequencies are the roots of the 2x2 determinant, found by
// scanning and bisection. This is the method of Wright et al. (1982) for rotating beams.
#include <cmath>
#include <functional>
#include <vector>

namespace ffr::test {

/// Axial force n(xi) = c0 + c1 xi + c2 xi^2 (nondimensional).
struct AxialForce {
  double c0 = 0, c1 = 0, c2 = 0;
};

/// Rotating about an axis through the root, hub radius 0, nondimensional speed s:
/// n = s^2 (1 - xi^2) / 2  (Wright et al. 1982; Hodges & Rutkowski 1981).
inline AxialForce rotating(double s) { return {s * s / 2, 0, -s * s / 2}; }
/// Self-weight with gamma = rho A g L^3 / (E I): n = gamma (1 - xi) (tension: hanging).
inline AxialForce self_weight(double gamma) { return {gamma, -gamma, 0}; }
/// A constant end force p = P L^2 / (E I).
inline AxialForce end_force(double p) { return {p, 0, 0}; }

namespace detail {
// The 2x2 free-end determinant at lambda.
inline double free_end_det(const AxialForce& f, double lambda) {
  constexpr int K = 400;
  double w2[2], w3[2];
  for (int s = 0; s < 2; ++s) {
    std::vector<long double> a(K + 5, 0.0L);
    a[2 + s] = 1.0L;
    // [n w']' = n w'' + n' w'; with n = c0 + c1 xi + c2 xi^2 the xi^k coefficient is
    // c0 (k+2)(k+1) a_{k+2} + c1 (k+1) k a_{k+1} + c2 k (k-1) a_k  +  c1 (k+1) a_{k+1} + 2 c2 k a_k.
    for (int k = 0; k + 4 <= K; ++k) {
      const long double rhs = f.c0 * (k + 2.0L) * (k + 1.0L) * a[k + 2] + f.c1 * (k + 1.0L) * (k + 1.0L) * a[k + 1] +
                              f.c2 * (k * (k - 1.0L) + 2.0L * k) * a[k] + lambda * a[k];
      a[k + 4] = rhs / ((k + 4.0L) * (k + 3.0L) * (k + 2.0L) * (k + 1.0L));
    }
    long double d1 = 0, d2 = 0, d3 = 0;
    for (int k = 1; k <= K; ++k) d1 += k * a[k];
    for (int k = 2; k <= K; ++k) d2 += k * (k - 1.0L) * a[k];
    for (int k = 3; k <= K; ++k) d3 += k * (k - 1.0L) * (k - 2.0L) * a[k];
    const long double n1 = f.c0 + f.c1 + f.c2;
    w2[s] = static_cast<double>(d2);
    w3[s] = static_cast<double>(d3 - n1 * d1);
  }
  return w2[0] * w3[1] - w2[1] * w3[0];
}
}  // namespace detail

/// The first `count` nondimensional frequencies omega_bar = sqrt(lambda) (ascending).
inline std::vector<double> cantilever_frequencies(const AxialForce& f, int count) {
  std::vector<double> out;
  double prev = detail::free_end_det(f, 1e-6);
  double w_prev = 1e-3;
  for (double w = 0.02; w < 200 && static_cast<int>(out.size()) < count; w += 0.02) {
    const double d = detail::free_end_det(f, w * w);
    if ((d > 0) != (prev > 0)) {
      double lo = w_prev, hi = w;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        const double dm = detail::free_end_det(f, mid * mid);
        if ((dm > 0) == (prev > 0)) lo = mid;
        else hi = mid;
      }
      out.push_back(0.5 * (lo + hi));
    }
    prev = d;
    w_prev = w;
  }
  return out;
}

}  // namespace ffr::test
