// The trapezoidal rule and the generalized-alpha method as coefficients of the index-3 step
// (FORMULATION.md section 9).
//
// Generalized-alpha in the form of Arnold & Bruls (2007, "Convergence of the generalized-alpha
// scheme for constrained mechanical systems"): the equations of motion and the constraints hold
// at t_{n+1} with the end-of-step accelerations q_ddot_{n+1} (as in the trapezoidal step), and a
// pseudo-acceleration a carries the numerical damping,
//
//   q_{n+1}     = q_n + h q_dot_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
//   q_dot_{n+1} = q_dot_n + h (1 - gamma) a_n + h gamma a_{n+1}
//   (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) q_ddot_{n+1} + alpha_f q_ddot_n.
//
// For a linear system with constant coefficients this is Chung & Hulbert's method (1993): the
// combination (1 - alpha_f) EOM_{n+1} + alpha_f EOM_n is their balance at t_{n+1-alpha_f} with a
// as their acceleration, so it has their amplification matrix. Eliminating a_{n+1} gives
//
//   a_{n+1}     = (q_{n+1} - q_n - h q_dot_n - h^2 (1/2 - beta) a_n) / (beta h^2)
//   q_dot_{n+1} = gamma / (beta h) q_{n+1} + qd_hat
//   q_ddot_{n+1} = (1 - alpha_m) / ((1 - alpha_f) beta h^2) q_{n+1} + qdd_hat,
//
// the trapezoidal rule's form with other coefficients. At rho_inf = 1 (alpha_m = alpha_f = 1/2,
// beta = 1/4, gamma = 1/2) and a_0 = q_ddot_0 the recurrence keeps a_n = q_ddot_n and the step is
// the trapezoidal one.
//
// The projections change q_dot_{n+1} and q_ddot_{n+1} after Newton; the recurrence is advanced
// with the projected accelerations (finish_step_scheme), which is what keeps rho_inf = 1 equal to
// the trapezoidal ALI3-P step (whose next step starts from the projected rates).
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/scheme.hpp"
#include "ffr/runtime/state.hpp"

#include <algorithm>
#include <cmath>

