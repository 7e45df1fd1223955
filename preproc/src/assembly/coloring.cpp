// Greedy element colouring (see coloring.hpp).
#include "coloring.hpp"

namespace ffr::preproc::detail {

std::vector<std::vector<std::size_t>> color_elements(const std::vector<std::vector<Index>>& ents, Index num_entities) {
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

}  // namespace ffr::preproc::detail
