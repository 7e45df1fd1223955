// Node sets of the physical groups read from a mesh file. load_mesh takes them from the
// groups' element connectivity (gmsh's getNodesForPhysicalGroup builds the same set, slowly);
// the expected sets below are read off the file by hand: the nodes of each group's elements.
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/part/part.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <set>

using namespace ffr;

namespace {

// Two positive TET4 in two volume entities (one group "body"), a triangle, a line and a point,
// each in a group of its own; node tags not 1..n, so a mix-up of tags and indices shows.
const char* kMsh = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
4
0 4 "tip"
1 3 "edge"
2 2 "face"
3 1 "body"
$EndPhysicalNames
$Nodes
5
10 0 0 0
20 1 0 0
30 0 1 0
40 0 0 1
50 1 1 1
$EndNodes
$Elements
5
1 4 2 1 1 10 20 30 40
2 4 2 1 2 20 50 30 40
3 2 2 2 3 10 20 30
4 1 2 3 4 40 50
5 15 2 4 5 50
$EndElements
)";

std::set<std::size_t> tags_of(const preproc::Mesh& mesh, const std::string& group) {
  std::set<std::size_t> tags;
  for (auto i : mesh.node_groups.at(group)) tags.insert(mesh.node_tags.at(static_cast<std::size_t>(i)));
  return tags;
}

}  // namespace

TEST(MeshGroups, NodeSetsAreTheNodesOfEachGroupsElements) {
  test::TempDir dir("mesh_groups");
  test::write_text(dir / "m.msh", kMsh);
  preproc::PartSpec part;
  part.file = dir / "p.json";
  part.geometry = dir / "m.msh";
  const preproc::Mesh mesh = preproc::load_mesh(part);

  using Tags = std::set<std::size_t>;
  EXPECT_EQ(tags_of(mesh, "body"), (Tags{10, 20, 30, 40, 50}));
  EXPECT_EQ(tags_of(mesh, "all"), (Tags{10, 20, 30, 40, 50}));  // default group: the volumes
  EXPECT_EQ(tags_of(mesh, "face"), (Tags{10, 20, 30}));
  EXPECT_EQ(tags_of(mesh, "edge"), (Tags{40, 50}));
  EXPECT_EQ(tags_of(mesh, "tip"), (Tags{50}));
  // Stored once each, ascending (what the interfaces and the DOF maps expect).
  for (const auto& [name, nodes] : mesh.node_groups) {
    EXPECT_TRUE(std::is_sorted(nodes.begin(), nodes.end())) << name;
    EXPECT_EQ(std::adjacent_find(nodes.begin(), nodes.end()), nodes.end()) << name;
  }
}
