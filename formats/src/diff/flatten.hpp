#pragma once
// Internal to diff: every numeric dataset of a SID as the file holds it (C order, shape), and
// the structural comparison of names and labels.
#include "ffr/formats/sid.hpp"

#include "size.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace ffr::formats::diff_detail {

/// One dataset: C-order values and shape, with a floor for its scale (its natural size).
struct Flat {
  std::string path;
  std::vector<std::uint64_t> shape;
  std::vector<double> v;
  double floor = 0;
};

/// Every numeric dataset; nodes in `node_order` (names present in both files). Without
/// `modal` only the mode-independent ones.
std::vector<Flat> flatten(const Sid& s, const std::vector<std::string>& node_order, const Size& z, bool modal);

/// Differences of sizes, names and labels, one line each.
void structural(const Sid& a, const Sid& b, std::vector<std::string>& out);

}  // namespace ffr::formats::diff_detail
