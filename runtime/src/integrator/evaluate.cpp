// Shared evaluation and the tangent of the ALI3-P Newton iteration.
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "tangent_blocks.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace ffr::runtime {

void evaluate(const Model& model, Data& data, double t, Scope scope) {
  update_bodies(model, data, scope);
  update_markers(model, data, scope);
  mass_matrices(model, data);
  generalized_forces(model, data, t);
  evaluate_constraints(model, data, t, scope);
}

// W, T and the factorisation cover the unknowns only: the leading nf x nf blocks.
void refresh_tangent(const Model& model, Data& data, double t, const VectorXd& lam, bool modal_acceleration) {
  const StepCoefficients& k = data.state.k;  // kv = h/2, kq = h^2/4 for the trapezoidal rule
  const int nf = data.nf;
  force_tangents(model, data, t);
  auto W = data.W.topLeftCorner(nf, nf);
  const auto combine = [&](int r0, int nr, int c0, int nc) {
    data.W.block(r0, c0, nr, nc) = k.kv * data.C.block(r0, c0, nr, nc) + k.kq * data.K.block(r0, c0, nr, nc);
  };
  // Over the tangent blocks where that pays (tangent_blocks.hpp): W, C, K and M are zero outside
  // them. A body's own blocks take M in the same pass.
  if (data.tangent_blocks_pay)
    detail::for_each_pair_block(model, data, true, combine);
  else
    W = k.kv * data.C.topLeftCorner(nf, nf) + k.kq * data.K.topLeftCorner(nf, nf);  // one pass
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    if (!data.integrated[i]) continue;
    auto Wb = W.block(b.offset, b.offset, b.ncoord(), b.ncoord());
    const MatrixXd& M = data.bodies[i].M;
    if (data.tangent_blocks_pay) {
      detail::for_each_body_block(model, data, static_cast<int>(i), [&](int r0, int nr, int c0, int nc) {
        W.block(r0, c0, nr, nc) = k.kv * data.C.block(r0, c0, nr, nc) + k.kq * data.K.block(r0, c0, nr, nc) +
                                  M.block(r0 - b.offset, c0 - b.offset, nr, nc);
      });
    } else {
      Wb += M;
    }
    body_stiffening_rate_tangents(b, data.bodies[i], data.state.q.segment(b.offset + 12, b.nq), data.state.qd.segment(b.offset + 12, b.nq),
                                  k.kv, Wb);
  }
  refresh_constraint_tangent(model, data, lam, modal_acceleration);
}

namespace {

// T = W over the unknowns' tangent blocks (both zero outside them), or whole where that is cheaper.
void copy_tangent_blocks(const Model& model, Data& data) {
  if (!data.tangent_blocks_pay) {
    data.T.topLeftCorner(data.nf, data.nf) = data.W.topLeftCorner(data.nf, data.nf);
    return;
  }
  detail::for_each_tangent_block(model, data, true, [&](int r0, int nr, int c0, int nc) {
    data.T.block(r0, c0, nr, nc) = data.W.block(r0, c0, nr, nc);
  });
}

}  // namespace

void refresh_constraint_tangent(const Model& model, Data& data, const VectorXd& lam, bool modal_acceleration) {
  const double kq = data.state.k.kq;
  // The rows' penalties data.alpha were set by step() at its start.
  copy_tangent_blocks(model, data);
  add_penalty_tangent(model, data, data.alpha, kq, data.T);
  // The constraint forces' own derivative, with the multipliers of the current iterate.
  add_constraint_hessian(model, data, lam, kq, data.T);
  // The inertia forces' derivative through the modal masses at the iterate's accelerations: like
  // the constraint Hessian it depends on the iterate, so it is rebuilt here, not kept in W.
  if (modal_acceleration) add_modal_acceleration_tangent(model, data, kq, data.T);
  factorize_tangent(data);
  data.tangent_valid = true;
  data.tangent_metric_only = false;
  ++data.stats.factorizations;
}

void factorize_metric(const Model& model, Data& data) {
  copy_tangent_blocks(model, data);
  add_penalty_tangent(model, data, data.alpha, data.state.k.kq, data.T);
  factorize_tangent(data);
  // Not Newton's tangent: a step that would keep it (reuse_jacobian) builds its own.
  data.tangent_valid = false;
  data.tangent_metric_only = true;
  ++data.stats.factorizations;
}

