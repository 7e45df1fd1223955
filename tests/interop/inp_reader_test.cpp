// Abaqus/CalculiX input decks (.inp) as a part's geometry.
//
// References, none computed by ffr:
//  - gmsh's own .inp writer (gmsh 4.8, `-format inp`): the deck it writes of a mesh and the
//    MSH 4.1 file of that mesh give the same SID (formats::diff, rtol 1e-9). gmsh orders the
//    deck's element nodes by itself, so this checks the reader's node orders independently.
//  - CalculiX (`ccx` 2.20 from Debian) *FREQUENCY on the very deck ffr-reduce reads, with the
//    deck's *MATERIAL and *SOLID SECTION: the same frequencies to 1e-6 (ccx prints 7 digits).
//  - The element tables of the Abaqus manual (C3D10, C3D20 node numbering) and of the gmsh
//    reference manual ("Node ordering"): a single element written in Abaqus order lands in
//    gmsh order.
#include "ffr/calculix/deck.hpp"
#include "ffr/formats/diff.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "mesh/inp_reader.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

using namespace ffr;

namespace {

// The deck gmsh writes of `msh` (the identical mesh: no re-meshing), with the node sets of
// the physical groups, and without gmsh's plane elements (CPS*, which ffr does not take) and
// their element sets; `c3d8i` renames gmsh's C3D8 to the incompatible-mode C3D8I.
std::string gmsh_deck(const std::filesystem::path& msh, const std::filesystem::path& inp, bool c3d8i = false) {
  const auto r = test::run("gmsh " + msh.string() + " -0 -setnumber Mesh.SaveGroupsOfNodes 1 -format inp -o " + inp.string());
  if (r.status != 0 || !std::filesystem::exists(inp)) throw std::runtime_error("gmsh failed: " + r.output);
  std::istringstream in(formats::read_text_file(inp));
  std::ostringstream out;
  std::string line;
  bool drop = false;
  std::vector<std::string> dropped_sets;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '*' && line.rfind("**", 0) != 0) {
      drop = false;
      if (line.rfind("*ELEMENT", 0) == 0 && line.find("type=C3D") == std::string::npos) {
        drop = true;
        dropped_sets.push_back(line.substr(line.find("ELSET=") + 6));
      }
      // gmsh also lists the plane elements under their physical group's element set.
      if (line.rfind("*ELSET", 0) == 0 && line.find("ELSET=clamp") != std::string::npos) drop = true;
      if (c3d8i && line.find("type=C3D8,") != std::string::npos) line.replace(line.find("type=C3D8,"), 10, "type=C3D8I,");
    }
    if (!drop) out << line << "\n";
  }
  return out.str();
}

struct Bar {
  test::TempDir dir{"interop_inp"};
  std::string deck;
  // A 0.2 x 0.02 x 0.012 bar, clamped at x = 0: tetrahedra of the given order, or (hex) a
  // structured HEX8/HEX20 grid, its linear bricks C3D8I or (c3d8i false) gmsh's C3D8.
  Bar(int order, bool hex, bool c3d8i = true) {
    if (hex)
      test::write_text(dir / "bar.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.2, 0, 0}; Line(1) = {1, 2};
e[] = Extrude{0, 0.02, 0}{Line{1}; Layers{3}; Recombine;};
v[] = Extrude{0, 0, 0.012}{Surface{e[1]}; Layers{2}; Recombine;};
Transfinite Curve{1} = 13;
Physical Volume("body") = {v[1]};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
    else
      test::write_text(dir / "bar.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
    test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", order == 1 ? 0.004 : 0.006, order);
    deck = gmsh_deck(dir / "bar.msh", dir / "gmsh.inp", hex && c3d8i);
  }
  formats::Sid reduce(const std::string& geometry, const std::string& materials, const std::string& extra = "") {
    test::write_text(dir / "part.json", R"({"geometry": ")" + geometry + R"(", )" + materials + R"(
      "interfaces": [{"name": "root", "group": "clamp"}], "visual": false, )" + extra + R"(
      "reduction": {"method": "clamped", "interface": "root", "modes": 6}})");
    return preproc::run_pipeline(preproc::load_part(dir / "part.json"));
  }
};

const char* kSteel = R"("materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],)";
const char* kDeckSteel = "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n*SOLID SECTION, ELSET=body, MATERIAL=STEEL\n";

