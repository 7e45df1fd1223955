// Cutting the supernodal elimination tree for threaded substitutions (see solve_schedule.hpp).
#include "solve_schedule.hpp"

#include <algorithm>
#include <numeric>

namespace ffr::preproc::detail {
namespace {

using Index = std::int64_t;

// Largest bin after dealing the subtrees, largest first, each to the lightest bin (LPT).
double deal(const std::vector<Index>& cand, const std::vector<double>& subtree, unsigned bins,
            std::vector<std::vector<Index>>* out) {
  std::vector<Index> order = cand;
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return subtree[a] > subtree[b]; });
  std::vector<double> load(bins, 0.0);
  if (out) out->assign(bins, {});
  for (const Index c : order) {
    const auto b = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    load[b] += subtree[c];
    if (out) (*out)[b].push_back(c);
  }
  return *std::max_element(load.begin(), load.end());
}

}  // namespace

SolveSchedule make_solve_schedule(const cholmod_factor& L, unsigned threads, std::int64_t min_entries,
                                  TreeWork measure) {
  SolveSchedule plan;
  if (threads < 2 || !L.is_super || static_cast<std::int64_t>(L.xsize) < min_entries) return plan;
  const auto* super = static_cast<const SuiteSparse_long*>(L.super);
  const auto* pi = static_cast<const SuiteSparse_long*>(L.pi);
  const auto* rows = static_cast<const SuiteSparse_long*>(L.s);
  const auto ns = static_cast<Index>(L.nsuper);

  // Parent of each supernode: the one holding its first row below the diagonal block.
  std::vector<Index> parent(static_cast<std::size_t>(ns), -1);
  std::vector<double> work(static_cast<std::size_t>(ns)), subtree(static_cast<std::size_t>(ns));
  std::vector<Index> first(static_cast<std::size_t>(ns)), count(static_cast<std::size_t>(ns), 1);
  for (Index s = 0; s < ns; ++s) {
    const Index nscol = super[s + 1] - super[s], nsrow = pi[s + 1] - pi[s];
    work[s] = static_cast<double>(nscol) * static_cast<double>(nsrow) *
              (measure == TreeWork::Flops ? static_cast<double>(nsrow) : 1.0);
    if (nsrow > nscol) {
      const Index r = rows[pi[s] + nscol];
      parent[s] = static_cast<Index>(std::upper_bound(super, super + ns + 1, r) - super) - 1;
      if (parent[s] <= s) return plan;  // not post-ordered as expected: stay serial
    }
    subtree[s] = work[s];
    first[s] = s;
  }
  for (Index s = 0; s < ns; ++s)
    if (parent[s] >= 0) {
      subtree[parent[s]] += subtree[s];
      first[parent[s]] = std::min(first[parent[s]], first[s]);
      count[parent[s]] += count[s];
    }
  // Post-order check: each subtree is exactly the range first .. root.
  for (Index s = 0; s < ns; ++s)
    if (count[s] != s - first[s] + 1) return plan;
  std::vector<std::vector<Index>> children(static_cast<std::size_t>(ns));
  std::vector<Index> cand;
  for (Index s = 0; s < ns; ++s) (parent[s] >= 0 ? children[parent[s]] : cand).push_back(s);
  const double total = std::accumulate(work.begin(), work.end(), 0.0);

  // Move the heaviest subtree's root into the top, one at a time, and keep the cut with the
  // least serial-equivalent cost (top + heaviest thread). A few hundred steps reach far below
  // the separators that matter.
  std::vector<Index> top, best_top, best_cand;
  double top_work = 0, best_cost = total;
  for (int step = 0; step < 512 && !cand.empty(); ++step) {
    const double cost = top_work + deal(cand, subtree, threads, nullptr);
    if (cost < best_cost) {
      best_cost = cost;
      best_top = top;
      best_cand = cand;
    }
    const auto heaviest = std::max_element(cand.begin(), cand.end(), [&](Index a, Index b) { return subtree[a] < subtree[b]; });
    const Index c = *heaviest;
    cand.erase(heaviest);
    top.push_back(c);
    top_work += work[c];
    cand.insert(cand.end(), children[c].begin(), children[c].end());
  }
  if (best_cand.empty() || total - std::accumulate(best_top.begin(), best_top.end(), 0.0, [&](double a, Index s) { return a + work[s]; }) < total / 3)
    return plan;

  std::vector<std::vector<Index>> bins;
  deal(best_cand, subtree, threads, &bins);
  double parallel = 0;
  for (auto& bin : bins) {
    std::sort(bin.begin(), bin.end());
    std::vector<SupernodeRange> ranges;
    for (const Index c : bin) {
      ranges.push_back({first[c], c});
      parallel += subtree[c];
    }
    plan.parts.push_back(std::move(ranges));
  }
  std::sort(best_top.begin(), best_top.end());
  plan.slot.assign(L.n, -1);
  for (const Index s : best_top) {
    plan.top.push_back({s, s});
    for (Index k = super[s]; k < super[s + 1]; ++k) {
      plan.slot[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(plan.top_columns.size());
      plan.top_columns.push_back(k);
    }
  }
  plan.parallel_fraction = parallel / total;
  return plan;
}

}  // namespace ffr::preproc::detail
