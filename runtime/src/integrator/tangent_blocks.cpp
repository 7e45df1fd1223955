// The coupled body pairs of the tangent's blocks, collected once; the order in which the
// factorisation takes the bodies, and the row spans of its columns that the blocks give
// (tangent_blocks.hpp).
#include "tangent_blocks.hpp"

#include <algorithm>
#include <numeric>

namespace ffr::runtime::detail {

std::vector<std::array<int, 2>> coupled_body_pairs(const Model& model) {
  std::vector<std::array<int, 2>> pairs;
  for_each_coupling(model, [&](int a, int b) { pairs.push_back({std::min(a, b), std::max(a, b)}); });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

namespace {

// The integrated bodies' unknown coordinates, ascending (as Data::unknowns, or [0, nf)).
std::vector<int> unknown_coordinates(const Model& model, const Data& data, int body) {
  const Body& b = model.bodies[static_cast<std::size_t>(body)];
  std::vector<int> c;
  if (data.unknowns.empty()) {
    for (int k = 0; k < b.ncoord(); ++k) c.push_back(b.offset + k);
    return c;
  }
  const auto lo = std::lower_bound(data.unknowns.begin(), data.unknowns.end(), b.offset);
  const auto hi = std::lower_bound(lo, data.unknowns.end(), b.offset + b.ncoord());
  return {lo, hi};
}

}  // namespace

void column_spans(const Model& model, const Data& data, const std::vector<int>& pos, int k, int* first, int* last) {
  for (int j = 0; j < k; ++j) first[j] = last[j] = j;
  // A block's rows are one body's coordinates, consecutive among the positions too.
  for_each_tangent_block(model, data, true, [&](int r0, int nr, int c0, int nc) {
    int g0 = k, g1 = -1;
    for (int r = r0; r < r0 + nr; ++r)
      if (const int g = pos[static_cast<std::size_t>(r)]; g >= 0) {
        g0 = std::min(g0, g);
        g1 = std::max(g1, g);
      }
    if (g1 < 0) return;
    for (int c = c0; c < c0 + nc; ++c)
      if (const int j = pos[static_cast<std::size_t>(c)]; j >= 0) {
        first[j] = std::min(first[j], g0);
        last[j] = std::max(last[j], g1);
      }
  });
}

namespace {

// Multiply-adds of SmallLU's elimination on a matrix with the symmetric pattern of these
// column ends, without pivoting: its row and column bounds widen as the elimination fills them
// (small_lu.cpp), and pivot k costs its column's rows below it times its row's columns right
// of it.
double envelope_work(std::vector<int> col_last) {
  std::vector<int> row_last = col_last;
  const int k = static_cast<int>(col_last.size());
  double work = 0;
  for (int p = 0; p < k; ++p) {
    const int c = col_last[static_cast<std::size_t>(p)], r = row_last[static_cast<std::size_t>(p)];
    work += static_cast<double>(c - p) * (r - p + 1);
    for (int j = p + 1; j <= r; ++j) col_last[static_cast<std::size_t>(j)] = std::max(col_last[static_cast<std::size_t>(j)], c);
    for (int i = p + 1; i <= c; ++i) row_last[static_cast<std::size_t>(i)] = std::max(row_last[static_cast<std::size_t>(i)], r);
  }
  return work;
}

// The bodies (indices into `nodes`) in the order of minimum external degree, each next body
// the one whose remaining neighbours hold the fewest unknowns (ties: the first), its neighbours
// then joined to each other as its elimination fills them; then postordered along the
// elimination tree, so that each subtree's bodies are consecutive and its root follows them.
// Why: on a hub with branches (a vehicle's frame with its axles, wheels, cab and engine) the
// hub comes last and each branch's fill stays in the branch's rows; taken in the model's
// order, with the hub first, the elimination filled everything the hub couples to.
std::vector<int> min_degree_postorder(const std::vector<int>& weight, std::vector<std::vector<char>> adj) {
  const int n = static_cast<int>(weight.size());
  std::vector<int> order, position(static_cast<std::size_t>(n), -1);
  for (int step = 0; step < n; ++step) {
    int best = -1;
    long best_degree = 0;
    for (int b = 0; b < n; ++b) {
      if (position[static_cast<std::size_t>(b)] >= 0) continue;
      long degree = 0;
      for (int c = 0; c < n; ++c)
        if (adj[static_cast<std::size_t>(b)][static_cast<std::size_t>(c)] && position[static_cast<std::size_t>(c)] < 0) degree += weight[static_cast<std::size_t>(c)];
      if (best < 0 || degree < best_degree) {
        best = b;
        best_degree = degree;
      }
    }
    position[static_cast<std::size_t>(best)] = step;
    order.push_back(best);
    for (int x = 0; x < n; ++x) {
      if (!adj[static_cast<std::size_t>(best)][static_cast<std::size_t>(x)] || position[static_cast<std::size_t>(x)] >= 0) continue;
      for (int y = 0; y < n; ++y)
        if (y != x && adj[static_cast<std::size_t>(best)][static_cast<std::size_t>(y)] && position[static_cast<std::size_t>(y)] < 0)
          adj[static_cast<std::size_t>(x)][static_cast<std::size_t>(y)] = 1;
    }
  }
  // Elimination tree: a body's parent is its filled neighbour eliminated next after it.
  std::vector<std::vector<int>> children(static_cast<std::size_t>(n));
  std::vector<int> roots;
  for (int b : order) {
    int parent = -1;
    for (int c = 0; c < n; ++c)
      if (adj[static_cast<std::size_t>(b)][static_cast<std::size_t>(c)] && position[static_cast<std::size_t>(c)] > position[static_cast<std::size_t>(b)] &&
          (parent < 0 || position[static_cast<std::size_t>(c)] < position[static_cast<std::size_t>(parent)]))
        parent = c;
    (parent < 0 ? roots : children[static_cast<std::size_t>(parent)]).push_back(b);
  }
  // Each body's children by the unknowns of their subtrees, largest first: the smaller ones
  // then sit next to their parent, so fewer rows lie between them and it (an envelope's
  // factorisation works over those rows too).
  std::vector<long> size(static_cast<std::size_t>(n), 0);
  for (int b : order) {  // children come before their parents in the order
    size[static_cast<std::size_t>(b)] += weight[static_cast<std::size_t>(b)];
    for (int c : children[static_cast<std::size_t>(b)]) size[static_cast<std::size_t>(b)] += size[static_cast<std::size_t>(c)];
  }
  const auto larger = [&](int a, int b) { return size[static_cast<std::size_t>(a)] > size[static_cast<std::size_t>(b)]; };
  for (auto& c : children) std::stable_sort(c.begin(), c.end(), larger);
  std::stable_sort(roots.begin(), roots.end(), larger);
  std::vector<int> post;
  const auto visit = [&](auto&& self, int b) -> void {
    for (int c : children[static_cast<std::size_t>(b)]) self(self, c);
    post.push_back(b);
  };
  for (int r : roots) visit(visit, r);
  return post;
}

}  // namespace

void factorisation_order(const Model& model, Data& data) {
  const int k = data.unknowns.empty() ? data.nf : static_cast<int>(data.unknowns.size());
  std::vector<int> nodes;                      // integrated bodies with unknowns
  std::vector<std::vector<int>> coords;        // their unknown coordinates
  std::vector<int> node_of(model.bodies.size(), -1);
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!data.integrated[i]) continue;
    std::vector<int> c = unknown_coordinates(model, data, static_cast<int>(i));
    if (c.empty()) continue;
    node_of[i] = static_cast<int>(nodes.size());
    nodes.push_back(static_cast<int>(i));
    coords.push_back(std::move(c));
  }
  const auto n = nodes.size();
  const auto positions = [&](const std::vector<int>& body_order) {
    std::vector<int> pos(static_cast<std::size_t>(model.ncoord), -1);
    int at = 0;
    for (int b : body_order)
      for (int c : coords[static_cast<std::size_t>(b)]) pos[static_cast<std::size_t>(c)] = at++;
    return pos;
  };
  std::vector<int> natural(n);
  std::iota(natural.begin(), natural.end(), 0);
  std::vector<int> weight(n);
  std::vector<std::vector<char>> adj(n, std::vector<char>(n, 0));
  for (std::size_t b = 0; b < n; ++b) weight[b] = static_cast<int>(coords[b].size());
  for_each_coupled_pair(data, true, [&](int a, int b) {
    const int x = node_of[static_cast<std::size_t>(a)], y = node_of[static_cast<std::size_t>(b)];
    if (x < 0 || y < 0) return;
    adj[static_cast<std::size_t>(x)][static_cast<std::size_t>(y)] = adj[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] = 1;
  });
  std::vector<int> chosen = natural;
  std::vector<int> pos = positions(natural);
  const std::vector<int> reordered = min_degree_postorder(weight, adj);
  const std::vector<int> pos_r = positions(reordered);
  // The model's order unless the other saves a tenth of the work: a chain (a geometrically
  // exact beam's nodes, links in a row) is banded in its own order already.
  const auto work = [&](const std::vector<int>& p) {
    std::vector<int> first(static_cast<std::size_t>(k)), last(static_cast<std::size_t>(k));
    column_spans(model, data, p, k, first.data(), last.data());
    return envelope_work(std::move(last));
  };
  if (work(pos_r) < 0.9 * work(pos)) {
    chosen = reordered;
    pos = pos_r;
  }
  data.lu_pos.assign(pos.begin(), pos.end());
  data.lu_runs.clear();
  for (int b : chosen) {
    for (int c : coords[static_cast<std::size_t>(b)]) {
      const int at = pos[static_cast<std::size_t>(c)];
      if (!data.lu_runs.empty() && data.lu_runs.back().first + data.lu_runs.back().len == c && data.lu_runs.back().at + data.lu_runs.back().len == at)
        ++data.lu_runs.back().len;
      else
        data.lu_runs.push_back({at, c, 1});
    }
  }
}

void tangent_row_spans(const Model& model, Data& data) {
  if (!data.tangent_blocks_pay) return;
  factorisation_order(model, data);
  const int k = data.unknowns.empty() ? data.nf : static_cast<int>(data.unknowns.size());
  column_spans(model, data, data.lu_pos, k, data.lu_first.data(), data.lu_last.data());
}

}  // namespace ffr::runtime::detail
