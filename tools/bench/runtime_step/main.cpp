// ffr-bench-runtime-step: the runtime's cost per time step.
//
//  1. Flexible slider-crank, rod with 10 modes (11-point free-free chain), h = 1 ms: per-step
//     wall time (best of several runs of the whole time loop, so shared-core noise is excluded),
//     Newton iterations and factorisations per step. Target: <= 25 us per step.
//  2. The same model with synthetic rods of growing point count (11 ... 2001 points: the
//     synthetic chain is dense, 20001 points took 20 GB) and the same 10 modes: the per-step
//     time must not depend on the mesh (largest / smallest <= 1.05). With SIDs that ffr-reduce
//     made from real meshes of 1k ... 1M DOF: mesh_independence.sh.
//
//  Options: --help. With --sids MODEL.json PLACEHOLDER DOF1=SID1 DOF2=SID2 ..., MODEL.json is run
//  with each SID (reduced by ffr-reduce from meshes of DOF1, DOF2, ... DOF) in place of the string
//  "PLACEHOLDER"; mesh_independence.sh makes the SIDs and calls it.
#include "sid_sizes.hpp"
#include "models.hpp"

#include "ffr/cli/cli.hpp"
#include "ffr/formats/sid_io.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <vector>

using namespace ffr::runtime;

namespace {

bool g_reuse = false;    // the tangent kept over steps (SolverSettings::reuse_jacobian)
bool g_keep_driven = false;  // the driven crank integrated like the other bodies (SolverSettings::eliminate_driven)
double g_omega = 150.0;  // crank speed [rad/s]

using Timing = bench::StepTiming;

// The best of `repeats` runs.
Timing time_model(const Model& model, int repeats) {
  Timing best;
  for (int r = 0; r < repeats; ++r) {
    Data data(model);
    initialize(model, data);
    const Timing t = bench::run_timed(model, data);
    if (r == 0 || t.us_per_step < best.us_per_step) best = t;
  }
  return best;
}

Model slider_crank(const std::filesystem::path& dir, int points, int modes, double h, double end) {
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(points, modes));
  bench::add_section_inertia(chain.sid, 0.008, 0.008);
  const std::string name = "rod_" + std::to_string(points) + ".sid.h5";
  ffr::formats::write_sid(chain.sid, dir / name);
  Model m = parse_model(bench::slider_crank_json(name, h, end, g_omega), dir, "slider_crank.json");
  if (g_reuse) m.settings.reuse_jacobian = true;
  if (g_keep_driven) {
    m.settings.eliminate_driven = false;
    finalize(m);
  }
  if (const char* pen = std::getenv("FFR_PENALTY")) m.settings.penalty = std::atof(pen);
  return m;
}

}  // namespace

const ffr::cli::Command kCommand{
    "ffr-bench-runtime-step",
    R"(
The runtime's cost per time step (see the top of tools/bench/runtime_step/main.cpp).

  --quick             shorter runs, fewer sizes
  --step-only         part 1 only (the flexible slider-crank)
  --reuse             keep the tangent over steps (SolverSettings::reuse_jacobian)
  --keep-driven       integrate the driven crank like the other bodies (no elimination)
  --omega RAD_PER_S   the crank's speed (default 150, the IVP Test Set's; the target's case)
  --sids MODEL.json PLACEHOLDER DOF1=SID1 ...
                      instead, MODEL.json run with each SID in place of PLACEHOLDER
)",
    "ffr-bench-runtime-step [--quick] [--step-only] [--reuse] [--keep-driven] [--omega RAD_PER_S]\n"
    "       ffr-bench-runtime-step --sids MODEL.json PLACEHOLDER DOF1=SID1 ..."};

