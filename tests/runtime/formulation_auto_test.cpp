// "formulation": "auto" (choose_formulation, FORMULATION.md 18): the rule taken from the
// formulation study (tools/bench/formulations/RESULTS.md) — relative when the relative
// coordinates are at most a third of the absolute ones in a tree, a fifth with loops (cut joints) —
// applied to the study's own kinds of model on both sides of each threshold, and the note that
// says what was chosen and why. The counts in the notes are checked against counts made here
// from the models' definitions (12 natural coordinates per body plus its modes; one angle per
// revolute joint the tree places; 9 + modes for a flexible body hinged at its node).
#include "formulation_models.hpp"  // tools/bench/formulations
#include "models.hpp"              // tools/models: the slider-crank and its rod
#include "support.hpp"

#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>

using namespace ffr::runtime;

namespace {

std::string note_of(const Model& m) {
  for (const std::string& n : m.notes)
    if (n.rfind("formulation: ", 0) == 0) return n;
  return {};
}

void expect_choice(const Model& m, bool relative, const std::string& text) {
  const std::string note = note_of(m);
  std::printf("%s\n", note.c_str());
  EXPECT_EQ(static_cast<bool>(m.relative), relative) << note;
  EXPECT_NE(note.find(text), std::string::npos) << note;
}

/// n rigid links of pendulum_chain_json, then `flexible` rods (6 modes, 0.3 m) hinged end to end
/// at their nodes; "auto".
std::string chain(int n, int flexible, const std::string& sid) {
  std::string json = formulations::pendulum_chain_json(std::max(n, 1), 1e-3, 0.01, "auto");
  if (n == 0) {  // no rigid link: the rods start at the ground
    json = R"({"gravity": [0, -9.81, 0], "bodies": [], "joints": [], "solver": {"formulation": "auto", "end": 0.01, "step": 0.001}})";
  }
  std::string bodies, joints;
  for (int i = 0; i < flexible; ++i) {
    const std::string name = "rod" + std::to_string(i);
    const std::string parent = i ? "rod" + std::to_string(i - 1) : n ? "link" + std::to_string(n - 1) : "ground";
    bodies += std::string(n || i ? ", " : "") + R"({"name": ")" + name + R"(", "type": "flexible", "sid": ")" + sid +
              R"(", "position": [)" + formulations::num(0.1 * n + 0.3 * i) + ", 0, 0]}";
    joints += std::string(n || i ? ", " : "") + R"({"name": "f)" + std::to_string(i) + R"(", "type": "revolute", "body1": ")" + parent +
              "\", " + (i ? R"("node1": "B", )" : "") + R"("body2": ")" + name + R"(", "node2": "A", "axis": [0, 0, 1]})";
  }
  json.insert(json.find("], \"joints\": ["), bodies);
  json.insert(json.find("], \"solver\""), joints);
  return json;
}

}  // namespace

TEST(FormulationAuto, TreesUpToAThirdOfTheCoordinatesGoRelative) {
  test::TempDir dir("auto_trees");
  const auto rod = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 6));
  ffr::formats::write_sid(rod.sid, dir / "rod.sid.h5");
  // 20 rigid links: 20 angles against 240 (1/12).
  expect_choice(test::model_from(chain(20, 0, "rod.sid.h5"), dir.path), true,
                "relative (solver.formulation \"auto\": 20 relative coordinates against 240 absolute ones; 20 bodies (0 flexible, 0 modes), "
                "20 placed by joints, 0 free, 0 cut joint(s); relative when it has at most a third");
  // Five rigid links and a rod hinged at its node: 5 + (9 + 6) = 20 against 60 + 18 = 78 (0.26).
  expect_choice(test::model_from(chain(5, 1, "rod.sid.h5"), dir.path), true,
                "relative (solver.formulation \"auto\": 20 relative coordinates against 78 absolute ones; 6 bodies (1 flexible, 6 modes), "
                "6 placed by joints, 0 free, 0 cut joint(s)");
  // Two rigid links and the rod: 2 + 15 = 17 against 24 + 18 = 42 (0.40).
  expect_choice(test::model_from(chain(2, 1, "rod.sid.h5"), dir.path), false,
                "absolute (solver.formulation \"auto\": 17 relative coordinates against 42 absolute ones; 3 bodies (1 flexible, 6 modes), "
                "3 placed by joints, 0 free, 0 cut joint(s)");
  // Two rods hinged at their nodes: 2 (9 + 6) = 30 against 2 (12 + 6) = 36 (0.83).
  expect_choice(test::model_from(chain(0, 2, "rod.sid.h5"), dir.path), false,
                "absolute (solver.formulation \"auto\": 30 relative coordinates against 36 absolute ones; 2 bodies (2 flexible, 12 modes), "
                "2 placed by joints, 0 free, 0 cut joint(s); relative when it has at most a third");
}

TEST(FormulationAuto, LoopsUpToAFifthGoRelative) {
  test::TempDir dir("auto_loops");
  // The four-bar: its fourth joint cut, 3 angles against 36 (1/12).
  expect_choice(test::model_from(formulations::four_bar::json(1e-3, 0.01, "auto")), true,
                "relative (solver.formulation \"auto\": 3 relative coordinates against 36 absolute ones; 3 bodies (0 flexible, 0 modes), "
                "3 placed by joints, 0 free, 1 cut joint(s); relative when it has at most a fifth");
  // The flexible slider-crank: crank angle, rod at its node (9 + 6), slider slide, the wrist cut:
  // 17 against 42 (0.40 > 1/5).
  const auto rod = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 6));
  ffr::formats::write_sid(rod.sid, dir / "rod.sid.h5");
  const std::string crank = formulations::with_formulation(bench::slider_crank_json("rod.sid.h5", 1e-3, 0.01, 150.0), "auto");
  expect_choice(test::model_from(crank, dir.path), false,
                "absolute (solver.formulation \"auto\": 17 relative coordinates against 42 absolute ones; 3 bodies (1 flexible, 6 modes), "
                "3 placed by joints, 0 free, 1 cut joint(s); relative when it has at most a fifth");
}

TEST(FormulationAuto, AdaptiveStepsStayAbsolute) {
  std::string json = formulations::pendulum_chain_json(5, 1e-3, 0.01, "auto");
  const std::string step = "\"step\": 0.001";
  json.replace(json.find(step), step.size(), R"("step": "auto", "rtol": 1e-6)");
  expect_choice(test::model_from(json), false, "the relative formulation takes fixed steps only");
}