void expect_same_sid(const formats::Sid& a, const formats::Sid& b) {
  formats::DiffOptions o;
  o.rtol = 1e-9;
  const auto d = formats::diff(a, b, o);
  std::string worst;
  for (const auto& w : d.worst) worst += "\n  " + w.dataset + w.index + ": " + std::to_string(w.a) + " vs " + std::to_string(w.b);
  for (const auto& s : d.structural) worst += "\n  " + s;
  EXPECT_TRUE(d.equivalent) << d.datasets_different << " datasets differ:" << worst;
}

}  // namespace

// gmsh's deck and gmsh's MSH file of one TET10 mesh: the same SID, stiffening included.
TEST(InpDeck, GmshDeckGivesTheSameSidAsItsMsh) {
  Bar bar(2, false);
  test::write_text(bar.dir / "bar.inp", bar.deck);
  const formats::Sid msh = bar.reduce("bar.msh", kSteel, R"("stiffening": true,)");
  const formats::Sid inp = bar.reduce("bar.inp", kSteel, R"("stiffening": true,)");
  expect_same_sid(msh, inp);
}

// The deck's own material and section, where the part file gives none: the same SID.
TEST(InpDeck, DeckMaterialStandsInForThePartFiles) {
  Bar bar(2, false);
  test::write_text(bar.dir / "bar.inp", bar.deck + kDeckSteel);
  expect_same_sid(bar.reduce("bar.msh", kSteel), bar.reduce("bar.inp", ""));
  // The part file's material wins over the deck's for its group.
  test::write_text(bar.dir / "bar.inp", bar.deck + "*MATERIAL, NAME=SOFT\n*ELASTIC\n7e10, 0.33\n*DENSITY\n2700\n"
                                                    "*SOLID SECTION, ELSET=body, MATERIAL=SOFT\n");
  expect_same_sid(bar.reduce("bar.msh", kSteel), bar.reduce("bar.inp", kSteel));
}

// CalculiX on the deck ffr-reduce reads (material and section from the deck, the clamp held in
// a *STEP ffr passes over) against ffr's clamped modes. C3D20 integrates stiffness and mass
// with 27 points, exactly as ffr's HEX20 on this box: 1e-6 (ccx prints 7 digits). C3D8 is the
// trilinear brick with 2x2x2 Gauss points for stiffness and mass (CalculiX manual, "Eight-node
// brick element (C3D8)"), exact on this box's rectangular bricks, as ffr's full-integration
// HEX8 (2x2x2 stiffness, 3x3x3 mass): 1e-6. CalculiX's C3D10 integrates with 4 points
// (CalculiX manual, C3D10), which is not exact for the quadratic tetrahedron's mass, where
// ffr's is: its frequencies sit 2.5e-6 off here, hence 1e-5. (ffr's TET4 and incompatible-mode
// HEX8 are not CalculiX's C3D4 and C3D8I in dynamics: 1.6 % and 2.5 % apart on this bar, so no
// element-level comparison is made with them here.)
struct CcxCase {
  int order;
  bool hex;
  double tol;
  const char* name;
  bool c3d8i = true;
};
class InpCalculix : public ::testing::TestWithParam<CcxCase> {};

