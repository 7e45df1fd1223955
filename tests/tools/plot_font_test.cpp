// ffr-info's plot text: every printable ASCII character has a glyph of its own (the font once
// lacked most capitals, so `road_FL` printed as `road_`), a rendered label covers exactly its
// glyphs' pixels cell by cell, and legends name components by the output's type, which ffr-sim
// writes into the results file.
#include "font5x7.hpp"
#include "plot_axes.hpp"
#include "png.hpp"

#include "ffr/formats/results_io.hpp"

#include <gtest/gtest.h>

#include <bitset>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

using namespace ffr::info;

namespace {
int pixels(const Glyph& g) {
  int n = 0;
  for (auto row : g) n += static_cast<int>(std::bitset<8>(row).count());
  return n;
}
}  // namespace

TEST(PlotFont, EveryPrintableCharacterHasItsOwnGlyph) {
  std::set<Glyph> seen;
  for (int c = 0x20; c <= 0x7E; ++c) {
    const Glyph& g = glyph(static_cast<char>(c));
    for (auto row : g) EXPECT_EQ(row & ~0x1F, 0) << "'" << static_cast<char>(c) << "' is wider than 5 columns";
    if (c != ' ') {
      EXPECT_GT(pixels(g), 0) << "'" << static_cast<char>(c) << "' draws nothing";
    }
    EXPECT_TRUE(seen.insert(g).second) << "'" << static_cast<char>(c) << "' looks like another character";
  }
  // A byte the font has no glyph for (here the first of UTF-8's 'ä') is drawn, not dropped.
  EXPECT_GT(pixels(glyph(static_cast<char>(0xC3))), 0);
}

// Rendered at scale 1, cell i (6 pixels wide from x = 6 i) holds exactly the pixels of
// character i's glyph: nothing is dropped or smeared into a neighbour.
TEST(PlotFont, RenderedLabelCoversItsGlyphs) {
  const std::string label = "road_FL [x] Fz: kinetic/potential/total QWERTY 0123456789 {}|~";
  Canvas cv(6 * static_cast<int>(label.size()) + 4, 9);
  const Rgb ink{0, 0, 0};
  cv.text(0, 0, label, ink, 1);
  for (std::size_t i = 0; i < label.size(); ++i) {
    const Glyph& g = glyph(label[i]);
    int covered = 0;
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 6; ++x) {
        const Rgb p = cv.get(6 * static_cast<int>(i) + x, y);
        const bool on = p.r == 0 && p.g == 0 && p.b == 0;
        const bool want = y < 7 && x < 5 && (g[static_cast<std::size_t>(y)] & (0x10 >> x));
        EXPECT_EQ(on, want) << "'" << label[i] << "' at pixel (" << x << ", " << y << ")";
        covered += on;
      }
    if (label[i] != ' ') {
      EXPECT_GT(covered, 0) << "'" << label[i] << "' was not drawn";
    }
  }
}

TEST(PlotLegend, ComponentsAreNamedByTheOutputType) {
  EXPECT_EQ(component_name("energy", 0, 3), "kinetic");
  EXPECT_EQ(component_name("energy", 1, 3), "potential");
  EXPECT_EQ(component_name("energy", 2, 3), "total");
  EXPECT_EQ(component_name("node_position", 2, 3), "z");
  EXPECT_EQ(component_name("node_deformation", 0, 3), "x");
  EXPECT_EQ(component_name("joint_reaction", 4, 6), "My");
  EXPECT_EQ(component_name("modal_coordinates", 0, 4), "mode 1");
  EXPECT_EQ(component_name("joint_coordinate", 1, 2), "[1]");
  EXPECT_EQ(component_name("", 1, 3), "[1]");
}

// ffr-sim writes each output's type beside it, so ffr-info can name the legend; the plot is written.
TEST(PlotLegend, SimulatorRecordsTheOutputTypes) {
  const auto bin = std::filesystem::path(FFR_BINARY_DIR) / "bin";
  if (!std::filesystem::exists(bin / "ffr-sim") || !std::filesystem::exists(bin / "ffr-info")) GTEST_SKIP() << "tools missing";
  const auto dir = std::filesystem::temp_directory_path() / ("ffr_plot_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "model.json") << R"({"gravity": [0, 0, -9.81],
    "bodies": [{"name": "arm", "type": "rigid", "mass": 1, "com": [0.5, 0, 0],
                "inertia": [[0.001, 0, 0], [0, 0.02, 0], [0, 0, 0.02]], "position": [0, 0, 0]}],
    "joints": [{"name": "hub", "type": "revolute", "body1": "ground", "body2": "arm", "at": [0, 0, 0], "axis": [0, 1, 0]}],
    "solver": {"end": 0.1, "step": 0.01},
    "outputs": [{"name": "energy", "type": "energy"}, {"name": "tip_FL", "type": "node_position", "body": "arm", "at": [1, 0, 0]}]})";
  const std::string cd = "cd " + dir.string() + " && ";
  ASSERT_EQ(std::system((cd + (bin / "ffr-sim").string() + " model.json -o run.h5 --quiet").c_str()), 0);
  const auto r = ffr::formats::read_results(dir / "run.h5");
  EXPECT_EQ(r.find("energy")->type, "energy");
  EXPECT_EQ(r.find("tip_FL")->type, "node_position");
  ASSERT_EQ(std::system((cd + (bin / "ffr-info").string() + " run.h5 --plot energy,tip_FL --png run.png > /dev/null").c_str()), 0);
  EXPECT_GT(std::filesystem::file_size(dir / "run.png"), 1000u);
  std::filesystem::remove_all(dir);
}
