// ffr-bench-formulations: the study of 'Improved efficiency in FFR methods for flexible multibody
// dynamics by means of shape integrals preprocessing' (docs/references.md), measured: each model
// in the absolute (natural-coordinate) and the relative (joint-coordinate) formulation
// (FORMULATION.md 18), each with the flexible bodies' inertia from the shape integrals (the
// invariants, "inv") and from the FE mass matrix every evaluation (the co-rotational products,
// "fe": runtime/src/bodies/body_fe_inertia.cpp), the four runs alternating in one process, best of
// several runs of the whole time loop each, in the thread's CPU time per step. Models:
//  - chains: planar pendulum chains of 1 ... 50 rigid links, and of flexible links (the
//    consistent-mass rod below, hinged end to end at its nodes);
//  - mesh: the runtime benchmark's slider-crank (crank driven at 150 rad/s) whose rod is a
//    consistent-mass chain rod (33 ... ~1000 DOF) or a TET10 steel bar meshed and reduced by the
//    preprocessor's library (thousands ... ~1M DOF), with 6 and 30 modes
//    (tools/models/fe_bodies.hpp);
//  - loops: the slider-crank (one cut joint) carrying a chain of 1 ... 20 rigid links;
//  - vehicle: meshes/vehicle's model (prepared by its run.sh) in both formulations, invariants
//    only (its frame is a beam model: FullMass carries translational mass only).
// Output: one markdown row per model (stdout) and, with --csv, the same figures for plot.py.
//
// Usage: ffr-bench-formulations [--quick] [--part chains|mesh|loops|vehicle|all] [--max-dof N]
//                               [--work DIR] [--vehicle DIR] [--csv FILE] [--only TEXT]
//                               [--states FILE]
// (--only: the models whose name contains TEXT, e.g. "flexible chain of 2"; --states: the final
// absolute coordinates of every run, one line each, to compare two builds' motions.)
#include "fe_bodies.hpp"
#include "formulation_models.hpp"
#include "models.hpp"

#include "ffr/formats/sid_io.hpp"
#include "ffr/runtime/relative.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <time.h>

using namespace ffr::runtime;
namespace fs = std::filesystem;

