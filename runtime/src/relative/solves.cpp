// The relative step's solves and products with Phis (solves.hpp).
#include "solves.hpp"

#include "ffr/runtime/integrator.hpp"

namespace ffr::runtime::relative_detail {

namespace {

// out = D LU^-1 D rhs for the factor of D T D (D = diag(scale)).
template <class Lu>
void scaled_solve(Lu& lu, const VectorXd& scale, Data& data, const VectorXd& rhs, VectorXd& out) {
  ++data.stats.solves;
  out = scale.cwiseProduct(rhs);
  lu.solve_in_place(out);
  out.array() *= scale.array();
}

}  // namespace

void solve(RelativeWork& w, Data& data, const VectorXd& rhs, VectorXd& out) { scaled_solve(w.lu, w.scale, data, rhs, out); }

// The same with the projections' metric (refresh): the tangent without the rate and curvature
// terms, factorised when first needed after a refresh.
void solve_metric(RelativeWork& w, Data& data, const VectorXd& rhs, VectorXd& out) {
  if (!w.exact_tangent) return solve(w, data, rhs, out);
  if (w.metric_stale) {
    const auto d = w.Tm.diagonal().array().abs();
    w.scale_m = (d > 0).select(d.sqrt().inverse(), 1.0);
    w.lu_m.compute(w.scale_m.asDiagonal() * w.Tm * w.scale_m.asDiagonal());
    ++data.stats.factorizations;
    w.metric_stale = false;
  }
  scaled_solve(w.lu_m, w.scale_m, data, rhs, out);
}

int factor_kept_multipliers(RelativeWork& w, Data& data, bool metric, bool symmetrise) {
  const int k = static_cast<int>(w.kept.size());
  for (int i = 0; i < k; ++i) {
    w.y = w.Phis.row(w.kept[static_cast<std::size_t>(i)]).transpose();
    if (metric) solve_metric(w, data, w.y, w.y);
    else solve(w, data, w.y, w.y);
    w.projY.col(i) = w.y;
  }
  auto S = w.projS.topLeftCorner(k, k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) S(j, i) = w.Phis.row(w.kept[static_cast<std::size_t>(j)]).dot(w.projY.col(i));
  if (symmetrise)
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) S(j, i) = S(i, j) = 0.5 * (S(j, i) + S(i, j));
  return pivoted_cholesky(S, w.proj_order, w.proj_own);
}

// out(kept rows) = Phis v, each block over its nonzero columns.
void phis_times(const Model& model, RelativeWork& w, const VectorXd& v, VectorXd& out) {
  const RelativeTree& t = *model.relative;
  out.setZero();
  for (std::size_t kb = 0; kb < t.kept_blocks.size(); ++kb) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(t.kept_blocks[kb])];
    const int lo = w.span_lo[kb], len = w.span_hi[kb] - lo;
    out.segment(b.row0, b.rows).noalias() = w.Phis.block(b.row0, lo, b.rows, len) * v.segment(lo, len);
  }
}

// out += factor Phis^T lam over the kept rows, likewise.
void add_phis_t(const Model& model, RelativeWork& w, const VectorXd& lam, double factor, VectorXd& out) {
  const RelativeTree& t = *model.relative;
  for (std::size_t kb = 0; kb < t.kept_blocks.size(); ++kb) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(t.kept_blocks[kb])];
    const int lo = w.span_lo[kb], len = w.span_hi[kb] - lo;
    out.segment(lo, len).noalias() += factor * (w.Phis.block(b.row0, lo, b.rows, len).transpose() * lam.segment(b.row0, b.rows));
  }
}

}  // namespace ffr::runtime::relative_detail
