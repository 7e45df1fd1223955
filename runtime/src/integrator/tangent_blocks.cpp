// The coupled body pairs of the tangent's blocks, collected once (tangent_blocks.hpp).
#include "tangent_blocks.hpp"

namespace ffr::runtime::detail {

std::vector<std::array<int, 2>> coupled_body_pairs(const Model& model) {
  std::vector<std::array<int, 2>> pairs;
  for_each_coupling(model, [&](int a, int b) { pairs.push_back({std::min(a, b), std::max(a, b)}); });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace ffr::runtime::detail