namespace {

struct Args {
  bool quick = false;
  std::string part = "all";
  long max_dof = 1100000;
  fs::path work = fs::temp_directory_path() / "ffr_bench_formulations_work";
  fs::path vehicle;
  fs::path csv;
  std::string only;
  fs::path states;
};

std::string only_models;          ///< --only
std::FILE* states_file = nullptr;  ///< --states

struct Run {
  double us = 0, iterations = 0;
  bool ok = false;
  std::string error;
};

Run time_model(const Model& model, Run best, const std::string& label) {
  try {
    Data data(model);
    initialize(model, data);
    // The thread's CPU time, not the wall time: on the shared cores the wall time of a run moved
    // by a factor of two to three with the other jobs' load, the CPU time by far less.
    timespec c0{}, c1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
    const bench::StepTiming t = bench::run_timed(model, data);
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
    const double cpu_us = 1e6 * static_cast<double>(c1.tv_sec - c0.tv_sec) + 1e-3 * static_cast<double>(c1.tv_nsec - c0.tv_nsec);
    const double us = cpu_us / static_cast<double>(step_count(model));
    if (states_file && !best.ok) {  // (the first run's: every run of a model ends alike)
      std::fprintf(states_file, "%s:", label.c_str());
      for (Eigen::Index i = 0; i < data.state.q.size(); ++i) std::fprintf(states_file, " %.17g", data.state.q(i));
      std::fprintf(states_file, "\n");
    }
    if (!best.ok || us < best.us) {
      best.us = us;
      best.iterations = t.iterations_per_step;
    }
    best.ok = true;
  } catch (const std::exception& e) {
    best.error = e.what();
  }
  return best;
}

std::FILE* csv_file = nullptr;

/// The four runs of one model. `full_mass`: body name -> its FE mass data (the "fe" runs);
/// none: only the two "inv" runs (rigid models, or bodies without FE mass data).
struct Case {
  std::string group, name;
  std::string json;  ///< the model, formulation left to set
  std::map<std::string, std::shared_ptr<const FullMass>> full_mass;
  long dof = 0;      ///< FE DOF of the flexible bodies (0: none)
  int modes = 0, loops = 0;
};

void measure(const Case& c, const fs::path& dir, int repeats) {
  if (!only_models.empty() && c.name.find(only_models) == std::string::npos) return;
  const Model abs_inv = parse_model(formulations::with_formulation(c.json, "absolute"), dir, c.name + ".json");
  const Model rel_inv = parse_model(formulations::with_formulation(c.json, "relative"), dir, c.name + ".json");
  Model abs_fe = abs_inv, rel_fe = rel_inv;
  for (Model* m : {&abs_fe, &rel_fe})
    for (Body& b : m->bodies)
      if (const auto it = c.full_mass.find(b.name); it != c.full_mass.end()) b.full_mass = it->second;
  const bool fe = !c.full_mass.empty();
  Run ai, af, ri, rf;
  for (int k = 0; k < repeats; ++k) {  // alternating, so that a change of load from other processes falls on all four alike
    ai = time_model(abs_inv, ai, c.name + " abs inv");
    ri = time_model(rel_inv, ri, c.name + " rel inv");
    if (fe) {
      af = time_model(abs_fe, af, c.name + " abs fe");
      rf = time_model(rel_fe, rf, c.name + " rel fe");
    }
  }
  const int nabs = abs_inv.ncoord, nrel = rel_inv.relative ? rel_inv.relative->ns : -1;
  auto us = [](const Run& r) { return r.ok ? r.us : -1.0; };
  auto cell = [&](const Run& r) {
    char b[32];
    if (!r.ok) return std::string("fails");
    std::snprintf(b, sizeof b, "%.1f", r.us);
    return std::string(b);
  };
  auto ratio = [](const Run& a, const Run& b) {
    char s[32] = "-";
    if (a.ok && b.ok) std::snprintf(s, sizeof s, "%.2fx", a.us / b.us);
    return std::string(s);
  };
  std::printf("| %-28s | %5d / %4d | %7ld | %2d | %9s | %9s | %9s | %9s | %7s | %7s | %7s |\n", c.name.c_str(), nabs, nrel, c.dof, c.modes,
              cell(ai).c_str(), fe ? cell(af).c_str() : "-", cell(ri).c_str(), fe ? cell(rf).c_str() : "-", ratio(af, ai).c_str(),
              ratio(rf, ri).c_str(), ratio(ai, ri).c_str());
  for (const Run* r : {&ai, &af, &ri, &rf})
    if (!r->ok && !r->error.empty()) std::printf("    (%s: %s)\n", c.name.c_str(), r->error.substr(0, 200).c_str());
  std::fflush(stdout);
  if (csv_file) {
    int flexible = 0, modes = 0;  // from the model (the vehicle's Case does not know them)
    for (const Body& b : abs_inv.bodies)
      if (b.nq > 0) ++flexible, modes = std::max(modes, b.nq);
    std::fprintf(csv_file, "%s,\"%s\",%zu,%d,%d,%d,%ld,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.2f,%.2f,%.2f,%.2f\n", c.group.c_str(), c.name.c_str(),
                 abs_inv.bodies.size(), flexible, modes, c.loops, c.dof, nabs, nrel, rel_inv.relative ? rel_inv.relative->kept_rows : -1,
                 us(ai), fe ? us(af) : -1, us(ri), fe ? us(rf) : -1, ai.iterations, af.iterations, ri.iterations, rf.iterations);
    std::fflush(csv_file);
  }
}

void header(const char* title) {
  std::printf("\n%s\n\n", title);
  std::printf("| model                        | coords abs / rel | FE DOF | modes | abs inv us | abs fe us | rel inv us | rel fe us | abs fe/inv | rel fe/inv | abs/rel (inv) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
}

std::string solver(double h, double end) {
  return R"("solver": {"end": )" + formulations::num(end) + R"(, "step": )" + formulations::num(h) + "}";
}

/// n flexible links (`sid`, 0.3 m along x, nodes A and B at its ends), hinged end to end about z
/// at their nodes (the first at A to the ground), horizontal at rest, gravity along -y.
std::string flexible_chain_json(int n, const std::string& sid, double h, double end) {
  std::string bodies, joints;
  for (int i = 0; i < n; ++i) {
    bodies += (i ? ",\n" : "") + std::string(R"({"name": "link)") + std::to_string(i) + R"(", "type": "flexible", "sid": ")" + sid +
              R"(", "position": [)" + formulations::num(0.3 * i) + ", 0, 0]}";
    joints += (i ? ",\n" : "") + std::string(R"({"name": "j)") + std::to_string(i) + R"(", "type": "revolute", "body1": ")" +
              (i ? "link" + std::to_string(i - 1) : std::string("ground")) + "\", " + (i ? R"("node1": "B", )" : "") +
              R"("body2": "link)" + std::to_string(i) + R"(", "node2": "A", "axis": [0, 0, 1]})";
  }
  return R"({"gravity": [0, -9.81, 0], "bodies": [)" + bodies + R"(], "joints": [)" + joints + "], " + solver(h, end) + "}";
}