namespace ffr::runtime {
namespace {

// The trapezoidal rule: the model's scheme, or the generalized-alpha start's step.
bool trapezoidal(const Model& model, const Data& data) {
  return model.settings.integrator == Integrator::Trapezoidal || data.scheme.start_step;
}

}  // namespace

AlphaParameters AlphaParameters::from_spectral_radius(double rho) {
  AlphaParameters p;
  p.alpha_m = (2 * rho - 1) / (rho + 1);
  p.alpha_f = rho / (rho + 1);
  p.gamma = 0.5 - p.alpha_m + p.alpha_f;
  const double s = 1 - p.alpha_m + p.alpha_f;
  p.beta = 0.25 * s * s;
  return p;
}

StepCoefficients trapezoidal_coefficients(double h) {
  StepCoefficients k;
  k.h = k.h_prev = h;
  k.c1 = 2.0 / h;
  k.c2 = 4.0 / (h * h);
  k.kv = 0.5 * h;
  k.kq = 0.25 * h * h;
  return k;
}

void set_step_coefficients(const Model& model, Data& data, double h) {
  const double h_prev = data.state.k.h;
  if (trapezoidal(model, data)) {
    data.state.k = trapezoidal_coefficients(h);
  } else {
    const AlphaParameters p = AlphaParameters::from_spectral_radius(model.settings.spectral_radius);
    StepCoefficients& k = data.state.k;
    k.h = h;
    k.c1 = p.gamma / (p.beta * h);
    k.c2 = (1 - p.alpha_m) / ((1 - p.alpha_f) * p.beta * h * h);
    k.kv = k.c1 / k.c2;
    k.kq = 1 / k.c2;
    // A new step size: a_n stands for the acceleration at t_n + (alpha_m - alpha_f) h (Arnold &
    // Bruls), so its lead over q_ddot_n is rescaled with h; kept, it would be a first-order
    // error of the new step's a_n.
    if (data.state.have_previous && h != h_prev && h_prev > 0) data.state.a = data.state.qdd + (h / h_prev) * (data.state.a - data.state.qdd);
  }
  data.state.k.h_prev = h_prev > 0 ? h_prev : h;
}

void start_generalized_alpha(const Model& model, Data& data, double h) {
  const AlphaParameters p = AlphaParameters::from_spectral_radius(model.settings.spectral_radius);
  const double delta = p.alpha_m - p.alpha_f;
  data.state.a = data.state.qdd;
  if (delta == 0) return;  // rho_inf = 1: a_n = q_ddot_n, the trapezoidal rule
  save_state(data, data.start);
  data.scheme.start_step = true;
  try {
    step(model, data, h);
  } catch (...) {
    data.scheme.start_step = false;
    restore_state(data.start, data);
    throw;
  }
  data.scheme.start_step = false;
  data.vstar = data.state.qdd;  // q_ddot_1 (vstar: the projections' work, free between steps)
  restore_state(data.start, data);
  data.state.a = data.state.qdd + delta * (data.vstar - data.state.qdd);
  --data.stats.steps;  // not a step of the run
}

void set_step_predictors(const Model& model, Data& data) {
  const StepCoefficients& k = data.state.k;
  const double h = k.h;
  if (trapezoidal(model, data)) {
    const double h2 = h * h;
    data.qd_hat = -(2.0 / h) * data.q0 - data.qd0;
    data.qdd_hat = -(4.0 / h2) * data.q0 - (4.0 / h) * data.qd0 - data.qdd0;
    return;
  }
  const AlphaParameters p = AlphaParameters::from_spectral_radius(model.settings.spectral_radius);
  VectorXd& a = data.state.a;
  // a_{n+1} = q / (beta h^2) + base, base = -(q_n + h q_dot_n + h^2 (1/2 - beta) a_n) / (beta h^2);
  // data.tmp holds base (free at this point of the step).
  const double bh2 = p.beta * h * h;
  data.tmp = (-1.0 / bh2) * data.q0 - (h / bh2) * data.qd0 - ((0.5 - p.beta) / p.beta) * a;
  data.qd_hat = data.qd0 + (h * (1 - p.gamma)) * a + (h * p.gamma) * data.tmp;
  data.qdd_hat = ((1 - p.alpha_m) / (1 - p.alpha_f)) * data.tmp + (p.alpha_m / (1 - p.alpha_f)) * a -
                 (p.alpha_f / (1 - p.alpha_f)) * data.qdd0;
}

void finish_step_scheme(const Model& model, Data& data) {
  if (trapezoidal(model, data)) return;
  const AlphaParameters p = AlphaParameters::from_spectral_radius(model.settings.spectral_radius);
  data.state.a = ((1 - p.alpha_f) / (1 - p.alpha_m)) * data.state.qdd + (p.alpha_f / (1 - p.alpha_m)) * data.qdd0 -
                  (p.alpha_m / (1 - p.alpha_m)) * data.state.a;
}

double local_error(const Model& model, const Data& data) {
  const SolverSettings& s = model.settings;
  const double h = data.state.k.h;
  // Local errors (exact minus computed) for a smooth solution: the Taylor predictor's
  // -h^3/6 q''' against the scheme's. Trapezoidal: q_{n+1} = q_n + h q_dot_n + h^2/4 (q_ddot_n +
  // q_ddot_{n+1}) is off by +h^3/12 q''', so the converged minus the predicted coordinates are
  // h^3/4 q''' and the error a third of it. Generalized-alpha (a_n ~ q_ddot(t_n + delta h),
  // delta = alpha_m - alpha_f): the step adds h^3 (delta/2 + beta) q''' where the exact solution
  // adds h^3/6 q''', so error / difference = |1/6 - (delta/2 + beta)| / (delta/2 + beta).
  double ratio = 1.0 / 3.0;
  if (s.integrator == Integrator::GeneralizedAlpha) {
    const AlphaParameters p = AlphaParameters::from_spectral_radius(s.spectral_radius);
    const double c = 0.5 * (p.alpha_m - p.alpha_f) + p.beta;
    ratio = std::abs(1.0 / 6.0 - c) / c;
  }
  const double atol = s.atol >= 0 ? s.atol : s.rtol * model.length;
  const double L = model.length;
  // Error per unit step: the step's share of the tolerance is h / (end - start), so that the
  // local errors of the whole run add up to at most the tolerance (FORMULATION.md section 9).
  const double share = s.end > s.start ? h / (s.end - s.start) : 1.0;
  double worst = 0;
  const auto measure = [&](int i, double unit) {
    const double pred = data.q0(i) + h * data.qd0(i) + 0.5 * h * h * data.qdd0(i);
    const double e = ratio * std::abs(data.state.q(i) - pred) * unit;
    const double size = std::max(std::abs(data.q0(i)), std::abs(data.state.q(i))) * unit;
    worst = std::max(worst, e / ((atol + s.rtol * size) * share));
  };
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!data.integrated[b]) continue;  // a driven body follows its drive exactly
    const Body& body = model.bodies[b];
    const int o = body.offset;
    for (int i = 0; i < 3; ++i) measure(o + i, 1.0);
    // A frame vector's error moves a point at the model length by L times it.
    if (!(body.frame_locked && !data.unknowns.empty()))
      for (int i = 3; i < 12; ++i) measure(o + i, L);
    // A modal amplitude of y_scale moves the body's points by about the model length.
    for (int k = 0; k < body.nq; ++k) measure(o + 12 + k, L / body.y_scale(k));
  }
  return worst;
}

}  // namespace ffr::runtime
