#pragma once
// The FE mesh as the preprocessor sees it: nodes, element blocks per physical group, and
// node sets per physical group. Built from gmsh (mesh/gmsh_import) or by hand in tests.
//
// Node order inside every element follows gmsh's convention for that element type (the
// gmsh reference manual, "Node ordering"); every element kernel relies on it.

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ffr::preproc {

using Index = std::int64_t;

enum class ElementType {
  Point1,
  Line2, Line3,
  Tri3, Tri6, Quad4, Quad8, Quad9,
  Tet4, Tet10, Hex8, Hex20, Hex27, Wedge6, Wedge15, Wedge18, Pyramid5, Pyramid13, Pyramid14,
};

int num_nodes(ElementType t);
int dimension(ElementType t);     ///< 0 point, 1 line, 2 surface, 3 volume
const char* name(ElementType t);  ///< "TET10", "QUAD4", ...
/// gmsh element type number -> ElementType; throws std::invalid_argument for unsupported ones.
ElementType from_gmsh(int gmsh_type);
int to_gmsh(ElementType t);

/// How the elements of a HEX8 block are formulated (every other type has one formulation).
/// An FE deck names it per element (Abaqus/CalculiX C3D8I or C3D8, Nastran's PSOLID ISOP), so
/// it is carried per block, and the deck readers put the two in separate blocks.
enum class Hex8Formulation {
  Incompatible,     ///< incompatible modes (Taylor, Beresford & Wilson 1976): C3D8I; ffr's default
  FullIntegration,  ///< plain trilinear brick, 2x2x2 Gauss: C3D8 (locks in bending)
};

struct ElementBlock {
  ElementType type = ElementType::Tet4;
  std::string group;              ///< physical group name the elements belong to
  std::vector<Index> conn;        ///< size() * num_nodes(type) indices into Mesh::x, gmsh order
  std::vector<std::size_t> tags;  ///< gmsh element tags, for error messages (may be empty)
  Hex8Formulation hex8 = Hex8Formulation::Incompatible;  ///< HEX8 blocks only
  Index size() const { return static_cast<Index>(conn.size()) / ffr::preproc::num_nodes(type); }
  const Index* element(Index e) const { return conn.data() + e * ffr::preproc::num_nodes(type); }
};

struct Mesh {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> x;  ///< node coordinates, body frame
  /// gmsh node tag per node (may be empty). gmsh_import numbers the nodes along a space-filling
  /// curve, not in gmsh's order (src/mesh/node_order.hpp): the tags are the way back.
  std::vector<std::size_t> node_tags;
  std::vector<ElementBlock> blocks;
  std::map<std::string, std::vector<Index>> node_groups;        ///< physical group -> sorted node indices

  Index num_nodes() const { return x.rows(); }
  Index num_elements() const;
  /// Gathers the coordinates of element e of block b as an (nn x 3) matrix.
  Eigen::MatrixX3d element_coords(const ElementBlock& b, Index e) const;
  /// The gmsh tag of element e of block b if known, else its 1-based position.
  std::size_t element_tag(const ElementBlock& b, Index e) const;
  std::size_t node_tag(Index n) const;
};

/// The type name of a block's elements: name(type), and "HEX8_FULL" for a full-integration HEX8.
std::string block_type_name(const ElementBlock& b);

/// Element type name (block_type_name: "TET10", "HEX8_FULL", ...) -> elements of that type over
/// all blocks, each counted once (an element can be in two groups: "all" and a named one), for
/// the mesh report.
std::map<std::string, Index> element_counts(const Mesh& mesh);


}  // namespace ffr::preproc