void chains(const Args& a, const fs::path& dir) {
  header("### Chains (planar pendulums released horizontal; h = 1 ms)");
  const double h = 1e-3;
  for (int n : a.quick ? std::vector<int>{1, 5, 20} : std::vector<int>{1, 2, 5, 10, 20, 50}) {
    Case c;
    c.group = "chain_rigid";
    c.name = "rigid chain of " + std::to_string(n);
    c.json = formulations::pendulum_chain_json(n, h, n >= 20 ? 0.1 : 0.3, "absolute");
    const std::string key = "\"formulation\": \"absolute\", ";
    c.json.erase(c.json.find(key), key.size());
    measure(c, dir, a.quick ? 2 : 7);
  }
  const bench::FeBody rod = bench::consistent_rod(bench::rod_params(11, 6));
  ffr::formats::write_sid(rod.sid, dir / "link.sid.h5");
  // Rigid chains ending in one flexible link (0.3 m, at the last rigid link's end).
  for (int n : a.quick ? std::vector<int>{5} : std::vector<int>{2, 5, 10, 20, 50}) {
    Case c;
    c.group = "chain_mixed";
    c.name = std::to_string(n) + " rigid + 1 flexible link";
    std::string json = formulations::pendulum_chain_json(n, h, n >= 20 ? 0.1 : 0.3, "absolute");
    const std::string key = "\"formulation\": \"absolute\", ";
    json.erase(json.find(key), key.size());
    const std::string x = formulations::num(0.1 * n);
    json.insert(json.find("], \"joints\": ["), R"(, {"name": "flex", "type": "flexible", "sid": "link.sid.h5", "position": [)" + x + ", 0, 0]}");
    json.insert(json.find("], \"solver\""), R"(, {"name": "jf", "type": "revolute", "body1": "link)" + std::to_string(n - 1) +
                                                R"(", "body2": "flex", "node2": "A", "axis": [0, 0, 1]})");
    c.json = json;
    c.full_mass["flex"] = rod.full_mass;
    c.dof = rod.dof;
    c.modes = 6;
    measure(c, dir, a.quick ? 2 : 3);
  }
  for (int n : a.quick ? std::vector<int>{1, 5} : std::vector<int>{1, 2, 5, 10, 20, 50}) {
    Case c;
    c.group = "chain_flexible";
    c.name = "flexible chain of " + std::to_string(n);
    c.json = flexible_chain_json(n, "link.sid.h5", h, n >= 20 ? 0.02 : n >= 5 ? 0.05 : 0.2);
    for (int i = 0; i < n; ++i) c.full_mass["link" + std::to_string(i)] = rod.full_mass;
    c.dof = rod.dof;
    c.modes = 6;
    measure(c, dir, a.quick ? 2 : 3);
  }
}

