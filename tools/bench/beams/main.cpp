// ffr-bench-beams: the runtime's cost per time step of a beam pendulum against its element count,
// for the ancf and the geometrically exact beam (runtime/FORMULATION.md 15, 16).
//
// The pendulum: a 1 m steel-like beam of 10 x 10 mm (E = 2.1e9 Pa: it bends visibly), hung at its
// start by a spherical joint, released horizontal under gravity, 1 ms steps over 0.5 s (the swing
// through the bottom). Printed per formulation and element count: microseconds per step (best of
// three runs of the whole time loop, so shared-core noise is excluded), Newton iterations and
// factorisations per step, and the speed against real time (1 ms / step time). The issue's goal:
// 16 elements at least 100 times faster than real time (<= 10 us per step).
//
// Usage: ffr-bench-beams [--elements 2,4,8,16,32] [--end 0.5] [--formulation ancf|geometrically_exact]
#include "models.hpp"

#include "ffr/runtime/load.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

std::string pendulum_json(const std::string& form, int elements, double end) {
  const bool ge = form == "geometrically_exact";
  return std::string(R"({"gravity": [0, 0, -9.81],
    "bodies": [{"name": "beam", "type": "beam", "formulation": ")") + form + R"(", "start": [0, 0, 0], "end": [1, 0, 0],
      "elements": )" + std::to_string(elements) + R"(, "E": 2.1e9, "rho": 7850)" + (ge ? R"(, "nu": 0.3)" : "") + R"(,
      "section": {"A": 1e-4, "Iy": 8.333333333333334e-10, "Iz": 8.333333333333334e-10)" + (ge ? R"(, "J": 1.406e-9)" : "") +
         R"(}}],
    "joints": [{"name": "pin", "type": "spherical", "body1": "ground", "body2": "beam", "node2": "start"}],
    "solver": {"end": )" + std::to_string(end) + R"(, "step": 1e-3},
    "outputs": [{"name": "tip", "type": "node_position", "body": "beam", "node": "end"}]})";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> counts{2, 4, 8, 16, 32};
  double end = 0.5;
  std::vector<std::string> forms{"ancf", "geometrically_exact"};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--help")) {
      std::printf("usage: ffr-bench-beams [--elements 2,4,8,16,32] [--end 0.5] [--formulation ancf|geometrically_exact]\n");
      return 0;
    }
    if (!std::strcmp(argv[i], "--elements") && i + 1 < argc) {
      counts.clear();
      std::stringstream ss(argv[++i]);
      for (std::string t; std::getline(ss, t, ',');) counts.push_back(std::atoi(t.c_str()));
    } else if (!std::strcmp(argv[i], "--formulation") && i + 1 < argc) {
      forms = {argv[++i]};
    } else if (!std::strcmp(argv[i], "--end") && i + 1 < argc) {
      end = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "ffr-bench-beams: unknown argument '%s' (see --help)\n", argv[i]);
      return 2;
    }
  }
  std::printf("%-20s %8s %12s %10s %10s %14s\n", "formulation", "elements", "us/step", "iter/step", "fact/step",
              "x real time");
  for (const std::string& form : forms)
    for (const int n : counts) {
      const Model model = parse_model(pendulum_json(form, n, end), ".", "beam_pendulum.json");
      bench::StepTiming best;
      for (int r = 0; r < 3; ++r) {
        Data data(model);
        initialize(model, data);
        const bench::StepTiming t = bench::run_timed(model, data);
        if (r == 0 || t.us_per_step < best.us_per_step) best = t;
      }
      std::printf("%-20s %8d %12.1f %10.2f %10.2f %14.1f\n", form.c_str(), n, best.us_per_step, best.iterations_per_step,
                  best.factorizations_per_step, 1e3 / best.us_per_step);
      std::fflush(stdout);
    }
  return 0;
}
