#pragma once
// The relative step's linear algebra on its workspace (RelativeWork): solves with the factorised
// tangent and with the projections' metric, products with Phis = Phi_q R on the kept rows, and
// the projections (step.cpp's Newton iteration and its final projections use them).
#include "ffr/runtime/relative.hpp"

namespace ffr::runtime::relative_detail {

/// out = Ts^-1 rhs with the tangent's scaled factorisation (refresh in step.cpp).
void solve(RelativeWork& w, Data& data, const VectorXd& rhs, VectorXd& out);
/// The same with the projections' metric Tm (the tangent without R's rate and curvature terms),
/// factorised when first needed after a refresh; the tangent itself without the exact terms.
void solve_metric(RelativeWork& w, Data& data, const VectorXd& rhs, VectorXd& out);
/// Y = A^-1 Phis^T over the kept rows (w.projY; A the tangent, or with `metric` the projections'
/// metric) and S = Phis Y (w.projS), symmetrised when `symmetrise`, factorised by the pivoted
/// Cholesky of exact_multipliers.cpp; returns its rank (the rows pivoted past it are nearly
/// redundant: they keep a zero multiplier). The direct solves of Newton's direction (step.cpp)
/// and of the projections (projection.cpp).
int factor_kept_multipliers(RelativeWork& w, Data& data, bool metric, bool symmetrise);
/// out(kept rows) = Phis v, zero elsewhere.
void phis_times(const Model& model, RelativeWork& w, const VectorXd& v, VectorXd& out);
/// out += factor Phis^T lam over the kept rows.
void add_phis_t(const Model& model, RelativeWork& w, const VectorXd& lam, double factor, VectorXd& out);

}  // namespace ffr::runtime::relative_detail

namespace ffr::runtime {

/// A projection of x (s_dot or s_ddot) onto Phis x + b = 0 (b on the kept rows) in the metric
/// (projection.cpp); returns the residual left, times `scale` (h for rates, h^2 for
/// accelerations), in model lengths.
double relative_project(const Model& model, Data& data, VectorXd& x, const VectorXd& b, double scale);

}  // namespace ffr::runtime