void mesh(const Args& a, const fs::path& dir) {
  header("### One flexible body: the slider-crank's rod meshed ever finer (crank at 150 rad/s, h = 1 ms)");
  const double h = 1e-3;
  auto run = [&](const bench::FeBody& rod, const std::string& kind, int modes) {
    Case c;
    c.group = kind;
    c.name = kind + " " + std::to_string(rod.dof) + " DOF, " + std::to_string(modes) + " modes";
    const std::string sid = "rod_" + std::to_string(rod.dof) + "_" + std::to_string(modes) + ".sid.h5";
    ffr::formats::write_sid(rod.sid, dir / sid);
    // Long enough for a steady figure; the largest bodies' co-rotational steps take seconds.
    const double end = rod.dof > 300000 ? 0.003 : rod.dof > 30000 ? 0.01 : rod.dof > 3000 ? 0.03 : 0.2;
    c.json = bench::slider_crank_json(sid, h, end, 150.0);
    c.full_mass["rod"] = rod.full_mass;
    c.dof = rod.dof;
    c.modes = modes;
    c.loops = 1;
    measure(c, dir, a.quick || rod.dof > 30000 ? 2 : rod.dof > 1000 ? 5 : 9);
  };
  for (int points : a.quick ? std::vector<int>{11, 34} : std::vector<int>{11, 34, 101, 334}) {
    if (3L * points > a.max_dof) break;
    for (int modes : {6, 30}) {
      if (modes > 3 * points - 5) continue;
      run(bench::consistent_rod(bench::rod_params(points, modes)), "consistent rod", modes);
    }
  }
  // TET10 bars of 0.3 m x 8 mm x 8 mm; mesh sizes for 4.8k, 10k, 73k, 124k, 340k and 977k DOF.
  for (double size : a.quick ? std::vector<double>{0.008} : std::vector<double>{0.008, 0.004, 0.002, 0.0016, 0.0011, 0.00075}) {
    const double est = 3.0 * (2 * std::ceil(0.008 / size) + 1) * (2 * std::ceil(0.008 / size) + 1) * (2 * std::ceil(0.3 / size) + 1);
    if (est > 1.3 * static_cast<double>(a.max_dof)) break;
    const bench::FeBody bar = bench::solid_bar(a.work, 0.3, 0.008, size, 30);
    std::fprintf(stderr, "TET10 bar, size %g: %ld DOF\n", size, bar.dof);
    run(bench::first_modes(bar, 6), "TET10 bar", 6);
    run(bar, "TET10 bar", 30);
  }
}

/// Loops at lower coordinate ratios: the slider-crank (6-mode consistent rod, one cut joint) with
/// a planar chain of n rigid links hinged to the slider (no gravity: the slider swings it), the
/// crank at 15 rad/s.
void loops(const Args& a, const fs::path& dir) {
  header("### Loops: the slider-crank (one cut joint) carrying a chain of n rigid links on its slider");
  const bench::FeBody rod = bench::consistent_rod(bench::rod_params(11, 6));
  ffr::formats::write_sid(rod.sid, dir / "loop_rod.sid.h5");
  for (int n : a.quick ? std::vector<int>{2} : std::vector<int>{1, 2, 5, 10, 20}) {
    // The crank at 15 rad/s: at 150 the slider whips the links beyond what Newton follows at 1 ms.
    std::string json = bench::slider_crank_json("loop_rod.sid.h5", 1e-3, 0.2, 15.0);
    const double l = 0.1, m = 0.1, I = m * l * l / 12;
    std::string bodies, joints;
    for (int i = 0; i < n; ++i) {
      const double x0 = 0.45 + l * i;
      bodies += ",\n    {\"name\": \"link" + std::to_string(i) + "\", \"type\": \"rigid\", \"mass\": " + formulations::num(m) +
                ", \"com\": [" + formulations::num(x0 + 0.5 * l) + ", 0, 0], \"inertia\": [[1e-7, 0, 0], [0, " + formulations::num(I) +
                ", 0], [0, 0, " + formulations::num(I) + "]]}";
      joints += ",\n    {\"name\": \"h" + std::to_string(i) + "\", \"type\": \"revolute\", \"body1\": \"" +
                (i ? "link" + std::to_string(i - 1) : std::string("slider")) + "\", \"body2\": \"link" + std::to_string(i) +
                "\", \"at\": [" + formulations::num(x0) + ", 0, 0], \"axis\": [0, 0, 1]}";
    }
    const std::string bodies_end = "\n  ],\n  \"joints\"", joints_end = "\n  ],\n  \"motions\"";
    json.insert(json.find(bodies_end), bodies);
    json.insert(json.find(joints_end), joints);
    Case c;
    c.group = "loop";
    c.name = "slider-crank + " + std::to_string(n) + " links";
    c.json = json;
    c.full_mass["rod"] = rod.full_mass;
    c.dof = rod.dof;
    c.modes = 6;
    c.loops = 1;
    measure(c, dir, a.quick ? 2 : 5);
  }
}