TEST_P(InpCalculix, FrequenciesOfTheDeck) {
  const CcxCase c = GetParam();
  Bar bar(c.order, c.hex, c.c3d8i);
  if (c.hex && c.order == 1) {
    ASSERT_NE(bar.deck.find("type=C3D8,"), std::string::npos);
  }
  test::write_text(bar.dir / "job.inp", bar.deck + kDeckSteel + "*STEP\n*BOUNDARY\nclamp, 1, 3\n*FREQUENCY\n6\n*END STEP\n");
  const formats::Sid sid = bar.reduce("job.inp", "");
  const auto r = test::run("cd " + bar.dir.path().string() + " && OMP_NUM_THREADS=1 ccx -i job");
  const std::vector<double> ccx = calculix::read_frequencies(bar.dir / "job.dat");
  ASSERT_EQ(ccx.size(), 6u) << r.output.substr(0, 2000);
  double worst = 0;
  for (Eigen::Index k = 0; k < 6; ++k) {
    const double rel = sid.refmod.frequency_hz(k) / ccx[static_cast<std::size_t>(k)] - 1.0;
    worst = std::max(worst, std::abs(rel));
    EXPECT_LE(std::abs(rel), c.tol) << "mode " << k + 1 << ": " << sid.refmod.frequency_hz(k) << " Hz (ffr) vs "
                                    << ccx[static_cast<std::size_t>(k)] << " Hz (CalculiX)";
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
  std::printf("%s: largest relative difference of the 6 frequencies to CalculiX %.2e\n", c.name, worst);
}

INSTANTIATE_TEST_SUITE_P(Elements, InpCalculix,
                         ::testing::Values(CcxCase{2, true, 1e-6, "C3D20"}, CcxCase{2, false, 1e-5, "C3D10"},
                                           CcxCase{1, true, 1e-6, "C3D8", false}),
                         [](const auto& info) { return std::string(info.param.name); });

// A QUAD4 plate: gmsh's deck with its plane elements (CPS4) declared as the shells they are
// meshed for (S4, the same node order), gmsh's edge elements (T3D2) dropped for their node
// set, and a *SHELL SECTION: the same SID as the MSH file with the part file's shell.
TEST(InpDeck, ShellDeckGivesTheSameSidAsItsMsh) {
  test::TempDir dir("interop_shell");
  test::write_text(dir / "plate.geo", R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 0.3, 0.1};
Recombine Surface{1};
Physical Surface("skin") = {1};
Physical Curve("edge") = Curve In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
  const auto r = test::run("gmsh -2 -clmax 0.02 -format msh41 " + (dir / "plate.geo").string() + " -o " + (dir / "plate.msh").string() +
                           " && gmsh " + (dir / "plate.msh").string() + " -0 -setnumber Mesh.SaveGroupsOfNodes 1 -format inp -o " +
                           (dir / "gmsh.inp").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::istringstream in(formats::read_text_file(dir / "gmsh.inp"));
  std::ostringstream deck;
  std::string line;
  bool drop = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '*' && line.rfind("**", 0) != 0) {
      drop = line.find("type=T3D2") != std::string::npos || line.find("ELSET=edge") != std::string::npos;
      if (const auto p = line.find("type=CPS4"); p != std::string::npos) line.replace(p, 9, "type=S4");
    }
    if (!drop) deck << line << "\n";
  }
  ASSERT_NE(deck.str().find("type=S4"), std::string::npos);
  test::write_text(dir / "plate.inp", deck.str() + "*MATERIAL, NAME=AL\n*ELASTIC\n7e10, 0.33\n*DENSITY\n2700\n"
                                                   "*SHELL SECTION, ELSET=skin, MATERIAL=AL\n0.002\n");
  const auto reduce = [&](const std::string& geometry, const std::string& shells) {
    test::write_text(dir / "part.json", R"({"geometry": ")" + geometry + R"(", "visual": false, )" + shells + R"(
      "interfaces": [{"name": "root", "group": "edge"}],
      "reduction": {"method": "clamped", "interface": "root", "modes": 6}})");
    return preproc::run_pipeline(preproc::load_part(dir / "part.json"));
  };
  expect_same_sid(reduce("plate.msh", R"("shells": [{"group": "skin", "thickness": 0.002, "E": 7e10, "nu": 0.33, "rho": 2700}],)"),
                  reduce("plate.inp", ""));
}

// A B31 beam: gmsh's deck of a line mesh (its T3D2 truss elements declared as the B31 beams
// they are meshed for, the same two nodes), with the section from the part file's "beams":
// the same SID as the MSH file.
TEST(InpDeck, BeamDeckGivesTheSameSidAsItsMsh) {
  test::TempDir dir("interop_beam");
  test::write_text(dir / "spar.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.5, 0.1, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 21;
Physical Curve("spar") = {1};
Physical Point("root") = {1};
)");
  const auto r = test::run("gmsh -1 -format msh41 " + (dir / "spar.geo").string() + " -o " + (dir / "spar.msh").string() +
                           " && gmsh " + (dir / "spar.msh").string() + " -0 -setnumber Mesh.SaveGroupsOfNodes 1 -format inp -o " +
                           (dir / "gmsh.inp").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::string deck = formats::read_text_file(dir / "gmsh.inp");
  ASSERT_NE(deck.find("type=T3D2"), std::string::npos);
  deck.replace(deck.find("type=T3D2"), 9, "type=B31");
  // gmsh's point element of the root (no element ffr takes) and its set: the node set stays.
  std::istringstream in(deck);
  std::ostringstream out;
  std::string line;
  bool drop = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '*' && line.rfind("**", 0) != 0)
      drop = (line.rfind("*ELEMENT", 0) == 0 && line.find("type=B31") == std::string::npos) || line.find("ELSET=root") != std::string::npos;
    if (!drop) out << line << "\n";
  }
  test::write_text(dir / "spar.inp", out.str());
  const auto reduce = [&](const std::string& geometry) {
    test::write_text(dir / "part.json", R"({"geometry": ")" + geometry + R"(", "visual": false,
      "beams": [{"group": "spar", "E": 2.1e11, "nu": 0.3, "rho": 7850,
                 "section": {"A": 4e-4, "Iy": 2e-8, "Iz": 3e-8, "J": 4e-8, "ky": 0.85, "kz": 0.85}, "y_axis": [0, 0, 1]}],
      "interfaces": [{"name": "root", "group": "root"}],
      "reduction": {"method": "clamped", "interface": "root", "modes": 6}})");
    return preproc::run_pipeline(preproc::load_part(dir / "part.json"));
  };
  expect_same_sid(reduce("spar.msh"), reduce("spar.inp"));
}

