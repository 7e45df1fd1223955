// Greedy colouring of element blocks (see coloring.hpp).
#include "coloring.hpp"

#include <algorithm>
#include <utility>

namespace ffr::preproc::detail {
namespace {

// Classes of item indices (into ents) with no entity in common within a class, each in
// increasing order. ents[e] lists the entities item e writes to; num_entities bounds them.
std::vector<std::vector<std::size_t>> color_sets(const std::vector<std::vector<Index>>& ents, Index num_entities) {
  const std::size_t ne = ents.size();
  // Elements of each entity (CSR).
  std::vector<std::size_t> ptr(static_cast<std::size_t>(num_entities) + 1, 0);
  for (const auto& e : ents)
    for (const Index x : e) ++ptr[static_cast<std::size_t>(x) + 1];
  for (std::size_t x = 0; x < static_cast<std::size_t>(num_entities); ++x) ptr[x + 1] += ptr[x];
  std::vector<std::size_t> elems(ptr.back()), fill(ptr.begin(), ptr.end() - 1);
  for (std::size_t e = 0; e < ne; ++e)
    for (const Index x : ents[e]) elems[fill[static_cast<std::size_t>(x)]++] = e;

  // Smallest colour not used by an already coloured element that shares an entity.
  std::vector<int> color(ne, -1);
  std::vector<std::size_t> seen;  // seen[c] == e + 1: colour c is taken for element e
  std::vector<std::vector<std::size_t>> classes;
  for (std::size_t e = 0; e < ne; ++e) {
    for (const Index x : ents[e])
      for (std::size_t k = ptr[static_cast<std::size_t>(x)]; k < ptr[static_cast<std::size_t>(x) + 1]; ++k) {
        const int c = color[elems[k]];
        if (c >= 0) seen[static_cast<std::size_t>(c)] = e + 1;
      }
    std::size_t c = 0;
    while (c < seen.size() && seen[c] == e + 1) ++c;
    if (c == seen.size()) {
      seen.push_back(0);
      classes.emplace_back();
    }
    color[e] = static_cast<int>(c);
    classes[c].push_back(e);
  }
  return classes;
}

}  // namespace

ElementBlocks color_blocks(const std::vector<std::vector<Index>>& ents, Index num_entities, std::size_t block_size) {
  ElementBlocks out;
  const std::size_t ne = ents.size();
  std::vector<std::pair<Index, std::size_t>> key(ne);
  for (std::size_t e = 0; e < ne; ++e)
    key[e] = {ents[e].empty() ? num_entities : *std::min_element(ents[e].begin(), ents[e].end()), e};
  std::sort(key.begin(), key.end());
  out.order.resize(ne);
  for (std::size_t k = 0; k < ne; ++k) out.order[k] = key[k].second;
  const std::size_t bs = std::max<std::size_t>(1, block_size);
  std::vector<std::vector<Index>> block_ents;
  for (std::size_t b0 = 0; b0 < ne; b0 += bs) {
    out.block_ptr.push_back(b0);
    std::vector<Index> u;
    for (std::size_t k = b0; k < std::min(ne, b0 + bs); ++k) u.insert(u.end(), ents[out.order[k]].begin(), ents[out.order[k]].end());
    std::sort(u.begin(), u.end());
    u.erase(std::unique(u.begin(), u.end()), u.end());
    block_ents.push_back(std::move(u));
  }
  out.block_ptr.push_back(ne);
  out.classes = color_sets(block_ents, num_entities);
  return out;
}

}  // namespace ffr::preproc::detail
