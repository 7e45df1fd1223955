#include "node_mass.hpp"

#include "../run_parts.hpp"
#include "../solver/kernel_clones.hpp"

#include <algorithm>

namespace ffr::preproc::detail {
namespace {

// yf += (Ms (x) I3) xf over the nodes, for an upper-only Ms and rows of R = 3 p values a node:
// each stored m_ab (a < b) adds m_ab x_b to y_a and m_ab x_a to y_b. R fixed at compile time
// where the block Lanczos needs it (blocks of four: R = 12, three vectors of four), 0 for any.
template <int R>
void node_product(const SparseMatrix& Ms, Index b0, Index b1, Index r, const double* xf, double* yf) {
  const auto* outer = Ms.outerIndexPtr();
  const auto* inner = Ms.innerIndexPtr();
  const double* val = Ms.valuePtr();
  if constexpr (R > 0) {
    using simd::load;
    using simd::store;
    using simd::v4;
    constexpr int NV = R / 4;
    for (Index b = b0; b < b1; ++b) {
      v4 xb[NV], acc[NV] = {};
      for (int k = 0; k < NV; ++k) xb[k] = load(xf + b * R + 4 * k);
      for (auto e = outer[b]; e < outer[b + 1]; ++e) {
        const Index a = inner[e];
        const double m = val[e];
        if (a < b) {
          for (int k = 0; k < NV; ++k) {
            store(yf + a * R + 4 * k, load(yf + a * R + 4 * k) + m * xb[k]);
            acc[k] += m * load(xf + a * R + 4 * k);
          }
        } else if (a == b) {
          for (int k = 0; k < NV; ++k) acc[k] += m * xb[k];
        }
      }
      for (int k = 0; k < NV; ++k) store(yf + b * R + 4 * k, load(yf + b * R + 4 * k) + acc[k]);
    }
  } else {
    for (Index b = b0; b < b1; ++b)
      for (auto e = outer[b]; e < outer[b + 1]; ++e) {
        const Index a = inner[e];
        const double m = val[e];
        for (Index c = 0; c < r; ++c) yf[b * r + c] += m * xf[a * r + c];
        if (a < b)
          for (Index c = 0; c < r; ++c) yf[a * r + c] += m * xf[b * r + c];
      }
  }
}

FFR_KERNEL_CLONES
void node_product_any(const SparseMatrix& Ms, Index b0, Index b1, Index r, const double* xf, double* yf) {
  switch (r) {
    case 12: node_product<12>(Ms, b0, b1, r, xf, yf); break;
    default: node_product<0>(Ms, b0, b1, r, xf, yf); break;
  }
}

}  // namespace

std::shared_ptr<const NodeMassProduct> NodeMassProduct::make(const FeModel& model, const Assembled& fe,
                                                             const std::vector<Index>& rows) {
  if (fe.has_structural || fe.Ms.nonZeros() == 0 || rows.empty() || fe.Ms.rows() != model.mesh->num_nodes())
    return nullptr;
  std::vector<Index> slot;
  slot.reserve(rows.size());
  for (const Index r : rows) {
    if (r < 0 || r >= model.mesh_dofs()) return nullptr;  // an interface node's DOF
    const Index a = model.dof_node[static_cast<std::size_t>(r)];
    if (model.node_ndof[static_cast<std::size_t>(a)] != 3) return nullptr;
    slot.push_back(3 * a + (r - model.node_dof[static_cast<std::size_t>(a)]));
  }
  return std::shared_ptr<const NodeMassProduct>(new NodeMassProduct(fe.Ms, std::move(slot)));
}

void NodeMassProduct::apply(const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) const {
  const Index n = rows(), p = X.cols(), r = 3 * p;
  const auto size = static_cast<std::size_t>(Ms_.rows() * r);
  // Node a's component c of column k sits at (3 a + c) p + k = slot p + k. The slots of nodes
  // without a row here (held ones) are never written, so xf's zeros from its sizing stay: their
  // columns of Ms (x) I3 are not M's.
  if (xf_.size() != size) xf_.assign(size, 0.0);
  yf_.resize(size);
  // The gather, the zeroing and (below) the scatter on the threads too: on one thread they
  // were 58 ms of the 100k-DOF plate's Lanczos stage at two threads, the other core waiting.
  const unsigned row_parts = parts_for(n * p, Index{1} << 18);
  const auto row_split = [&](unsigned q) { return n * static_cast<Index>(q) / static_cast<Index>(row_parts); };
  run_parts(row_parts, row_split, [&](unsigned q, Index j0, Index j1) {
    const auto y0 = static_cast<std::size_t>(size * q / row_parts), y1 = static_cast<std::size_t>(size * (q + 1) / row_parts);
    std::fill(yf_.begin() + static_cast<std::ptrdiff_t>(y0), yf_.begin() + static_cast<std::ptrdiff_t>(y1), 0.0);
    for (Index k = 0; k < p; ++k) {
      const double* x = X.col(k).data();
      for (Index j = j0; j < j1; ++j) xf_[static_cast<std::size_t>(slot_[static_cast<std::size_t>(j)] * p + k)] = x[j];
    }
  });
  // The columns in parts of about equal entries, one thread each (run_parts.hpp); a part writes
  // the rows of its own columns and, mirrored, rows of earlier ones, so each part after the
  // first adds into a buffer of its own (rows up to its last column), summed at the end.
  const Index N = Ms_.outerSize();
  const auto* outer = Ms_.outerIndexPtr();
  const unsigned parts = parts_for(Ms_.nonZeros() * p, Index{1} << 18);
  if (extra_.size() + 1 < parts) extra_.resize(parts - 1);
  const auto split = [&](unsigned q) -> Index {
    if (q == 0) return 0;
    if (q >= parts) return N;
    const auto target = static_cast<Index>(static_cast<double>(outer[N]) * q / parts);
    return static_cast<Index>(std::lower_bound(outer, outer + N + 1, target) - outer);
  };
  run_parts(parts, split, [&](unsigned q, Index b0, Index b1) {
    double* y = yf_.data();
    if (q > 0) {
      auto& e = extra_[q - 1];
      e.assign(static_cast<std::size_t>(b1 * r), 0.0);
      y = e.data();
    }
    node_product_any(Ms_, b0, b1, r, xf_.data(), y);
  });
  Y.resize(n, p);
  if (parts > 1)
    run_parts(row_parts, row_split, [&](unsigned q, Index, Index) {
      // The other parts' sums into this share of yf, in part order (the same sums on any thread).
      const auto y0 = static_cast<std::size_t>(size * q / row_parts), y1 = static_cast<std::size_t>(size * (q + 1) / row_parts);
      for (unsigned e = 1; e < parts; ++e) {
        const auto& extra = extra_[e - 1];
        for (std::size_t i = y0; i < std::min(y1, extra.size()); ++i) yf_[i] += extra[i];
      }
    });
  run_parts(row_parts, row_split, [&](unsigned, Index j0, Index j1) {
    for (Index k = 0; k < p; ++k) {
      double* y = Y.col(k).data();
      for (Index j = j0; j < j1; ++j) y[j] = yf_[static_cast<std::size_t>(slot_[static_cast<std::size_t>(j)] * p + k)];
    }
  });
}

std::vector<double> node_mass_values(const FeModel& model, const SparseMatrix& Ms, const SparseMatrix& C,
                                     const std::vector<Index>& rows) {
  const auto n = static_cast<Index>(rows.size());
  if (C.rows() != n || C.cols() != n || !C.isCompressed() || Ms.rows() != model.mesh->num_nodes()) return {};
  // Node and component of each row.
  std::vector<Index> node(static_cast<std::size_t>(n));
  std::vector<int> comp(static_cast<std::size_t>(n));
  for (Index j = 0; j < n; ++j) {
    const Index r = rows[static_cast<std::size_t>(j)];
    if (r < 0 || r >= model.mesh_dofs()) return {};
    const Index a = model.dof_node[static_cast<std::size_t>(r)];
    if (model.node_ndof[static_cast<std::size_t>(a)] != 3) return {};
    node[static_cast<std::size_t>(j)] = a;
    comp[static_cast<std::size_t>(j)] = static_cast<int>(r - model.node_dof[static_cast<std::size_t>(a)]);
  }
  const auto* outer = C.outerIndexPtr();
  const auto* inner = C.innerIndexPtr();
  const auto* ms_outer = Ms.outerIndexPtr();
  const auto* ms_inner = Ms.innerIndexPtr();
  const double* ms_val = Ms.valuePtr();
  // Ms(a, b) for a > b (C's numbering need not follow the nodes'): its upper triangle holds it
  // in column a.
  const auto lookup = [&](Index a, Index b) {
    const auto* first = ms_inner + ms_outer[a];
    const auto* last = ms_inner + ms_outer[a + 1];
    const auto* it = std::lower_bound(first, last, b);
    return it != last && *it == b ? ms_val[it - ms_inner] : 0.0;
  };
  std::vector<double> values(static_cast<std::size_t>(C.nonZeros()));
  const unsigned parts = parts_for(C.nonZeros(), Index{1} << 20);
  const auto split = [&](unsigned q) { return n * static_cast<Index>(q) / static_cast<Index>(parts); };
  run_parts(parts, split, [&](unsigned, Index j0, Index j1) {
    // Column b of Ms scattered by row node (a <= b), once for the columns of one node.
    std::vector<double> column(static_cast<std::size_t>(Ms.rows()), 0.0);
    Index held = -1;
    const auto hold = [&](Index b) {
      if (held == b) return;
      if (held >= 0)
        for (auto e = ms_outer[held]; e < ms_outer[held + 1]; ++e) column[static_cast<std::size_t>(ms_inner[e])] = 0.0;
      for (auto e = ms_outer[b]; e < ms_outer[b + 1]; ++e) column[static_cast<std::size_t>(ms_inner[e])] = ms_val[e];
      held = b;
    };
    for (Index j = j0; j < j1; ++j) {
      const Index b = node[static_cast<std::size_t>(j)];
      const int cb = comp[static_cast<std::size_t>(j)];
      hold(b);
      for (auto e = outer[j]; e < outer[j + 1]; ++e) {
        const Index i = inner[e];
        const Index a = node[static_cast<std::size_t>(i)];
        values[static_cast<std::size_t>(e)] =
            comp[static_cast<std::size_t>(i)] != cb ? 0.0 : a <= b ? column[static_cast<std::size_t>(a)] : lookup(a, b);
      }
    }
  });
  return values;
}

}  // namespace ffr::preproc::detail