void vehicle(const Args& a, const fs::path&) {
  if (a.vehicle.empty()) return;
  header("### The vehicle (meshes/vehicle, prepared by its run.sh; h as in its model)");
  std::ifstream f(a.vehicle / "model.json");
  if (!f) {
    std::printf("(no %s)\n", (a.vehicle / "model.json").string().c_str());
    return;
  }
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  // The first seconds only (settling at rest and speeding up): the end time is set here.
  const std::string key = "\"end\":";
  if (const auto at = text.find(key); at != std::string::npos) {
    const auto stop = text.find_first_of(",}", at);
    text.replace(at, stop - at, "\"end\": " + std::string(a.quick ? "0.5" : "2.0"));
  }
  Case c;
  c.group = "vehicle";
  c.name = "vehicle";
  c.json = text;
  c.loops = 0;
  measure(c, a.vehicle, a.quick ? 1 : 3);
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("missing value after " + s);
      return argv[++i];
    };
    if (s == "--quick") a.quick = true;
    else if (s == "--part") a.part = value();
    else if (s == "--max-dof") a.max_dof = std::stol(value());
    else if (s == "--work") a.work = value();
    else if (s == "--vehicle") a.vehicle = value();
    else if (s == "--csv") a.csv = value();
    else if (s == "--only") a.only = value();
    else if (s == "--states") a.states = value();
    else {
      std::fprintf(stderr, "usage: ffr-bench-formulations [--quick] [--part chains|mesh|loops|vehicle|all] [--max-dof N] [--work DIR] [--vehicle DIR] [--csv FILE] [--only TEXT] [--states FILE]\n");
      return 2;
    }
  }
  if (!a.csv.empty()) {
    csv_file = std::fopen(a.csv.c_str(), "w");
    if (!csv_file) {
      std::fprintf(stderr, "cannot write %s\n", a.csv.c_str());
      return 2;
    }
    std::fprintf(csv_file, "group,model,bodies,flexible,modes,loops,fe_dof,coords_abs,coords_rel,rows_rel,abs_inv_us,abs_fe_us,rel_inv_us,rel_fe_us,abs_inv_it,abs_fe_it,rel_inv_it,rel_fe_it\n");
  }
  only_models = a.only;
  if (!a.states.empty() && !(states_file = std::fopen(a.states.c_str(), "w"))) {
    std::fprintf(stderr, "cannot write %s\n", a.states.c_str());
    return 2;
  }
  const auto dir = bench::temp_dir("formulations");
  if (a.part == "all" || a.part == "chains") chains(a, dir);
  if (a.part == "all" || a.part == "mesh") mesh(a, dir);
  if (a.part == "all" || a.part == "loops") loops(a, dir);
  if (a.part == "all" || a.part == "vehicle") vehicle(a, dir);
  fs::remove_all(dir);
  if (csv_file) std::fclose(csv_file);
  if (states_file) std::fclose(states_file);
  return 0;
}
