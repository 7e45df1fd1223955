// The relative step's projections of s_dot and s_ddot onto the kept rows (solves.hpp), in the
// metric F = Tm of the last refresh (R^T W R with the constraints' terms, kq Phis^T alpha Phis
// among them: the passes below are Cuadrado's projection repeated).
//
// A pass x <- x - F^-1 kq Phis^T alpha (Phis x + b) multiplies the residual by
// (I + kq alpha S_A)^-1, S_A = Phis A^-1 Phis^T with A = F - kq Phis^T alpha Phis: along an
// eigenvector of S_A of eigenvalue s it shrinks by 1 / (1 + kq alpha s) a pass. Where kept rows
// are nearly redundant s is tiny and the passes crawl: the planar slider-crank modelled in 3-D
// holds the rod's out-of-plane rotations at both of its nodes (the revolute it hangs on and the
// cut joint), which a rigid rod satisfies together and a flexible one only through its stiff
// torsion and out-of-plane modes (kq K of the highest modes far above the penalty), so s is
// small there. With 30 modes of the consistent rod the velocity projection stopped at the pass
// limit (tools/bench/formulations/RESULTS.md), as passes at such a rate would. The absolute
// step solves the same case directly when its passes stall (projection.cpp, exact_multipliers.cpp);
// so does this one: with Y = F^-1 Phis^T on the kept rows and S = Phis Y, the correction
// x <- x - Y mu, S mu = Phis x + b meets the kept rows exactly and is the projection in the
// metric A (F (x - x*) = -Phis^T mu, so A (x - x*) = -Phis^T (mu - kq alpha c*)); S is factorised
// by the pivoted Cholesky of exact_multipliers.cpp (nearly redundant rows keep a zero multiplier)
// and the solve refined with its residual.
#include "solves.hpp"

#include "ffr/runtime/integrator.hpp"

#include <cmath>

namespace ffr::runtime {
namespace {

using namespace relative_detail;

// The residual of the kept rows at x, into w.c, in model lengths times `scale`.
double residual(const Model& model, RelativeWork& w, const VectorXd& x, const VectorXd& b, double scale) {
  phis_times(model, w, x, w.c);
  w.c += b.cwiseProduct(w.keep);
  return w.c.size() > 0 ? w.c.cwiseAbs().maxCoeff() * scale / model.length : 0.0;
}

double project_exact(const Model& model, Data& data, VectorXd& x, const VectorXd& b, double scale) {
  RelativeWork& w = *data.relative;
  const int k = static_cast<int>(w.kept.size());
  constexpr int refinements = 3;
  const int rank = factor_kept_multipliers(w, data, true, false);
  const auto S = w.projS.topLeftCorner(k, k);
  double res = residual(model, w, x, b, scale);
  for (int round = 0; round <= refinements && res >= model.settings.tolerance; ++round) {
    for (int i = 0; i < k; ++i) w.proj_c(i) = w.c(w.kept[static_cast<std::size_t>(i)]);
    pivoted_cholesky_solve(S, w.proj_order, rank, w.proj_c, w.proj_w, w.proj_mu);
    x.noalias() -= w.projY.leftCols(k) * w.proj_mu.head(k);
    res = residual(model, w, x, b, scale);
    if (!std::isfinite(res)) break;
  }
  return res;
}

}  // namespace

double relative_project(const Model& model, Data& data, VectorXd& x, const VectorXd& b, double scale) {
  RelativeWork& w = *data.relative;
  const double kq = data.state.k.kq;
  // The passes' limit, and the shrink of the residual a pass slower than which the direct
  // solve takes over (from the fourth pass on: the first ones also take the components of x*
  // that the metric moves at once).
  constexpr int max_passes = 50, first_check = 3;
  constexpr double slow = 0.5;
  double res = residual(model, w, x, b, scale), prev = res;
  for (int pass = 0; pass < max_passes; ++pass) {
    if (res < model.settings.tolerance || !std::isfinite(res)) return res;
    if (pass >= first_check && res > slow * prev) break;
    w.r = data.alpha.cwiseProduct(w.c);
    w.f.setZero();
    add_phis_t(model, w, w.r, kq, w.f);
    solve_metric(w, data, w.f, w.ds);
    x -= w.ds;
    prev = res;
    res = residual(model, w, x, b, scale);
  }
  if (res < model.settings.tolerance || !std::isfinite(res)) return res;
  return project_exact(model, data, x, b, scale);
}

}  // namespace ffr::runtime
