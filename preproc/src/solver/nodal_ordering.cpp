#include "nodal_ordering.hpp"

#include <metis.h>

#include <algorithm>
#include <limits>
#include <utility>

namespace ffr::preproc::detail {
namespace {

using Eigen::Index;

// The graph of the strictly upper entries, mirrored: adjacency lists in CSR, each sorted.
struct Graph {
  std::vector<std::int64_t> start;  // n + 1
  std::vector<idx_t> adj;
};

bool build_graph(const SparseMatrix& A, Graph& g) {
  const Index n = A.cols();
  g.start.assign(static_cast<std::size_t>(n) + 1, 0);
  auto each_upper = [&A](auto&& f) {
    for (Index j = 0; j < A.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it)
        if (it.row() < j) f(it.row(), j);
  };
  each_upper([&g](Index i, Index j) {
    ++g.start[static_cast<std::size_t>(i) + 1];
    ++g.start[static_cast<std::size_t>(j) + 1];
  });
  for (std::size_t v = 0; v < static_cast<std::size_t>(n); ++v) g.start[v + 1] += g.start[v];
  if (g.start.back() > std::numeric_limits<idx_t>::max()) return false;
  g.adj.resize(static_cast<std::size_t>(g.start.back()));
  std::vector<std::int64_t> next(g.start.begin(), g.start.end() - 1);
  each_upper([&](Index i, Index j) {
    g.adj[static_cast<std::size_t>(next[static_cast<std::size_t>(j)]++)] = static_cast<idx_t>(i);
    g.adj[static_cast<std::size_t>(next[static_cast<std::size_t>(i)]++)] = static_cast<idx_t>(j);
  });
  // Sorted already when A's columns are (each list receives its smaller neighbours while its
  // own column is read, the larger ones from later columns in order); sort where not.
  for (std::size_t v = 0; v < static_cast<std::size_t>(n); ++v) {
    auto b = g.adj.begin() + g.start[v], e = g.adj.begin() + g.start[v + 1];
    if (!std::is_sorted(b, e)) std::sort(b, e);
  }
  return true;
}

// Whether v and w (v != w) have the same closed neighbourhood: w in N(v) and
// N(v) \ {w} == N(w) \ {v}.
bool same_closed(const Graph& g, idx_t v, idx_t w) {
  const std::int64_t bv = g.start[static_cast<std::size_t>(v)], ev = g.start[static_cast<std::size_t>(v) + 1];
  const std::int64_t bw = g.start[static_cast<std::size_t>(w)], ew = g.start[static_cast<std::size_t>(w) + 1];
  if (ev - bv != ew - bw) return false;
  if (!std::binary_search(g.adj.begin() + bv, g.adj.begin() + ev, w)) return false;
  std::int64_t p = bv, q = bw;
  for (;;) {
    while (p < ev && g.adj[static_cast<std::size_t>(p)] == w) ++p;
    while (q < ew && g.adj[static_cast<std::size_t>(q)] == v) ++q;
    if (p == ev || q == ew) return p == ev && q == ew;
    if (g.adj[static_cast<std::size_t>(p)] != g.adj[static_cast<std::size_t>(q)]) return false;
    ++p;
    ++q;
  }
}

// METIS_NodeND on the quotient graph (group G: columns first[G] .. first[G + 1] - 1, weight
// its column count), the order expanded to the n columns.
NodalOrdering order_groups(idx_t ng, std::vector<idx_t> xadj, std::vector<idx_t> adjncy, std::vector<idx_t> weight,
                           const std::vector<idx_t>& first, Index n) {
  NodalOrdering out;
  idx_t nv = ng;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> order(static_cast<std::size_t>(ng)), inverse(static_cast<std::size_t>(ng));
  if (METIS_NodeND(&nv, xadj.data(), adjncy.data(), weight.data(), options, order.data(), inverse.data()) != METIS_OK)
    return out;

  // METIS: row k of the permuted matrix is row order[k] of the original.
  out.perm.reserve(static_cast<std::size_t>(n));
  for (idx_t k = 0; k < ng; ++k) {
    const idx_t G = order[static_cast<std::size_t>(k)];
    for (idx_t v = first[static_cast<std::size_t>(G)]; v < first[static_cast<std::size_t>(G) + 1]; ++v) out.perm.push_back(v);
  }
  out.groups = ng;
  return out;
}

}  // namespace

NodalOrdering nodal_metis_ordering(const SparseMatrix& A) {
  NodalOrdering out;
  const Index n = A.cols();
  if (n < 4 || n > std::numeric_limits<idx_t>::max()) return out;
  Graph g;
  if (!build_graph(A, g)) return out;

  // Supervariables: runs of consecutive columns equal to the run's first (the DOFs of a node
  // are numbered together by the assembly).
  std::vector<idx_t> first;  // first column of each group, then n
  std::vector<idx_t> group(static_cast<std::size_t>(n));
  for (idx_t v = 0; v < static_cast<idx_t>(n); ++v) {
    if (v == 0 || !same_closed(g, first.back(), v)) first.push_back(v);
    group[static_cast<std::size_t>(v)] = static_cast<idx_t>(first.size() - 1);
  }
  const idx_t ng = static_cast<idx_t>(first.size());
  first.push_back(static_cast<idx_t>(n));
  if (ng < 2 || 3 * static_cast<Index>(ng) > 2 * n) return out;  // under 1.5 columns a group

  // Quotient graph: the groups of the first column's neighbours (non-decreasing, since groups
  // are runs), without repeats and without the group itself; weight = columns in the group.
  std::vector<idx_t> xadj(static_cast<std::size_t>(ng) + 1, 0), adjncy, weight(static_cast<std::size_t>(ng));
  adjncy.reserve(g.adj.size() / 9 + static_cast<std::size_t>(ng));
  for (idx_t G = 0; G < ng; ++G) {
    const idx_t r = first[static_cast<std::size_t>(G)];
    weight[static_cast<std::size_t>(G)] = first[static_cast<std::size_t>(G) + 1] - r;
    idx_t last = -1;
    for (std::int64_t p = g.start[static_cast<std::size_t>(r)]; p < g.start[static_cast<std::size_t>(r) + 1]; ++p) {
      const idx_t H = group[static_cast<std::size_t>(g.adj[static_cast<std::size_t>(p)])];
      if (H != G && H != last) adjncy.push_back(H);
      last = H;
    }
    xadj[static_cast<std::size_t>(G) + 1] = static_cast<idx_t>(adjncy.size());
  }
  g = Graph{};  // the DOF graph is no longer needed: free it before METIS works
  return order_groups(ng, std::move(xadj), std::move(adjncy), std::move(weight), first, n);
}

NodalOrdering metis_ordering(const QuotientGraph& q) {
  const auto ng = static_cast<std::int64_t>(q.first.size()) - 1;
  const std::int64_t n = ng >= 0 ? q.first.back() : 0;
  constexpr auto kMax = static_cast<std::int64_t>(std::numeric_limits<idx_t>::max());
  if (ng < 1 || n > kMax || static_cast<std::int64_t>(q.adjncy.size()) > kMax ||
      static_cast<std::int64_t>(q.xadj.size()) != ng + 1)
    return {};
  const auto narrow = [](const std::vector<std::int64_t>& v) { return std::vector<idx_t>(v.begin(), v.end()); };
  const std::vector<idx_t> first = narrow(q.first);
  std::vector<idx_t> weight(static_cast<std::size_t>(ng));
  for (std::size_t G = 0; G < weight.size(); ++G) weight[G] = first[G + 1] - first[G];
  return order_groups(static_cast<idx_t>(ng), narrow(q.xadj), narrow(q.adjncy), std::move(weight), first, n);
}

}  // namespace ffr::preproc::detail
