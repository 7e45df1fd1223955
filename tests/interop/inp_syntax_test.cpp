// The deck syntax the .inp reader takes (Abaqus Keywords Reference: keyword and data lines,
// "**" comments, continuation of keyword lines and of element data lines, GENERATE, sets
// named in set data, case-insensitive keywords and names), the node orders of the Abaqus
// manual's C3D10 and C3D20 against gmsh's ("Node ordering" of the gmsh reference manual), and
// every refusal: file, line and what was expected, exit status 2, no SID.
#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "mesh/bdf_reader.hpp"
#include "mesh/inp_reader.hpp"
#include "deck_refusal.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

namespace {

preproc::Mesh read(const test::TempDir& dir, const std::string& deck) {
  test::write_text(dir / "d.inp", deck);
  return preproc::detail::read_inp((dir / "d.inp").string(), nullptr);
}

const preproc::ElementBlock& block(const preproc::Mesh& m, const std::string& group) {
  for (const auto& b : m.blocks)
    if (b.group == group) return b;
  throw std::runtime_error("no block " + group);
}

const char* kTwoBricks = R"(** a comment line
*Heading
 two bricks and a skin
*node, nset=NALL
1, 0, 0, 0
2, 1.0D0, 0, 0
3, 1, 1, 0
4, 0, 1, 0

5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
9, 2, 0, 0
10, 2, 1, 0
11, 2, 0, 1
12, 2, 1, 1
*ELEMENT, TYPE=C3D8I,
 ELSET=Block
1, 1, 2, 3, 4,
5, 6, 7, 8
2, 2, 9, 10, 3, 6, 11, 12, 7
*Element, type=s4, elset=Skin
10, 1, 2, 6, 5
*ELSET, ELSET=first
1
*ELSET, ELSET=both
FIRST, 2
*NSET, NSET=ends, GENERATE
9, 12, 1
*NSET, nset=block
1
)";

}  // namespace

TEST(InpSyntax, SetsBlocksAndNodes) {
  test::TempDir dir("inp_syntax");
  const preproc::Mesh m = read(dir, kTwoBricks);
  ASSERT_EQ(m.num_nodes(), 12);
  // Blocks per set, in the order the sets are defined, then "all" (the bricks).
  std::vector<std::string> groups;
  for (const auto& b : m.blocks) groups.push_back(b.group + ":" + preproc::name(b.type) + ":" + std::to_string(b.size()));
  EXPECT_EQ(groups, (std::vector<std::string>{"Block:HEX8:2", "Skin:QUAD4:1", "first:HEX8:1", "both:HEX8:2", "all:HEX8:2"}));
  EXPECT_EQ(block(m, "both").tags, (std::vector<std::size_t>{1, 2}));
  EXPECT_EQ(block(m, "Skin").tags, (std::vector<std::size_t>{10}));
  // Element 2 in deck order: nodes 2, 9, 10, 3, 6, 11, 12, 7.
  const auto& b = block(m, "Block");
  const std::vector<std::size_t> expected{2, 9, 10, 3, 6, 11, 12, 7};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(m.node_tag(b.element(1)[i]), expected[static_cast<std::size_t>(i)]);
  // The Fortran exponent of node 2.
  const Eigen::MatrixX3d x1 = m.element_coords(b, 0);
  EXPECT_EQ(x1(1, 0), 1.0);
  // Node groups: *NODE's NSET, GENERATE, an element set's nodes joined with the node set of the
  // same name (spelled as the element set).
  EXPECT_EQ(m.node_groups.at("NALL").size(), 12u);
  std::vector<std::size_t> ends;
  for (const auto n : m.node_groups.at("ends")) ends.push_back(m.node_tag(n));
  std::sort(ends.begin(), ends.end());
  EXPECT_EQ(ends, (std::vector<std::size_t>{9, 10, 11, 12}));
  EXPECT_EQ(m.node_groups.at("Block").size(), 12u);
  EXPECT_EQ(m.node_groups.at("Skin").size(), 4u);
  EXPECT_EQ(m.node_groups.count("block"), 0u);
}

