// ffr-bench-runtime-corotational: the paper "Improved efficiency in FFR methods for flexible
// multibody dynamics by means of shape integrals preprocessing" (docs/references.md) compares, in the absolute natural-coordinate formulation, the
// same simulation with the flexible bodies' mass matrix and velocity-dependent inertia forces
// obtained every step from the FE mass matrix (the co-rotational way) or from shape integrals
// computed once. It reports ~2.75x ("about 175%") for bodies of 10 elements (33 DOF) with 6 modes.
//
// Here: the flexible slider-crank (IVP Test Set geometry, crank at 150 rad/s, h = 1 ms), rod = a
// chain of N points (3N DOF) with the consistent mass of its bar elements and 6 modes
// (tools/models/fe_bodies.hpp), both ways, same integrator and settings. Reported: per-step time
// of the whole step and of the inertia evaluation alone (what every Newton evaluation and tangent
// refresh computes of it: mass matrix, inertia forces, their tangents, the modal-acceleration
// tangent), and the speed-up; the two runs' final states agree (same FE model).
#include "fe_bodies.hpp"
#include "models.hpp"

#include "ffr/cli/cli.hpp"
#include "ffr/formats/sid_io.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>

using namespace ffr::runtime;

namespace {

struct Timing {
  double step_us, inertia_us, iterations;
  VectorXd q;
};

Timing time_runs(const Model& model, int repeats) {
  Timing t{1e300, 1e300, 0, {}};
  for (int r = 0; r < repeats; ++r) {
    Data data(model);
    initialize(model, data);
    const bench::StepTiming st = bench::run_timed(model, data);
    t.step_us = std::min(t.step_us, st.us_per_step);
    t.iterations = st.iterations_per_step;
    t.q = data.state.q;
    // The inertia evaluation alone: what the two ways differ in, per Newton iteration with a
    // tangent refresh.
    const int reps = 2000;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < reps; ++k) {
      update_bodies(model, data);
      mass_matrices(model, data);
      for (std::size_t b = 0; b < model.bodies.size(); ++b) {
        const Body& body = model.bodies[b];
        const int o = body.offset, nb = body.ncoord();
        data.tmp.setZero();
        auto Qb = data.tmp.segment(o, nb);
        auto Kb = data.K.block(o, o, nb, nb);
        auto Cb = data.C.block(o, o, nb, nb);
        if (body.full_mass) {
          fe_inertia_forces(body, data.bodies[b], data.state.qd.segment(o, nb), Qb);
          fe_inertia_tangents(body, data.bodies[b], data.state.qd.segment(o, nb), Kb, Cb);
        } else {
          body_inertia_forces(body, data.bodies[b], data.state.qd.segment(o, nb), Qb);
          body_inertia_tangents(body, data.bodies[b], data.state.qd.segment(o, nb), Kb, Cb);
        }
      }
      add_modal_acceleration_tangent(model, data, 1.0, data.T);
    }
    t.inertia_us = std::min(t.inertia_us, 1e6 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / reps);
  }
  return t;
}

}  // namespace

const ffr::cli::Command kCommand{"ffr-bench-runtime-corotational",
                                  "\nSeed 000's comparison (see the top of its main.cpp).\n\n  --quick   two sizes, short runs\n",
                                  "ffr-bench-runtime-corotational [--quick]"};

int run(ffr::cli::Args& args) {
  const bool quick = args.flag("--quick");
  if (const auto pos = args.positionals(); !pos.empty()) throw ffr::cli::UsageError("unexpected argument " + pos[0]);
  const auto dir = bench::temp_dir("corot");
  const int repeats = quick ? 2 : 5;
  const double end = quick ? 0.05 : 0.2;
  std::printf("# co-rotational vs shape integrals: flexible slider-crank, rod with 6 modes, h = 1 ms, %g s, best of %d\n", end, repeats);
  std::printf("%8s %6s | %12s %12s %8s | %12s %12s %8s | %10s\n", "points", "DOF", "step corot", "step invar", "speedup",
              "inertia corot", "inertia inv", "speedup", "|dq| end");
  const std::vector<int> sizes = quick ? std::vector<int>{11, 101} : std::vector<int>{11, 21, 51, 101, 201};
  for (int points : sizes) {
    const bench::FeBody rod = bench::consistent_rod(bench::rod_params(points, 6));
    const std::string name = "rod_" + std::to_string(points) + ".sid.h5";
    ffr::formats::write_sid(rod.sid, dir / name);
    const Model inv = parse_model(bench::slider_crank_json(name, 1e-3, end, 150.0), dir, "slider_crank.json");
    Model cor = inv;
    cor.bodies[1].full_mass = rod.full_mass;
    const Timing a = time_runs(cor, repeats), b = time_runs(inv, repeats);
    std::printf("%8d %6d | %10.2fus %10.2fus %7.2fx | %10.2fus %10.2fus %7.2fx | %10.2e\n", points, 3 * points, a.step_us,
                b.step_us, a.step_us / b.step_us, a.inertia_us, b.inertia_us, a.inertia_us / b.inertia_us,
                (a.q - b.q).cwiseAbs().maxCoeff());
  }
  std::filesystem::remove_all(dir);
  return 0;
}

int main(int argc, char** argv) { return ffr::cli::run_main(argc, argv, kCommand, run); }