int run(ffr::cli::Args& args) {
  if (args.flag("--sids")) {
    const auto pos = args.positionals();
    if (pos.size() < 3) throw ffr::cli::UsageError("--sids needs MODEL.json, PLACEHOLDER and at least one DOF=SID");
    std::vector<bench::SidCase> sids;
    for (std::size_t i = 2; i < pos.size(); ++i) {
      const auto eq = pos[i].find('=');
      if (eq == std::string::npos) throw ffr::cli::UsageError("expected DOF=SID, got " + pos[i]);
      sids.push_back({pos[i].substr(eq + 1), std::atol(pos[i].c_str())});
    }
    try {
      // A round is ~0.2 s: 15 of them give each SID a quiet moment on a shared machine.
      return bench::run_sid_sizes(pos[0], pos[1], sids, 15);
    } catch (const ModelError& e) {
      throw std::invalid_argument(e.what());  // bad input: exit 2
    }
  }
  const bool quick = args.flag("--quick"), step_only = args.flag("--step-only");
  g_reuse = args.flag("--reuse");
  g_keep_driven = args.flag("--keep-driven");
  if (const auto w = args.number("--omega")) {
    if (*w < 0) throw ffr::cli::UsageError("--omega: the crank speed must be >= 0 rad/s");
    g_omega = *w;
  }
  if (const auto pos = args.positionals(); !pos.empty()) throw ffr::cli::UsageError("unexpected argument " + pos[0]);
  const auto dir = bench::temp_dir("step");
  const int repeats = quick ? 2 : 7;
  const double end = quick ? 0.2 : 1.0;

  std::printf("# 1. flexible slider-crank, 10 modes, h = 1 ms, crank at %g rad/s (best of %d runs of %g s)\n", g_omega,
              repeats, end);
  const Model sc = slider_crank(dir, 11, 10, 1e-3, end);
  const Timing t = time_model(sc, repeats);
  std::printf("coordinates %d, constraint rows %d; unknowns of the step %d and %d (driven bodies eliminated, frames locked)\n",
              sc.ncoord, sc.nconstraints, sc.nunknown, sc.nactive);
  std::printf("per step %.2f us  (Newton iterations %.2f, factorisations %.2f, solves %.2f per step)  target <= 25 us: %s\n",
              t.us_per_step, t.iterations_per_step, t.factorizations_per_step, t.solves_per_step,
              t.us_per_step <= 25 ? "met" : "NOT met");
  if (step_only) {
    std::filesystem::remove_all(dir);
    return 0;
  }

  std::printf("\n# 2. per-step time vs mesh size (10 modes each; rounds interleaved, best of each)\n");
  // The synthetic chain's 10 modes change with its point count (a finer chain is a different
  // rod), and so may the work of a step: Newton iterations, tangents and solves (the
  // projections' passes depend on the rod's stiffness). Only chains that take the same work as
  // the smallest (each count within 2 %) are compared; a tangent costs several iterations, so a
  // time per iteration does not compare chains whose mix differs.
  // (tools/bench/runtime_step/mesh_independence.sh runs one model with SIDs of one part
  // reduced from four meshes: the real measure.)
  std::vector<int> sizes = quick ? std::vector<int>{11, 201, 2001} : std::vector<int>{11, 101, 1001, 2001};
  std::vector<Model> models;
  for (int points : sizes) models.push_back(slider_crank(dir, points, 10, 1e-3, end));
  std::vector<Timing> best(sizes.size(), Timing{1e300, 0, 0, 0});
  // The machine is shared: interleave the sizes over several rounds so that a busy moment hits
  // every size alike, and keep each size's best round.
  for (int round = 0; round < repeats; ++round)
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      const Timing t = time_model(models[i], 1);
      if (t.us_per_step < best[i].us_per_step) best[i] = t;
    }
  std::printf("%10s %10s %12s %14s %8s %8s\n", "points", "us/step", "iterations", "factorisations", "solves", "ratio");
  auto same_work = [&](const Timing& t) {
    auto close = [](double a, double b) { return std::abs(a - b) <= 0.02 * b; };
    return close(t.iterations_per_step, best[0].iterations_per_step) &&
           close(t.factorizations_per_step, best[0].factorizations_per_step) && close(t.solves_per_step, best[0].solves_per_step);
  };
  double slowest = 0, fastest = 1e300;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const bool compared = same_work(best[i]);
    if (compared) {
      slowest = std::max(slowest, best[i].us_per_step);
      fastest = std::min(fastest, best[i].us_per_step);
    }
    std::printf("%10d %10.2f %12.2f %14.2f %8.2f %8.3f%s\n", sizes[i], best[i].us_per_step, best[i].iterations_per_step,
                best[i].factorizations_per_step, best[i].solves_per_step, best[i].us_per_step / best[0].us_per_step,
                compared ? "" : "  (other work: not compared)");
  }
  // Slowest over fastest, whichever sizes they are: a ratio to the first size alone reads 1
  // when the smallest mesh happens to be the slowest.
  const double worst = slowest / fastest;
  std::printf("time per step at equal work, slowest / fastest %.3f (required <= 1.05): %s\n", worst,
              worst <= 1.05 ? "met" : "NOT met");
  std::filesystem::remove_all(dir);
  return 0;
}

int main(int argc, char** argv) { return ffr::cli::run_main(argc, argv, kCommand, run); }