// One element written in Abaqus order (nodes at the corners and the edge midpoints the Abaqus
// manual's figure gives) read in gmsh order: gmsh node k must sit at the midpoint of gmsh's
// edge k (gmsh reference manual).
TEST(InpSyntax, QuadraticNodeOrders) {
  test::TempDir dir("inp_order");
  struct Case {
    const char* type;
    std::vector<Eigen::Vector3d> corners;
    std::vector<std::pair<int, int>> abaqus_edges, gmsh_edges;  // 1-based / 0-based corners
  };
  const std::vector<Case> cases = {
      {"C3D10",
       {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
       {{1, 2}, {2, 3}, {3, 1}, {1, 4}, {2, 4}, {3, 4}},
       {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}},
      {"C3D20",
       {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
       {{1, 2}, {2, 3}, {3, 4}, {4, 1}, {5, 6}, {6, 7}, {7, 8}, {8, 5}, {1, 5}, {2, 6}, {3, 7}, {4, 8}},
       {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3}, {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}}},
  };
  for (const Case& c : cases) {
    std::ostringstream deck;
    deck << "*NODE\n";
    std::vector<Eigen::Vector3d> x = c.corners;
    for (const auto& [a, b] : c.abaqus_edges) x.push_back(0.5 * (c.corners[static_cast<std::size_t>(a - 1)] + c.corners[static_cast<std::size_t>(b - 1)]));
    for (std::size_t i = 0; i < x.size(); ++i) deck << i + 1 << ", " << x[i].x() << ", " << x[i].y() << ", " << x[i].z() << "\n";
    deck << "*ELEMENT, TYPE=" << c.type << "\n1";
    for (std::size_t i = 0; i < x.size(); ++i) deck << (i == 14 ? ",\n" : ", ") << i + 1;  // 16 entries a line at most
    deck << "\n";
    const preproc::Mesh m = read(dir, deck.str());
    const Eigen::MatrixX3d xe = m.element_coords(m.blocks.at(0), 0);
    for (std::size_t k = 0; k < c.corners.size(); ++k) EXPECT_EQ((xe.row(static_cast<Eigen::Index>(k)).transpose() - c.corners[k]).norm(), 0.0) << c.type << " corner " << k;
    for (std::size_t k = 0; k < c.gmsh_edges.size(); ++k) {
      const auto [a, b] = c.gmsh_edges[k];
      const Eigen::Vector3d mid = 0.5 * (c.corners[static_cast<std::size_t>(a)] + c.corners[static_cast<std::size_t>(b)]);
      EXPECT_EQ((xe.row(static_cast<Eigen::Index>(c.corners.size() + k)).transpose() - mid).norm(), 0.0)
          << c.type << " gmsh node " << c.corners.size() + k;
    }
  }
}

namespace {

const char* kTet = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";
const char* kTetElement = "*ELEMENT, TYPE=C3D4, ELSET=body\n1, 1, 2, 3, 4\n";
const char* kTetMaterial = "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n*SOLID SECTION, ELSET=body, MATERIAL=STEEL\n";

std::string refusal(const test::TempDir& dir, const std::string& deck, const std::string& group = "body") {
  return test::deck_refusal(dir, "bad.inp", deck, group);
}

}  // namespace

TEST(InpRefusals, EveryBadDeckNamesFileLineAndWhatWasExpected) {
  test::TempDir dir("inp_bad");
  const std::string ok = std::string(kTet) + kTetElement + kTetMaterial;
  struct Case {
    std::string deck, group, expected;
  };
  const std::vector<Case> cases = {
      {ok + "*CLOAD\n1, 1, 5.0\n", "body", "bad.inp: line 14 (*CLOAD): keyword *CLOAD is not supported"},
      {std::string(kTet) + "*ELEMENT, TYPE=C3D15, ELSET=body\n1, 1, 2, 3, 4\n" + kTetMaterial, "body",
       "bad.inp: line 6 (*ELEMENT, TYPE=C3D15, ELSET=body): element type C3D15 is not in ffr's element library (ffr reads C3D4, C3D10, C3D8I, C3D8, C3D20, S3, S4, B31)"},
      {std::string(kTet) + "*ELEMENT, TYPE=C3D8, ELSET=body\n1, 1, 2, 3, 4\n", "body",
       "bad.inp: line 7: element 1: C3D8 has 8 nodes, found 4"},
      {"*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 0\n6, 1, 0, 0\n7, 1, 1, 0\n8, 0, 1, 0\n"
       "*ELEMENT, TYPE=C3D8, ELSET=body\n1, 1, 2, 3, 4, 5, 6, 7, 8\n" + std::string(kTetMaterial), "body",
       "bad.inp: element 1 (HEX8, group body): HEX8 element is degenerate (zero volume)"},
      {std::string(kTet) + "*ELEMENT, TYPE=C3D8R, ELSET=body\n1, 1, 2, 3, 4, 1, 2, 3, 4\n", "body",
       "bad.inp: line 6 (*ELEMENT, TYPE=C3D8R, ELSET=body): C3D8R (reduced or modified integration) is not in ffr's element library"},
      {std::string(kTet) + kTetElement + "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n"
                                         "*SOLID SECTION, ELSET=nothere, MATERIAL=STEEL\n",
       "body", "bad.inp: line 13 (*SOLID SECTION, ELSET=nothere, MATERIAL=STEEL): no element set 'nothere' in the deck"},
      {std::string(kTet) + kTetElement + "*SOLID SECTION, ELSET=body, MATERIAL=STEEL\n", "body",
       "no material 'STEEL' in the deck"},
      {std::string(kTet) + kTetElement + "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*SOLID SECTION, ELSET=body, MATERIAL=STEEL\n",
       "body", "bad.inp: line 8 (*MATERIAL, NAME=STEEL): material STEEL has no *DENSITY"},
      {std::string(kTet) + "*ELEMENT, TYPE=C3D4, ELSET=body\n1, 1, 2, 3, 99\n" + kTetMaterial, "body",
       "bad.inp: line 7: element 1: node 99 is not defined"},
      {std::string(kTet) + "*ELEMENT, TYPE=C3D4, ELSET=body\n1, 1, 2, 3\n" + kTetMaterial, "body",
       "bad.inp: line 7: element 1: C3D4 has 4 nodes, found 3"},
      {ok + "*BOUNDARY\n1, 1, 3\n", "body", "bad.inp: line 14 (*BOUNDARY): *BOUNDARY in the model data is not taken"},
      {ok + "*ELSET, ELSET=more\n1, 7\n", "body", "bad.inp: line 14 (element set more): element 7 is not defined"},
      {ok + "*NODE\n2, 5, 5, 5\n", "body", "bad.inp: line 15: node 2 defined twice (first at line 3)"},
      {ok + "*STEP\n*FREQUENCY\n3\n", "body", "bad.inp: line 14 (*STEP): *STEP without *END STEP"},
      {std::string(kTet) + kTetElement + "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e5, 0.3\n*DENSITY\n7850\n"
                                         "*SOLID SECTION, ELSET=body, MATERIAL=STEEL\n",
       "body", "bad.inp: line 13 (*SOLID SECTION, ELSET=body, MATERIAL=STEEL): sqrt(E / rho) = 5.17 m/s"},
      {std::string(kTet) + kTetElement + "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, x\n", "body",
       "bad.inp: line 10: expected Poisson's ratio nu, found 'x'"},
      {ok, "nowhere", "bad.json: interfaces[0].group: no group 'nowhere' in the mesh"},
      {std::string("*NODE\n1, 0, 0, 0\n*ELSET, ELSET=body\n") + kTetMaterial, "body", "bad.inp: the deck has no elements"},
      {"1, 0, 0, 0\n", "body", "bad.inp: line 1: a data line where a keyword (*...) was expected"},
      // A range of more ids than the deck has lines (each node or element is a line) names ids
      // that are not defined: refused at once (it took 48 s and 6 GB for four such lines).
      {ok + "*NSET, NSET=big, GENERATE\n1, 100000000\n", "body",
       "bad.inp: line 15: GENERATE 1, 100000000, 1 names 100000000 ids, more than the deck's 15 lines define"},
      {ok + "*ELSET, ELSET=big, GENERATE\n1, 31, 2\n", "body", "bad.inp: line 15: GENERATE 1, 31, 2 names 16 ids, more than the deck's 15 lines"},
      {ok + "*ELSET, ELSET=big, GENERATE\n1, 29, 2\n", "body", "bad.inp: line 14 (element set big): element 3 is not defined"},
  };
  for (const Case& c : cases) {
    const std::string what = refusal(dir, c.deck, c.group);
    EXPECT_NE(what.find(c.expected), std::string::npos) << "deck:\n" << c.deck << "\nmessage: " << what << "\nexpected: " << c.expected;
  }
}

// A set named in a set's data lines adds its members each time: 24 lines that each double the
// last set ask for 4 * 2^24 ids (hours and all the memory before; the bound refuses it at the
// line that crosses 5e7 members in all, deck_mesh.hpp).
TEST(InpRefusals, SetsDoublingEachOtherAreBounded) {
  test::TempDir dir("inp_doubling");
  std::string deck = std::string(kTet) + kTetElement + kTetMaterial + "*NSET, NSET=s0\n1, 2, 3, 4\n";
  for (int k = 1; k <= 24; ++k)
    deck += "*NSET, NSET=s" + std::to_string(k) + "\ns" + std::to_string(k - 1) + ", s" + std::to_string(k - 1) + "\n";
  // s_k holds 4 * 2^k ids; the sets reach 4 * (2^(k+1) - 1) > 5e7 in all first at k = 23, line 61.
  const std::string what = refusal(dir, deck);
  EXPECT_NE(what.find("bad.inp: line 61: set s23: the deck's sets would hold more than 50000000 members in all"),
            std::string::npos) << what;
}

// The command line: exit status 2, the message on stderr, no SID written.
TEST(InpRefusals, CommandLineExitsWithTwoAndWritesNothing) {
  test::TempDir dir("inp_cli");
  (void)refusal(dir, std::string(kTet) + "*ELEMENT, TYPE=C3D15, ELSET=body\n1, 1, 2, 3, 4\n" + kTetMaterial);
  const auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "bad.json").string() + " -o " + (dir / "bad.sid.h5").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bad.inp: line 6"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.sid.h5"));
}

