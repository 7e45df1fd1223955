#pragma once
// Time integration: the index-3 augmented Lagrangian formulation with mass-orthogonal
// projections of velocities and accelerations (ALI3-P) (Bayo & Ledesma 1996; Cuadrado, Cardenal,
// Morer & Bayo 2000), with the trapezoidal rule or generalized-alpha (scheme.hpp), fixed or
// adaptive steps (step_control.hpp). FORMULATION.md section 9.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

#include <functional>
#include <string>
#include <vector>

namespace ffr::runtime {

/// Everything at the current state: kinematics, mass matrices, forces Q, constraints (with
/// Scope::Unknowns, the bodies, markers and rows of the unknowns alone, see Scope).
void evaluate(const Model& model, Data& data, double t, Scope scope = Scope::All);

/// Makes the initial state consistent (FORMULATION.md section 10): positions with the joints and
/// motions at the start time (mass-weighted least change), velocities likewise, then the
/// accelerations and multipliers from the equations of motion. Returns what it changed, as
/// sentences for the caller to show. Throws SolverError if the constraints cannot be met.
std::vector<std::string> initialize(const Model& model, Data& data);

/// One step of settings.step from data.state.t. Throws SolverError when Newton does not converge.
/// Allocation-free.
void step(const Model& model, Data& data);
/// One step of h from data.state.t (adaptive steps, step_control.cpp); the same otherwise.
void step(const Model& model, Data& data, double h);

/// Which coordinates are the step's unknowns: every body's (eliminate = false: what the
/// initial conditions need, every body being moved into place) or, with the model's driven
/// bodies eliminated, the integrated bodies' only; then each driven body's present pose becomes
/// its drive's reference (DriveReference) and it follows its drive from here on.
void set_unknowns(const Model& model, Data& data, bool eliminate);

/// Positions, rates and accelerations of the driven bodies at time t, from their drives (while
/// they are eliminated; nothing otherwise). Allocation-free.
void drive_bodies(const Model& model, Data& data, double t);

/// The largest violation of the constraints among driven bodies and the ground (the rows after
/// data.na), relative to the model length, and the block that has it (-1 when none).
double driven_violation(const Model& model, const Data& data, int& block);

/// Replaces the frame vectors of the predictor data.state.q by each body's frame at the step start
/// (data.q0) turned by the rotation its angular velocity and acceleration predict.
/// Allocation-free.
void predict_frames(const Model& model, Data& data);

/// Projects data.state.qd (then data.state.qdd) onto the velocity (acceleration) constraints in the metric
/// of the last factorised tangent. Needs evaluate() at the current q. Returns the scaled residual.
/// A projection that does not converge (after a fresh tangent and the metric alone) throws a
/// SolverError, or, for the velocities with must_converge = false, returns infinity.
double project_velocities(const Model& model, Data& data, double t, bool must_converge = true);
double project_accelerations(const Model& model, Data& data, double t);

/// Factorises T = W + kq (alpha Phi_q^T Phi_q + sum lam_i Phi_i,qq) with W = M + kv C + kq K
/// (the scheme's coefficients, scheme.hpp: h/2 and h^2/4 for the trapezoidal rule) at the current state (lam: the multipliers to use in the constraints' second derivatives;
/// alpha: the step's penalties, which step() sets). Without modal_acceleration, the inertia
/// forces' derivative through the modal masses at the current accelerations is left out.
void refresh_tangent(const Model& model, Data& data, double t, const VectorXd& lam, bool modal_acceleration = true);
/// The same with the W of the last refresh: only the constraint terms are rebuilt at the
/// current state (what a tangent built a little way off misses most, see step()).
void refresh_constraint_tangent(const Model& model, Data& data, const VectorXd& lam, bool modal_acceleration = true);

/// Factorises the projections' own matrix T = W + h^2/4 alpha Phi_q^T Phi_q with the W of the
/// last refresh (without the constraints' second derivatives, with which the projection passes
/// are a modified Newton iteration that need not converge).
void factorize_metric(const Model& model, Data& data);

/// Factorises data.T after symmetric diagonal scaling S T S, S = diag(|T_ii|^-1/2). The tangent
/// mixes masses (down to ~1e-6 for a bar's section inertia) with h^2/4 K of stiff modes and the
/// penalty (~1e5): unscaled, partial pivoting loses most digits and Newton converges slowly.
void factorize_tangent(Data& data);
/// out = T^-1 rhs with the scaled factorisation (out and rhs distinct).
void solve_tangent(Data& data, const VectorXd& rhs, VectorXd& out);

/// The multipliers mu of the rows of the unknowns with Phi_a T^-1 Phi_a^T mu = c (T the factorised
/// tangent at hand), zero on rows that are numerically combinations of others (exact_multipliers.cpp).
/// factor_exact_multipliers builds Y = T^-1 Phi_a^T (data.projY; a correction T^-1 Phi_a^T mu is
/// Y mu) and factorises S = Phi_a Y, returning its rank; solve_exact_multipliers then gives mu
/// (data.proj_mu) for a c that is neither data.r nor data.tmp.
int factor_exact_multipliers(Data& data);
void solve_exact_multipliers(Data& data, const VectorXd& c);
/// Their factorisation, for any such S (k x k, symmetric positive semi-definite, both triangles
/// stored; the relative step's projections use it too): S(p, p) = L L^T in place (L in S's lower
/// triangle), stopped where the rows left are combinations of the others up to round-off; returns
/// the rank. `order` (k entries) and `own` (k) are work. pivoted_cholesky_solve: mu [k] with
/// S mu = c on the independent rows, zero on the others (w [k]: work).
int pivoted_cholesky(Eigen::Ref<MatrixXd> S, std::vector<int>& order, VectorXd& own);
void pivoted_cholesky_solve(const Eigen::Ref<const MatrixXd>& S, const std::vector<int>& order, int rank, const VectorXd& c, VectorXd& w,
                            VectorXd& mu);

/// Scaled infinity norm of a coordinate increment: each coordinate by its inertia weight
/// (Model::increment_weight), i.e. in model lengths of the displacement of its body's mass.
double scaled_norm(const Model& model, const VectorXd& dq);

}  // namespace ffr::runtime
