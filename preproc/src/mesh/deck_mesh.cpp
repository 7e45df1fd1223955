#include "deck_mesh.hpp"

#include "ffr/formats/h5.hpp"
#include "node_order.hpp"
#include "../stopwatch.hpp"

#include <algorithm>
#include <map>
#include <unordered_map>
#include <utility>

namespace ffr::preproc::detail {

using formats::FormatError;

Mesh build_deck_mesh(const DeckMesh& d, MeshReport* report, std::chrono::steady_clock::time_point start) {
  const std::string& file = d.file;
  if (d.node_ids.empty()) throw FormatError(file, "", "the deck has no nodes");
  if (d.elements.empty()) throw FormatError(file, "", "the deck has no elements");
  const auto at = [](int line) { return "line " + std::to_string(line); };

  Mesh mesh;
  std::unordered_map<std::size_t, Index> node_index;
  if (!number_nodes(d.node_ids, d.xyz, mesh, node_index)) {
    std::unordered_map<std::size_t, int> seen;
    for (std::size_t i = 0; i < d.node_ids.size(); ++i) {
      const auto [it, fresh] = seen.emplace(d.node_ids[i], d.node_lines[i]);
      if (!fresh)
        throw FormatError(file, at(d.node_lines[i]),
                          "node " + std::to_string(d.node_ids[i]) + " defined twice (first at line " +
                              std::to_string(it->second) + ")");
    }
  }
  std::unordered_map<std::size_t, std::size_t> element_index;
  for (std::size_t e = 0; e < d.elements.size(); ++e) {
    const DeckMesh::Element& el = d.elements[e];
    const auto [it, fresh] = element_index.emplace(el.id, e);
    if (!fresh)
      throw FormatError(file, at(el.line),
                        "element " + std::to_string(el.id) + " defined twice (first at line " +
                            std::to_string(d.elements[it->second].line) + ")");
    for (int i = 0; i < num_nodes(el.type); ++i)
      if (!node_index.count(d.conn[el.first + static_cast<std::size_t>(i)]))
        throw FormatError(file, at(el.line),
                          "element " + std::to_string(el.id) + ": node " +
                              std::to_string(d.conn[el.first + static_cast<std::size_t>(i)]) + " is not defined");
  }

  const auto add_group = [&](const std::string& name, const std::vector<std::size_t>& elements) {
    std::map<std::pair<ElementType, Hex8Formulation>, std::size_t> block_of_type;
    std::vector<Index>& set = mesh.node_groups[name];
    for (const std::size_t e : elements) {
      const DeckMesh::Element& el = d.elements[e];
      const Hex8Formulation hex8 = el.type == ElementType::Hex8 ? el.hex8 : Hex8Formulation::Incompatible;
      auto [it, fresh] = block_of_type.try_emplace(std::make_pair(el.type, hex8), mesh.blocks.size());
      if (fresh) mesh.blocks.push_back(ElementBlock{el.type, name, {}, {}, hex8});
      ElementBlock& b = mesh.blocks[it->second];
      b.tags.push_back(el.id);
      for (int i = 0; i < num_nodes(el.type); ++i) {
        const Index n = node_index.at(d.conn[el.first + static_cast<std::size_t>(i)]);
        b.conn.push_back(n);
        set.push_back(n);
      }
    }
  };
  // Which set last took each element (its number + 1): a repeated id is taken once, without a
  // hash set per set (a set may list tens of millions of ids).
  std::vector<std::size_t> taken_by(d.elements.size(), 0);
  for (std::size_t k = 0; k < d.element_sets.size(); ++k) {
    const DeckMesh::Set& s = d.element_sets[k];
    std::vector<std::size_t> members;
    for (const std::size_t id : s.ids) {
      const auto it = element_index.find(id);
      if (it == element_index.end())
        throw FormatError(file, s.where, "element " + std::to_string(id) + " is not defined");
      if (taken_by[it->second] != k + 1) {
        taken_by[it->second] = k + 1;
        members.push_back(it->second);
      }
    }
    add_group(s.name, members);
  }
  if (!d.has_all) {
    int top = 0;
    for (const auto& el : d.elements) top = std::max(top, dimension(el.type));
    std::vector<std::size_t> members;
    for (std::size_t e = 0; e < d.elements.size(); ++e)
      if (dimension(d.elements[e].type) == top) members.push_back(e);
    add_group("all", members);
  }
  for (const DeckMesh::Set& s : d.node_sets) {
    std::vector<Index>& set = mesh.node_groups[s.name];
    for (const std::size_t id : s.ids) {
      const auto it = node_index.find(id);
      if (it == node_index.end()) throw FormatError(file, s.where, "node " + std::to_string(id) + " is not defined");
      set.push_back(it->second);
    }
  }
  for (auto& [name, set] : mesh.node_groups) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    set.shrink_to_fit();
  }
  if (report) {
    report->element_counts = element_counts(mesh);
    report->nodes = mesh.num_nodes();
    report->meshed = false;
    report->gmsh_log.clear();
    report->seconds = seconds_since(start);
  }
  return mesh;
}

}  // namespace ffr::preproc::detail
