#include "ffr/preproc/mesh/mesh.hpp"

#include <set>
#include <stdexcept>
#include <string>

namespace ffr::preproc {

namespace {
struct TypeInfo {
  ElementType type;
  int gmsh, nodes, dim;
  const char* name;
};
// gmsh element type numbers: gmsh reference manual, "MSH file format", element types.
constexpr TypeInfo kTypes[] = {
    {ElementType::Point1, 15, 1, 0, "POINT1"},    {ElementType::Line2, 1, 2, 1, "LINE2"},
    {ElementType::Line3, 8, 3, 1, "LINE3"},       {ElementType::Tri3, 2, 3, 2, "TRI3"},
    {ElementType::Tri6, 9, 6, 2, "TRI6"},         {ElementType::Quad4, 3, 4, 2, "QUAD4"},
    {ElementType::Quad8, 16, 8, 2, "QUAD8"},      {ElementType::Quad9, 10, 9, 2, "QUAD9"},
    {ElementType::Tet4, 4, 4, 3, "TET4"},         {ElementType::Tet10, 11, 10, 3, "TET10"},
    {ElementType::Hex8, 5, 8, 3, "HEX8"},         {ElementType::Hex20, 17, 20, 3, "HEX20"},
    {ElementType::Hex27, 12, 27, 3, "HEX27"},     {ElementType::Wedge6, 6, 6, 3, "WEDGE6"},
    {ElementType::Wedge15, 18, 15, 3, "WEDGE15"}, {ElementType::Wedge18, 13, 18, 3, "WEDGE18"},
    {ElementType::Pyramid5, 7, 5, 3, "PYRAMID5"}, {ElementType::Pyramid13, 19, 13, 3, "PYRAMID13"},
    {ElementType::Pyramid14, 14, 14, 3, "PYRAMID14"},
};
const TypeInfo& info(ElementType t) {
  for (const auto& i : kTypes)
    if (i.type == t) return i;
  throw std::logic_error("unknown ElementType");
}
}  // namespace

int num_nodes(ElementType t) { return info(t).nodes; }
int dimension(ElementType t) { return info(t).dim; }
const char* name(ElementType t) { return info(t).name; }
int to_gmsh(ElementType t) { return info(t).gmsh; }

ElementType from_gmsh(int gmsh_type) {
  for (const auto& i : kTypes)
    if (i.gmsh == gmsh_type) return i.type;
  throw std::invalid_argument("unsupported gmsh element type " + std::to_string(gmsh_type));
}

Index Mesh::num_elements() const {
  Index n = 0;
  for (const auto& b : blocks) n += b.size();
  return n;
}

Eigen::MatrixX3d Mesh::element_coords(const ElementBlock& b, Index e) const {
  const int nn = ffr::preproc::num_nodes(b.type);
  Eigen::MatrixX3d xe(nn, 3);
  const Index* c = b.element(e);
  for (int i = 0; i < nn; ++i) xe.row(i) = x.row(c[i]);
  return xe;
}

std::size_t Mesh::element_tag(const ElementBlock& b, Index e) const {
  return b.tags.empty() ? static_cast<std::size_t>(e + 1) : b.tags[static_cast<std::size_t>(e)];
}

std::size_t Mesh::node_tag(Index n) const {
  return node_tags.empty() ? static_cast<std::size_t>(n + 1) : node_tags[static_cast<std::size_t>(n)];
}

std::string block_type_name(const ElementBlock& b) {
  if (b.type == ElementType::Hex8 && b.hex8 == Hex8Formulation::FullIntegration) return "HEX8_FULL";
  return name(b.type);
}

std::map<std::string, Index> element_counts(const Mesh& mesh) {
  std::map<std::string, std::set<std::size_t>> tags;
  for (const auto& b : mesh.blocks) tags[block_type_name(b)].insert(b.tags.begin(), b.tags.end());
  std::map<std::string, Index> counts;
  for (const auto& [t, s] : tags) counts[t] = static_cast<Index>(s.size());
  return counts;
}

}  // namespace ffr::preproc
