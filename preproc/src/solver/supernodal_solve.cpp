// Supernodal forward and back substitution (see supernodal_solve.hpp for why).
//
// CHOLMOD's supernodal structure: supernode s holds columns k1 = super[s] .. k2 = super[s+1] - 1
// of L on nsrow = pi[s+1] - pi[s] rows; its row indices rows[pi[s] ..] start with k1 .. k2 - 1
// (the lower triangle L11 on top), followed by the nsrow - nscol rows of the rectangular L21
// below. The values are packed (factor_packing.hpp): from values + px[s], in stripes of kStripe
// columns, stripe t from row kStripe t down, row by row (panel_columns below finds a panel's).
//
// Forward (L y = P b), supernodes in order:  y1 <- L11^-1 y1,   y[rows of L21] -= L21 y1.
// Back (L^T z = y), in reverse order:        y1 <- L11^-T (y1 - L21^T y[rows of L21]).
// Both sweep the columns of a supernode in panels of eight (a stripe, panels::kPanel): each
// step reads the panel's rows of L once and applies them to all right-hand sides of the
// interleaved block. The forward sweep reads the packed values as one ascending stream, the back
// sweep (rows from the last, in each panel) as one descending stream.
#include "supernodal_solve.hpp"

#include "../run_parts.hpp"
#include "factor_packing.hpp"
#include "kernel_clones.hpp"
#include "supernodal_panels.hpp"

#include <algorithm>
#include <cassert>

// The kernels are compiled for AVX2/FMA and AVX-512 as well (kernel_clones.hpp): with the
// right-hand sides interleaved, one fused multiply-add per factor entry keeps up with memory,
// where the baseline SSE2 code needs four instructions per entry and does not.

