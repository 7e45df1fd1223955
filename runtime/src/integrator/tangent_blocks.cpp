// The coupled body pairs of the tangent's blocks, collected once, and the factorised tangent's
// row spans they give (tangent_blocks.hpp).
#include "tangent_blocks.hpp"

namespace ffr::runtime::detail {

std::vector<std::array<int, 2>> coupled_body_pairs(const Model& model) {
  std::vector<std::array<int, 2>> pairs;
  for_each_coupling(model, [&](int a, int b) { pairs.push_back({std::min(a, b), std::max(a, b)}); });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

void tangent_row_spans(const Model& model, Data& data) {
  if (!data.tangent_blocks_pay) return;
  const std::vector<int>& u = data.unknowns;
  const int k = u.empty() ? data.nf : static_cast<int>(u.size());
  // The position among the factorised columns of the first unknown at or after coordinate c
  // (the unknowns ascend, so a block's rows and columns stay contiguous there).
  const auto at = [&](int c) {
    return u.empty() ? std::min(c, data.nf) : static_cast<int>(std::lower_bound(u.begin(), u.end(), c) - u.begin());
  };
  for (int j = 0; j < k; ++j) data.lu_first[j] = data.lu_last[j] = j;
  for_each_tangent_block(model, data, true, [&](int r0, int nr, int c0, int nc) {
    const int g0 = at(r0), g1 = at(r0 + nr);
    if (g1 <= g0) return;
    for (int j = at(c0), end = at(c0 + nc); j < end; ++j) {
      data.lu_first[j] = std::min(data.lu_first[j], g0);
      data.lu_last[j] = std::max(data.lu_last[j], g1 - 1);
    }
  });
}

}  // namespace ffr::runtime::detail