// C3D8 and C3D8I in one deck: every other brick of the bar's C3D8 block declared C3D8I. The
// reader keeps the two in blocks of their own, each with its elements, and the reduction uses
// both kernels. Reference: the incompatible-mode stiffness is the full-integration one less the
// condensed term K_ua K_aa^-1 K_au (positive semi-definite; Taylor, Beresford & Wilson 1976),
// and both share the trilinear consistent mass, so by the Courant–Fischer minimax principle
// each frequency of the mixed bar lies between the all-C3D8I and the all-C3D8 bar's. A reader
// or assembly that took one kernel for both would land on one of the two bounds.
TEST(InpDeck, C3D8AndC3D8IMixInOneDeck) {
  Bar bar(1, true, false);
  std::istringstream in(bar.deck);
  std::ostringstream full, incompatible, mixed;
  std::string line, even;
  bool bricks = false;
  while (std::getline(in, line)) {
    const bool keyword = !line.empty() && line[0] == '*';
    if (keyword && bricks) mixed << "*ELEMENT, type=C3D8I, ELSET=Volume1\n" << even;
    if (keyword) bricks = line.find("type=C3D8,") != std::string::npos;
    std::string as_i = line;
    if (bricks && keyword) as_i.replace(as_i.find("type=C3D8,"), 10, "type=C3D8I,");
    full << line << "\n";
    incompatible << as_i << "\n";
    if (bricks && !keyword && std::stoul(line.substr(0, line.find(','))) % 2 == 0) even += line + "\n";
    else mixed << line << "\n";
  }
  ASSERT_FALSE(even.empty());
  test::write_text(bar.dir / "mixed.inp", mixed.str() + kDeckSteel);
  test::write_text(bar.dir / "full.inp", full.str() + kDeckSteel);
  test::write_text(bar.dir / "incompatible.inp", incompatible.str() + kDeckSteel);

  const preproc::Mesh mesh = preproc::detail::read_inp((bar.dir / "mixed.inp").string(), nullptr);
  int blocks = 0;
  for (const auto& b : mesh.blocks) {
    if (b.group != "body") continue;
    ++blocks;
    ASSERT_EQ(b.type, preproc::ElementType::Hex8);
    const bool want_full = b.hex8 == preproc::Hex8Formulation::FullIntegration;
    for (const std::size_t tag : b.tags) EXPECT_EQ(tag % 2 == 1, want_full) << "element " << tag;
  }
  EXPECT_EQ(blocks, 2);
  EXPECT_EQ(preproc::element_counts(mesh).count("HEX8_FULL"), 1u);

  const formats::Sid f_mix = bar.reduce("mixed.inp", ""), f_full = bar.reduce("full.inp", ""),
                     f_inc = bar.reduce("incompatible.inp", "");
  for (Eigen::Index k = 0; k < 6; ++k) {
    const double lo = f_inc.refmod.frequency_hz(k), hi = f_full.refmod.frequency_hz(k), m = f_mix.refmod.frequency_hz(k);
    // The full-integration bar is stiffer (shear locking: 33 % in the first bending mode here,
    // 0.3 % in the fifth); the mixed one strictly inside.
    std::printf("mode %d: C3D8I %.2f Hz < mixed %.2f Hz < C3D8 %.2f Hz\n", static_cast<int>(k + 1), lo, m, hi);
    EXPECT_GT(hi, lo * 1.001) << "mode " << k + 1;
    EXPECT_GT(m, lo + 0.05 * (hi - lo)) << "mode " << k + 1 << ": " << lo << " < " << m << " < " << hi;
    EXPECT_LT(m, hi - 0.05 * (hi - lo)) << "mode " << k + 1 << ": " << lo << " < " << m << " < " << hi;
  }
  EXPECT_EQ(f_full.provenance.element_counts.count("HEX8_FULL"), 1u);
  EXPECT_EQ(f_inc.provenance.element_counts.count("HEX8_FULL"), 0u);
  EXPECT_NE(f_full.provenance.mesh_sha256, f_inc.provenance.mesh_sha256);
}

