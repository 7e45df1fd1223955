// ffr-bench-formulations: the per-step wall time of the relative (joint-coordinate) formulation
// against the absolute (natural-coordinate) one, FORMULATION.md 18, on the same models in one run:
// planar pendulum chains of 5 ... 40 rigid links (no loop), the four-bar (one loop, closed by a
// cut joint) and the runtime benchmark's flexible slider-crank (rod with 10 modes, crank driven
// at 150 rad/s; tools/bench/runtime_step). Each figure is the best of several runs of the whole
// time loop (shared-core noise excluded), the two formulations alternating.
//
// Usage: ffr-bench-formulations [--quick]
#include "formulation_models.hpp"
#include "models.hpp"

#include "ffr/formats/sid_io.hpp"
#include "ffr/runtime/relative.hpp"

#include <cstdio>
#include <cstring>
#include <string>

using namespace ffr::runtime;

namespace {

struct Row {
  bench::StepTiming t;
  int coordinates = 0, rows = 0;
};

Row time_model(const Model& model, int repeats, Row best) {
  for (int r = 0; r < repeats; ++r) {
    Data data(model);
    initialize(model, data);
    const bench::StepTiming t = bench::run_timed(model, data);
    if (best.t.us_per_step == 0 || t.us_per_step < best.t.us_per_step) best.t = t;
  }
  best.coordinates = model.relative ? model.relative->ns : model.ncoord;
  best.rows = model.relative ? model.relative->kept_rows : model.nconstraints;
  return best;
}

void compare(const char* name, const std::string& absolute_json, const std::string& relative_json, const std::filesystem::path& dir,
             int repeats) {
  const Model a = parse_model(absolute_json, dir, std::string(name) + ".json");
  const Model r = parse_model(relative_json, dir, std::string(name) + ".json");
  Row ra, rr;
  // Alternating, so both see the same machine load.
  for (int k = 0; k < repeats; ++k) {
    ra = time_model(a, 1, ra);
    rr = time_model(r, 1, rr);
  }
  std::printf("| %-26s | %4d / %4d | %4d / %4d | %9.2f | %9.2f | %5.2f / %5.2f | %6.2fx |\n", name, ra.coordinates, rr.coordinates,
              ra.rows, rr.rows, ra.t.us_per_step, rr.t.us_per_step, ra.t.iterations_per_step, rr.t.iterations_per_step,
              ra.t.us_per_step / rr.t.us_per_step);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  if (argc > 1 && !quick) {
    std::fprintf(stderr, "usage: ffr-bench-formulations [--quick]\n");
    return 2;
  }
  const int repeats = quick ? 2 : 5;
  const double end = quick ? 0.2 : 1.0, h = 1e-3;
  const auto dir = bench::temp_dir("formulations");
  std::printf("| model                      | coordinates (abs / rel) | constraint rows (abs / rel) | abs us/step | rel us/step | Newton it./step (abs / rel) | speed-up |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const int n : {5, 10, 20, 40}) {
    const std::string name = "chain of " + std::to_string(n) + " links";
    compare(name.c_str(), formulations::pendulum_chain_json(n, h, end, "absolute"),
            formulations::pendulum_chain_json(n, h, end, "relative"), dir, repeats);
  }
  compare("four-bar", formulations::four_bar::json(h, end, "absolute"), formulations::four_bar::json(h, end, "relative"), dir, repeats);
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 10));
  bench::add_section_inertia(chain.sid, 0.008, 0.008);
  ffr::formats::write_sid(chain.sid, dir / "rod.sid.h5");
  const std::string crank = bench::slider_crank_json("rod.sid.h5", h, end, 150.0);
  compare("slider-crank (10 modes)", formulations::with_formulation(crank, "absolute"), formulations::with_formulation(crank, "relative"),
          dir, repeats);
  std::filesystem::remove_all(dir);
  return 0;
}
