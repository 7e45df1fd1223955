// ffr's own reader of ASCII MSH 4.1 files (preproc/src/mesh/msh41_reader.hpp) against gmsh's
// import of the same files: the same nodes in the same order, the same element blocks, tags and
// node groups, element for element, for files gmsh itself wrote (solids of order 1 and 2, two
// volumes with named, unnamed and point groups, a surface mesh); and files it leaves to gmsh
// (MSH 2.2, binary, truncated), which load_mesh still reads, or refuses with gmsh's error.
#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/part/part.hpp"
#include "mesh/msh41_reader.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace ffr;

namespace {

preproc::PartSpec part_for(const std::filesystem::path& msh) {
  preproc::PartSpec part;
  part.file = msh.parent_path() / "part.json";
  part.geometry = msh;
  return part;
}

void expect_same(const preproc::Mesh& a, const preproc::Mesh& b) {
  ASSERT_EQ(a.x.rows(), b.x.rows());
  EXPECT_TRUE(a.x == b.x);
  EXPECT_EQ(a.node_tags, b.node_tags);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t k = 0; k < a.blocks.size(); ++k) {
    SCOPED_TRACE("block " + std::to_string(k) + " (" + b.blocks[k].group + ")");
    EXPECT_EQ(a.blocks[k].type, b.blocks[k].type);
    EXPECT_EQ(a.blocks[k].group, b.blocks[k].group);
    EXPECT_EQ(a.blocks[k].conn, b.blocks[k].conn);
    EXPECT_EQ(a.blocks[k].tags, b.blocks[k].tags);
  }
  EXPECT_EQ(a.node_groups, b.node_groups);
}

// Reads `msh` both ways and compares; the report too.
void compare(const std::filesystem::path& msh) {
  SCOPED_TRACE(msh.filename().string());
  preproc::MeshReport own, theirs;
  const auto native = preproc::detail::read_msh41(msh.string(), &own);
  ASSERT_TRUE(native.has_value()) << "the reader left a file gmsh wrote in MSH 4.1 to gmsh";
  const preproc::Mesh gmsh = preproc::detail::load_mesh_with_gmsh(part_for(msh), &theirs);
  expect_same(*native, gmsh);
  EXPECT_EQ(own.element_counts, theirs.element_counts);
  EXPECT_EQ(own.nodes, theirs.nodes);
  EXPECT_FALSE(own.meshed);
  // load_mesh takes the reader's mesh.
  expect_same(preproc::load_mesh(part_for(msh)), gmsh);
}

// Two boxes side by side: two named volume groups, a named surface group, an unnamed point
// group (named by its tag), so the default group "all" is added.
const char* kTwoBoxes = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Box(2) = {2, 0, 0, 1, 1, 1};
Coherence;
Physical Volume("left") = {1};
Physical Volume("right") = {2};
Physical Surface("clamp") = {1};
Physical Point(7) = {1};
)";

// A surface alone, its own group "all": gmsh_import adds none then.
const char* kPlate = R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 3, 1};
Physical Surface("all") = {1};
Physical Curve("edge") = {4};
)";

}  // namespace

TEST(Msh41Reader, GivesGmshsMeshForFilesGmshWrote) {
  test::TempDir dir("msh41");
  const std::filesystem::path cantilever = std::filesystem::path(FFR_SOURCE_DIR) / "meshes/cantilever/cantilever.geo";
  for (const int order : {1, 2}) {
    const auto msh = dir / ("cantilever" + std::to_string(order) + ".msh");
    test::gmsh_mesh(cantilever, msh, 0.02, order);
    compare(msh);
  }
  test::write_text(dir / "boxes.geo", kTwoBoxes);
  test::gmsh_mesh(dir / "boxes.geo", dir / "boxes.msh", 0.3, 2);
  compare(dir / "boxes.msh");
  test::write_text(dir / "plate.geo", kPlate);
  test::gmsh_mesh(dir / "plate.geo", dir / "plate.msh", 0.25, 1);
  compare(dir / "plate.msh");
}

TEST(Msh41Reader, LeavesOtherFilesToGmsh) {
  test::TempDir dir("msh41-other");
  // MSH 2.2: gmsh reads it.
  const std::filesystem::path msh22 = std::filesystem::path(FFR_SOURCE_DIR) / "tests/solid_elements/data/box_tet4.msh";
  EXPECT_FALSE(preproc::detail::read_msh41(msh22.string(), nullptr).has_value());
  EXPECT_GT(preproc::load_mesh(part_for(msh22)).num_nodes(), 0);

  // Binary MSH 4.1.
  test::write_text(dir / "boxes.geo", kTwoBoxes);
  const auto r = test::run("gmsh -3 -bin -format msh41 " + (dir / "boxes.geo").string() + " -o " +
                                   (dir / "boxes_bin.msh").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(preproc::detail::read_msh41((dir / "boxes_bin.msh").string(), nullptr).has_value());
  EXPECT_GT(preproc::load_mesh(part_for(dir / "boxes_bin.msh")).num_nodes(), 0);

  // Truncated in its elements: left to gmsh, whose error names the file.
  test::gmsh_mesh(dir / "boxes.geo", dir / "boxes.msh", 0.3, 1);
  std::string text = formats::read_text_file(dir / "boxes.msh");
  const auto cut = text.find("$Elements");
  ASSERT_NE(cut, std::string::npos);
  test::write_text(dir / "cut.msh", text.substr(0, cut + (text.size() - cut) / 2));
  EXPECT_FALSE(preproc::detail::read_msh41((dir / "cut.msh").string(), nullptr).has_value());
  try {
    preproc::load_mesh(part_for(dir / "cut.msh"));
    FAIL() << "a truncated mesh file was read";
  } catch (const formats::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.msh"), std::string::npos) << e.what();
  }

  // A missing file: gmsh_import's own message.
  try {
    preproc::load_mesh(part_for(dir / "missing.msh"));
    FAIL() << "a missing file was read";
  } catch (const formats::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}