namespace {

// Rows lo .. hi (positions among the factorised unknowns) of the scaled tangent's column of
// coordinate j, S T S, into out, along runs of positions over consecutive coordinates (each
// position at + i holds coordinate first + i), so the inner loops are contiguous (an
// element-wise indexed gather cost as much as a third of the factorisation).
void gather_column(const Data& data, const std::vector<Data::Run>& runs, int j, int lo, int hi, double* out) {
  const double* s = data.scale.data();
  const double* t = data.T.col(j).data();
  const double sj = s[j];
  for (const Data::Run& run : runs) {
    const int from = std::max(run.at, lo), to = std::min(run.at + run.len - 1, hi);
    for (int i = from; i <= to; ++i) out[i] = s[run.first + i - run.at] * t[run.first + i - run.at] * sj;
  }
}

// The scaled tangent over the unknowns in the factorisation's order (Data::lu_runs), each
// column between its rows Data::lu_first .. lu_last (tangent_blocks.hpp: T is zero outside
// them, which a debug build checks), factorised.
void factorize_within_spans(Data& data) {
  const int* first = data.lu_first.data();
  const int* last = data.lu_last.data();
  const Eigen::Index k = data.unknowns.empty() ? data.nf : static_cast<Eigen::Index>(data.unknowns.size());
  data.lu.compute_within(k, first, last, [&](SmallLU::MatrixMap& a) {
    for (const Data::Run& run : data.lu_runs)
      for (int c = 0; c < run.len; ++c) {
        const int j = run.at + c;
        gather_column(data, data.lu_runs, run.first + c, first[j], last[j], a.col(j).data());
      }
  });
#ifndef NDEBUG
  // Along the runs (position at + c holds coordinate first + c): no allocation, as in Release.
  for (const Data::Run& cr : data.lu_runs)
    for (int c = 0; c < cr.len; ++c) {
      const int j = cr.at + c;
      for (const Data::Run& rr : data.lu_runs)
        for (int r = 0; r < rr.len; ++r) {
          const int i = rr.at + r;
          if (i < first[j] || i > last[j]) assert(data.T(rr.first + r, cr.first + c) == 0.0 && "a tangent term outside its blocks");
        }
    }
#endif
}

}  // namespace

void factorize_tangent(Data& data) {
  const int nf = data.nf;
  // Whole-vector square roots and divisions (vectorised): the same values as 1 / sqrt(d) entry
  // by entry, a third of the cost of that scalar loop.
  const auto d = data.T.diagonal().head(nf).array().abs();
  data.scale.head(nf) = (d > 0).select(d.sqrt().inverse(), 1.0);
  if (data.tangent_blocks_pay) {
    factorize_within_spans(data);
    return;
  }
  if (!data.unknowns.empty()) {  // the unknowns' rows and columns only (Data::unknowns)
    const auto k = static_cast<Eigen::Index>(data.unknowns.size());
    data.lu.compute_filled(k, [&](SmallLU::MatrixMap& a) {
      for (Eigen::Index j = 0; j < k; ++j)
        gather_column(data, data.unknown_runs, data.unknowns[static_cast<std::size_t>(j)], 0, static_cast<int>(k) - 1, a.col(j).data());
    });
    return;
  }
  const auto S = data.scale.head(nf).asDiagonal();
  data.lu.compute(S * data.T.topLeftCorner(nf, nf) * S);
}

void solve_tangent(Data& data, const VectorXd& rhs, VectorXd& out) {
  ++data.stats.solves;
  const int nf = data.nf;
  // The coordinates of driven bodies are not unknowns: no change there.
  out.tail(out.size() - nf).setZero();
  // A singular tangent gives a non-finite direction, which the callers report.
  if (!data.lu.ok()) {
    out.head(nf).setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  // Gathered to the unknowns in the factorisation's order, solved, scattered back.
  const std::vector<Data::Run>* runs = data.tangent_blocks_pay ? &data.lu_runs : data.unknowns.empty() ? nullptr : &data.unknown_runs;
  if (runs) {
    const double* s = data.scale.data();
    double* w = data.lu_work.data();
    for (const Data::Run& run : *runs)
      for (int r = 0; r < run.len; ++r) w[run.at + r] = s[run.first + r] * rhs(run.first + r);
    data.lu.solve_in_place(data.lu_work);
    out.head(nf).setZero();  // the known frame vectors do not move
    for (const Data::Run& run : *runs)
      for (int r = 0; r < run.len; ++r) out(run.first + r) = s[run.first + r] * w[run.at + r];
    return;
  }
  out.head(nf) = data.scale.head(nf).cwiseProduct(rhs.head(nf));
  data.lu.solve_in_place(out);
  out.head(nf).array() *= data.scale.head(nf).array();
}

double scaled_norm(const Model& model, const VectorXd& dq) {
  return dq.size() == 0 ? 0.0 : dq.cwiseAbs().cwiseProduct(model.increment_weight).maxCoeff();
}

}  // namespace ffr::runtime
