#include "node_order.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace ffr::preproc::detail {
namespace {

constexpr int kBits = 21;  // per axis: 63 bits of code
constexpr double kCells = static_cast<double>((1u << kBits) - 1);

// The kBits low bits of v, spread to every third bit.
std::uint64_t spread(std::uint64_t v) {
  v &= (1u << kBits) - 1;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::vector<Index> spatial_order(const double* x, Index rows) {
  std::vector<Index> order(static_cast<std::size_t>(rows));
  if (rows == 0) return order;
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = x[a];
  for (Index i = 0; i < rows; ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], x[3 * i + a]);
      hi[a] = std::max(hi[a], x[3 * i + a]);
    }
  // One scale for all axes, so the curve's cells are cubes.
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double scale = extent > 0 ? kCells / extent : 0.0;
  std::vector<std::pair<std::uint64_t, Index>> key(static_cast<std::size_t>(rows));
  for (Index i = 0; i < rows; ++i) {
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double t = std::clamp((x[3 * i + a] - lo[a]) * scale, 0.0, kCells);  // NaN -> 0 cell
      code |= spread(static_cast<std::uint64_t>(t)) << a;
    }
    key[static_cast<std::size_t>(i)] = {code, i};
  }
  std::sort(key.begin(), key.end());
  for (std::size_t k = 0; k < key.size(); ++k) order[k] = key[k].second;
  return order;
}

bool number_nodes(const std::vector<std::size_t>& tags, const std::vector<double>& coord, Mesh& mesh,
                  std::unordered_map<std::size_t, Index>& index) {
  const std::vector<Index> order = spatial_order(coord.data(), static_cast<Index>(tags.size()));
  mesh.x.resize(static_cast<Index>(tags.size()), 3);
  mesh.node_tags.resize(tags.size());
  index.clear();
  index.reserve(tags.size() * 2);
  bool distinct = true;
  for (std::size_t i = 0; i < tags.size(); ++i) {
    const auto from = static_cast<std::size_t>(order[i]);
    distinct = index.emplace(tags[from], static_cast<Index>(i)).second && distinct;
    mesh.node_tags[i] = tags[from];
    for (int c = 0; c < 3; ++c) mesh.x(static_cast<Index>(i), c) = coord[3 * from + static_cast<std::size_t>(c)];
  }
  return distinct;
}

}  // namespace ffr::preproc::detail