namespace ffr::preproc::detail {
namespace {

using Index = std::int64_t;

using View = SupernodalView;

using panels::dot_p;
using panels::kPanel;
using panels::update_p;

// The packed values of a panel of supernode s starting at column j0 (a multiple of the panel
// width, which divides kStripe): L(i, j0 + q) = at(i, q) for the rows i >= r0 its stripe holds,
// rows rs apart (the stripe's width).
struct PanelColumns {
  const double* L;  // L(r0, j0)
  Index rs, r0;
  const double* row(Index i) const { return L + (i - r0) * rs; }
  double at(Index i, Index q) const { return L[(i - r0) * rs + q]; }
};

inline PanelColumns panel_columns(const View& v, Index s, Index nscol, Index nsrow, Index j0) {
  const Index t = j0 / kStripe, r0 = kStripe * t;
  return {v.values + v.px[s] + stripe_offset(nsrow, t) + (j0 - r0), std::min(kStripe, nscol - r0), r0};
}

// Forward step of supernode s. Updates to rows with a slot (the top of a threaded sweep, see
// solve_schedule.hpp) go to the accumulator acc instead of y.
template <int W>
void forward_node(const View& v, Index s, double* y, double* t, const std::int32_t* slot, double* acc) {
  const Index k1 = v.super[s], nscol = v.super[s + 1] - k1;
  const Index nsrow = v.pi[s + 1] - v.pi[s], m = nsrow - nscol;
  const SuiteSparse_long* below = v.rows + v.pi[s] + nscol;
  double* yd = y + k1 * W;
  std::fill(t, t + m * W, 0.0);
  constexpr int kP = kPanel;
  static_assert(kStripe % kP == 0, "a panel must lie in one stripe");
  for (Index j0 = 0; j0 < nscol; j0 += kP) {
    const int p = static_cast<int>(std::min<Index>(kP, nscol - j0));
    const PanelColumns L = panel_columns(v, s, nscol, nsrow, j0);
    // The panel's own triangle.
    for (int q = 0; q < p; ++q) {
      const Index j = j0 + q;
      double* yj = yd + j * W;
      const double d = L.at(j, q);
      for (int c = 0; c < W; ++c) yj[c] /= d;
      for (int r = q + 1; r < p; ++r) {
        const double l = L.at(j0 + r, q);
        for (int c = 0; c < W; ++c) yd[(j0 + r) * W + c] -= l * yj[c];
      }
    }
    // The rest of L11 below the panel, then L21 into the update rows.
    update_p<W>(p, L.row(j0 + p), L.rs, nscol - j0 - p, yd + j0 * W, yd + (j0 + p) * W);
    update_p<W>(p, L.row(nscol), L.rs, m, yd + j0 * W, t);
  }
  for (Index i = 0; i < m; ++i) {
    const Index r = below[i];
    double* yi = slot && slot[r] >= 0 ? acc + static_cast<Index>(slot[r]) * W : y + r * W;
    for (int c = 0; c < W; ++c) yi[c] += t[i * W + c];
  }
}

// Back step of supernode s: reads the rows below its diagonal block, writes its own.
template <int W>
void backward_node(const View& v, Index s, double* y, double* t) {
  const Index k1 = v.super[s], nscol = v.super[s + 1] - k1;
  const Index nsrow = v.pi[s + 1] - v.pi[s], m = nsrow - nscol;
  const SuiteSparse_long* below = v.rows + v.pi[s] + nscol;
  double* yd = y + k1 * W;
  for (Index i = 0; i < m; ++i) {
    const double* yi = y + below[i] * W;
    for (int c = 0; c < W; ++c) t[i * W + c] = yi[c];
  }
  // Panels from the last: the rows below a panel are final when it is reached.
  constexpr int kP = kPanel;
  const Index last = ((nscol - 1) / kP) * kP;
  for (Index j0 = last; j0 >= 0; j0 -= kP) {
    const int p = static_cast<int>(std::min<Index>(kP, nscol - j0));
    const PanelColumns L = panel_columns(v, s, nscol, nsrow, j0);
    dot_p<W>(p, L.row(nscol), L.rs, m, t, yd + j0 * W);
    dot_p<W>(p, L.row(j0 + p), L.rs, nscol - j0 - p, yd + (j0 + p) * W, yd + j0 * W);
    for (int q = p - 1; q >= 0; --q) {
      const Index j = j0 + q;
      double* yj = yd + j * W;
      for (int r = q + 1; r < p; ++r) {
        const double l = L.at(j0 + r, q);
        for (int c = 0; c < W; ++c) yj[c] -= l * yd[(j0 + r) * W + c];
      }
      const double d = L.at(j, q);
      for (int c = 0; c < W; ++c) yj[c] /= d;
    }
  }
}

struct Sweep {
  const SupernodeRange* ranges;
  std::size_t count;
  bool forward;
  const std::int32_t* slot;  ///< forward only: redirect updates of the top's rows ...
  double* acc;               ///< ... into this accumulator
};

template <int W>
void sweep_width(const View& v, const Sweep& w, double* y, double* t) {
  if (w.forward) {
    for (std::size_t k = 0; k < w.count; ++k)
      for (Index s = w.ranges[k].first; s <= w.ranges[k].last; ++s) forward_node<W>(v, s, y, t, w.slot, w.acc);
  } else {
    for (std::size_t k = w.count; k-- > 0;)
      for (Index s = w.ranges[k].last; s >= w.ranges[k].first; --s) backward_node<W>(v, s, y, t);
  }
}

// One sweep over a list of supernode ranges for an interleaved block, one clone per
// instruction set.
FFR_KERNEL_CLONES void sweep(const View& v, int width, const Sweep& w, double* y, double* t) {
  switch (width) {
    case 16: sweep_width<16>(v, w, y, t); break;
    case 8: sweep_width<8>(v, w, y, t); break;
    case 4: sweep_width<4>(v, w, y, t); break;
    default: sweep_width<1>(v, w, y, t); break;
  }
}

}  // namespace

SupernodalSolver::SupernodalSolver(const cholmod_factor& L, const double* values,
                                   std::vector<SuiteSparse_long> packed_offsets, unsigned threads)
    : n_(static_cast<std::int64_t>(L.n)),
      perm_(static_cast<const SuiteSparse_long*>(L.Perm)),
      px_(std::move(packed_offsets)),
      view_{static_cast<std::int64_t>(L.nsuper), static_cast<const SuiteSparse_long*>(L.super),
            static_cast<const SuiteSparse_long*>(L.pi), px_.data(),
            static_cast<const SuiteSparse_long*>(L.s), values},
      schedule_(make_solve_schedule(L, threads, kMinParallelEntries)) {
  assert(L.is_super && px_.size() == L.nsuper + 1);
  for (Index s = 0; s < view_.nsuper; ++s) {
    const Index nsrow = view_.pi[s + 1] - view_.pi[s], nscol = view_.super[s + 1] - view_.super[s];
    max_update_rows_ = std::max(max_update_rows_, nsrow - nscol);
  }
  const std::size_t nt = std::max<std::size_t>(1, schedule_.parts.size());
  t_.resize(nt);
  acc_.resize(nt);
}

unsigned SupernodalSolver::threads() const {
  return static_cast<unsigned>(std::max<std::size_t>(1, schedule_.parts.size()));
}

void SupernodalSolver::sweep_block(int width) {
  const View& v = view_;
  double* y = y_.data();
  const SupernodeRange all{0, v.nsuper - 1};
  if (schedule_.parts.empty()) {
    sweep(v, width, Sweep{&all, 1, true, nullptr, nullptr}, y, t_[0].data());
    sweep(v, width, Sweep{&all, 1, false, nullptr, nullptr}, y, t_[0].data());
    return;
  }
  const std::size_t nt = schedule_.parts.size(), ntop = schedule_.top_columns.size();
  // Each part on its own thread (the first on this one); the threads are joined before
  // anything else reads what they wrote.
  auto in_parallel = [&](auto&& body) {
    run_parts(static_cast<unsigned>(nt), [](unsigned p) { return p; },
              [&](unsigned k, unsigned, unsigned) { body(static_cast<std::size_t>(k)); });
  };
  in_parallel([&](std::size_t k) {
    std::fill(acc_[k].begin(), acc_[k].begin() + static_cast<std::ptrdiff_t>(ntop * width), 0.0);
    const auto& part = schedule_.parts[k];
    sweep(v, width, Sweep{part.data(), part.size(), true, schedule_.slot.data(), acc_[k].data()}, y, t_[k].data());
  });
  for (std::size_t i = 0; i < ntop; ++i) {
    double* yi = y + schedule_.top_columns[i] * width;
    for (std::size_t k = 0; k < nt; ++k)
      for (int c = 0; c < width; ++c) yi[c] += acc_[k][i * width + c];
  }
  const auto& top = schedule_.top;
  sweep(v, width, Sweep{top.data(), top.size(), true, nullptr, nullptr}, y, t_[0].data());
  sweep(v, width, Sweep{top.data(), top.size(), false, nullptr, nullptr}, y, t_[0].data());
  in_parallel([&](std::size_t k) {
    const auto& part = schedule_.parts[k];
    sweep(v, width, Sweep{part.data(), part.size(), false, nullptr, nullptr}, y, t_[k].data());
  });
}

void SupernodalSolver::solve(const double* B, std::int64_t ldb, std::int64_t ncols, double* X,
                             std::int64_t ldx) {
  for (Index j0 = 0; j0 < ncols;) {
    const Index left = ncols - j0;
    // Sixteen, eight or four at a time (a last two or three padded with zero columns: the
    // factor is read once either way), and a single column alone.
    const int width = left >= 16 ? 16 : left >= 8 ? 8 : left >= 2 ? 4 : 1;
    const Index k = std::min<Index>(width, left);
    const auto w = static_cast<std::size_t>(width);
    if (y_.size() < static_cast<std::size_t>(n_) * w) y_.resize(static_cast<std::size_t>(n_) * w);
    for (std::size_t p = 0; p < t_.size(); ++p) {
      if (t_[p].size() < static_cast<std::size_t>(max_update_rows_) * w) t_[p].resize(static_cast<std::size_t>(max_update_rows_) * w);
      if (!schedule_.parts.empty() && acc_[p].size() < schedule_.top_columns.size() * w)
        acc_[p].resize(schedule_.top_columns.size() * w);
    }
    double* y = y_.data();
    // The permutations on the threads too: on one they were 32 ms of the 100k-DOF plate's
    // Lanczos stage at two threads (92 solves), the other core waiting.
    const unsigned parts = parts_for(n_ * width, Index{1} << 18);
    const auto split = [&](unsigned p) { return n_ * static_cast<Index>(p) / static_cast<Index>(parts); };
    run_parts(parts, split, [&](unsigned, Index r0, Index r1) {
      for (Index r = r0; r < r1; ++r) {
        const Index src = perm_ ? perm_[r] : r;
        for (Index c = 0; c < width; ++c) y[r * width + c] = c < k ? B[src + (j0 + c) * ldb] : 0.0;
      }
    });
    sweep_block(width);
    run_parts(parts, split, [&](unsigned, Index r0, Index r1) {
      for (Index r = r0; r < r1; ++r) {
        const Index dst = perm_ ? perm_[r] : r;
        for (Index c = 0; c < k; ++c) X[dst + (j0 + c) * ldx] = y[r * width + c];
      }
    });
    j0 += k;
  }
}

}  // namespace ffr::preproc::detail
