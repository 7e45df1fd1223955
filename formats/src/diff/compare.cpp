// diff(): structural comparison, mode alignment, then every dataset entry by entry.
#include "ffr/formats/diff.hpp"

#include "flatten.hpp"
#include "size.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace ffr::formats {
namespace {

using diff_detail::Flat;

std::string index_of(std::uint64_t flat, const std::vector<std::uint64_t>& shape) {
  std::vector<std::uint64_t> ix(shape.size());
  for (std::size_t d = shape.size(); d-- > 0;) {
    ix[d] = flat % std::max<std::uint64_t>(shape[d], 1);
    flat /= std::max<std::uint64_t>(shape[d], 1);
  }
  std::string s = "[";
  for (std::size_t d = 0; d < ix.size(); ++d) {
    if (d) s += ',';
    s += std::to_string(ix[d]);
  }
  s += ']';
  return s;
}

}  // namespace

DiffReport diff(const Sid& a, const Sid& b_in, const DiffOptions& opt) {
  DiffReport rep;
  diff_detail::structural(a, b_in, rep.structural);
  const bool modal = a.nq() == b_in.nq();
  // Modal data can be compared only when the labels line up; node data needs the same names.
  std::vector<std::string> order;
  for (const auto& n : a.nodes)
    if (b_in.find_node(n.name) >= 0) order.push_back(n.name);
  Sid b = b_in;
  if (modal && opt.align && a.nq() > 0) {
    rep.alignment = align_modes(a, b_in, opt);
    b = transform_modes(b_in, rep.alignment.T);
  }
  const Size z = size_of(a);
  auto fa = diff_detail::flatten(a, order, z, modal);
  auto fb = diff_detail::flatten(b, order, z, modal);
  // Datasets present in only one file (stiffening interfaces, visual) are structural.
  std::map<std::string, const Flat*> mb;
  for (const auto& f : fb) mb[f.path] = &f;
  for (const auto& f : fa) {
    const auto it = mb.find(f.path);
    if (it == mb.end() || it->second->v.size() != f.v.size()) continue;
    const Flat& g = *it->second;
    ++rep.datasets_compared;
    double scale = f.floor;
    for (std::size_t i = 0; i < f.v.size(); ++i) scale = std::max({scale, std::abs(f.v[i]), std::abs(g.v[i])});
    const double allowed = opt.atol + opt.rtol * scale;
    bool differs = false;
    for (std::size_t i = 0; i < f.v.size(); ++i) {
      const double d = std::abs(f.v[i] - g.v[i]);
      if (!(d <= allowed)) {
        differs = true;
        rep.worst.push_back({f.path, index_of(i, f.shape), f.v[i], g.v[i], d, scale > 0 ? d / scale : d, allowed});
      }
    }
    rep.datasets_different += differs;
  }
  auto badness = [](const Difference& d) { return d.allowed > 0 ? d.abs / d.allowed : INFINITY; };
  std::stable_sort(rep.worst.begin(), rep.worst.end(), [&](const auto& x, const auto& y) { return badness(x) > badness(y); });
  // Keep the worst entry of every differing dataset, then fill up to max_reported.
  std::vector<Difference> kept;
  std::set<std::string> seen;
  for (const auto& d : rep.worst)
    if (seen.insert(d.dataset).second) kept.push_back(d);
  for (const auto& d : rep.worst) {
    if (static_cast<int>(kept.size()) >= std::max(opt.max_reported, static_cast<int>(seen.size()))) break;
    if (std::find_if(kept.begin(), kept.end(), [&](const auto& k) { return k.dataset == d.dataset && k.index == d.index; }) == kept.end())
      kept.push_back(d);
  }
  std::stable_sort(kept.begin(), kept.end(), [&](const auto& x, const auto& y) { return badness(x) > badness(y); });
  rep.worst = std::move(kept);
  rep.equivalent = rep.structural.empty() && rep.datasets_different == 0;
  return rep;
}

}  // namespace ffr::formats