// Nastran's CHEXA with 8 grids and PSOLID IN = 2, ISOP = FULL (the isoparametric brick with
// 2x2x2 Gauss points, Quick Reference Guide, PSOLID) is C3D8: gmsh's bulk data of the bar's
// HEX8 mesh (large field, 9 digits) against CalculiX's C3D8 on gmsh's .inp deck of that mesh.
TEST(BdfCalculix, ChexaWithFullIntegrationIsCalculixsC3D8) {
  Bar bar(1, true, false);
  test::write_text(bar.dir / "job.inp", bar.deck + kDeckSteel + "*STEP\n*BOUNDARY\nclamp, 1, 3\n*FREQUENCY\n6\n*END STEP\n");
  const auto r = test::run("cd " + bar.dir.path().string() + " && OMP_NUM_THREADS=1 ccx -i job");
  const std::vector<double> ccx = calculix::read_frequencies(bar.dir / "job.dat");
  ASSERT_EQ(ccx.size(), 6u) << r.output.substr(0, 2000);

  const auto g = test::run("gmsh " + (bar.dir / "bar.msh").string() + " -0 -setnumber Mesh.BdfFieldFormat 2 -format bdf -o " +
                           (bar.dir / "gmsh.bdf").string());
  ASSERT_EQ(g.status, 0) << g.output;
  // Without the clamp's CQUAD4s (gmsh's surface group); the clamp's grids as SET1 9.
  std::istringstream in(formats::read_text_file(bar.dir / "gmsh.bdf"));
  std::ostringstream deck;
  std::string line;
  bool drop = false;
  int hexes = 0;
  while (std::getline(in, line)) {
    const bool continuation = line.empty() || line[0] == '+' || line[0] == '*' || line[0] == ' ' || line[0] == ',';
    if (!continuation) drop = line.rfind("CQUAD4", 0) == 0 || line.rfind("ENDDATA", 0) == 0;
    if (!continuation && line.rfind("CHEXA", 0) == 0) ++hexes;
    if (!drop) deck << line << "\n";
  }
  ASSERT_GT(hexes, 0);
  preproc::PartSpec p;
  p.geometry = bar.dir / "bar.msh";
  const preproc::Mesh msh = preproc::load_mesh(p);
  for (const preproc::Index n : msh.node_groups.at("clamp")) deck << "SET1,9," << msh.node_tag(n) << "\n";
  // gmsh writes the volume's physical tag, 1, as the property id.
  deck << "PSOLID,1,3,,2,,FULL\nMAT1,3,2.1+11,,0.3,7850.\nENDDATA\n";
  test::write_text(bar.dir / "bar.bdf", deck.str());
  test::write_text(bar.dir / "part.json", R"({"geometry": "bar.bdf", "visual": false,
    "interfaces": [{"name": "root", "group": "set9"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 6}})");
  const formats::Sid sid = preproc::run_pipeline(preproc::load_part(bar.dir / "part.json"));
  EXPECT_EQ(sid.provenance.element_counts.count("HEX8_FULL"), 1u);
  double worst = 0;
  for (Eigen::Index k = 0; k < 6; ++k) {
    const double rel = sid.refmod.frequency_hz(k) / ccx[static_cast<std::size_t>(k)] - 1.0;
    worst = std::max(worst, std::abs(rel));
    EXPECT_LE(std::abs(rel), 1e-6) << "mode " << k + 1 << ": " << sid.refmod.frequency_hz(k) << " Hz (ffr) vs "
                                   << ccx[static_cast<std::size_t>(k)] << " Hz (CalculiX)";
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
  std::printf("CHEXA, PSOLID IN = 2, ISOP = FULL: largest relative difference of the 6 frequencies to CalculiX's C3D8 %.2e\n", worst);
}