// Damaged decks (the example decks cut short at many places, and with bytes replaced): each
// is read or refused with a FormatError, never another exception or a crash.
TEST(DeckRobustness, CutAndDamagedDecksAreReadOrRefused) {
  test::TempDir dir("deck_damage");
  int refused = 0, read_ok = 0;
  for (const char* name : {"arm.inp", "link.bdf"}) {
    const std::string text = formats::read_text_file(test::source(std::string("meshes/fe_interop/") + name));
    const bool inp = std::string(name).find(".inp") != std::string::npos;
    const auto path = dir / name;
    const auto attempt = [&](const std::string& t) {
      test::write_text(path, t);
      try {
        if (inp) (void)preproc::detail::read_inp(path.string(), nullptr);
        else (void)preproc::detail::read_bdf(path.string(), nullptr);
        ++read_ok;
      } catch (const formats::FormatError&) {
        ++refused;
      }
    };
    const std::size_t step = text.size() / 150 + 1;
    for (std::size_t cut = 0; cut < text.size(); cut += step) attempt(text.substr(0, cut));
    const char junk[] = {',', '*', '\n', 'x', '9', ' ', '-', '$', '+', '.'};
    for (std::size_t at = 7, k = 0; at < text.size(); at += step, ++k) {
      std::string t = text;
      t[at] = junk[k % sizeof junk];
      attempt(t);
    }
  }
  EXPECT_GT(refused, 50);
  EXPECT_GT(read_ok, 10);
}
