#pragma once
// The time-integration scheme of the index-3 step (FORMULATION.md section 9): the trapezoidal
// rule or the generalized-alpha method, both written so that the end-of-step rates are affine in
// the end-of-step coordinates,
//
//   q_dot = c1 q + qd_hat,   q_ddot = c2 q + qdd_hat,
//
// which is all the Newton iteration, its tangent and the projections need (they use
// kv = c1 / c2 and kq = 1 / c2 where the trapezoidal rule has h/2 and h^2/4).

#include <Eigen/Core>

namespace ffr::runtime {

struct Model;
struct Data;

/// The coefficients of one step.
struct StepCoefficients {
  double h = 0;       ///< the step
  double h_prev = 0;  ///< the step before (predictor extrapolation), h at the first step
  double c1 = 0, c2 = 0;
  double kv = 0;      ///< c1 / c2: factor of the damping tangent C in W (h/2 trapezoidal)
  double kq = 0;      ///< 1 / c2: factor of K, the penalty and the constraint Hessian (h^2/4)
};

/// Generalized-alpha parameters from the spectral radius at infinite frequency (Chung &
/// Hulbert 1993): alpha_m = (2 rho - 1) / (rho + 1), alpha_f = rho / (rho + 1),
/// gamma = 1/2 - alpha_m + alpha_f, beta = 1/4 (1 - alpha_m + alpha_f)^2.
struct AlphaParameters {
  double alpha_m = 0.5, alpha_f = 0.5, beta = 0.25, gamma = 0.5;
  static AlphaParameters from_spectral_radius(double rho_inf);
};

/// The scheme's mode. Its state beyond (q, q_dot, q_ddot, lambda) — the step's coefficients and
/// the pseudo-acceleration `a` of the generalized-alpha recurrence — is in State (state.hpp).
struct SchemeState {
  /// Set while the generalized-alpha start takes its trapezoidal step (start_generalized_alpha):
  /// the scheme's functions then act as the trapezoidal rule's.
  bool start_step = false;
};

/// Sets data.state.k for a step of h from data.state.t (and remembers the previous step).
void set_step_coefficients(const Model& model, Data& data, double h);
/// The trapezoidal coefficients for h: the metric the initial conditions' projections use.
StepCoefficients trapezoidal_coefficients(double h);

/// The generalized-alpha start, before the first step of h from a consistent state (t_0, q_0,
/// q_dot_0, q_ddot_0, lambda_0): a_0 = q_ddot(t_0 + delta h) + O(h^2), delta = alpha_m - alpha_f,
/// as q_ddot_0 + delta (q_ddot_1 - q_ddot_0) with q_ddot_1 from one trapezoidal step of h (whose
/// accelerations are second order), the state then restored (data.start). Throws SolverError
/// when that step's Newton fails. Allocation-free.
void start_generalized_alpha(const Model& model, Data& data, double h);

/// data.qd_hat and data.qdd_hat from the start-of-step state (data.q0, qd0, qdd0 and, for
/// generalized-alpha, data.state.a). Allocation-free.
void set_step_predictors(const Model& model, Data& data);

/// After the projections: advances the pseudo-acceleration with the projected accelerations,
/// (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) q_ddot_{n+1} + alpha_f q_ddot_n.
/// Allocation-free.
void finish_step_scheme(const Model& model, Data& data);

/// The estimated local error of the step just taken per unit step, in units of the tolerances
/// (accept when <= 1): the difference between the converged coordinates and the second-order
/// Taylor predictor q0 + h qd0 + h^2/2 qdd0 times the scheme's ratio of error constants
/// (scheme_coefficients.cpp), each coordinate measured as a displacement in metres against the
/// step's share h / (end - start) of atol + rtol |q|, so that the local errors of a run add up
/// to at most atol + rtol |q|. Positions, frame vectors and modal coordinates of the integrated
/// bodies only.
double local_error(const Model& model, const Data& data);

}  // namespace ffr::runtime
