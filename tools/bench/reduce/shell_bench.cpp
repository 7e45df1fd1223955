// reduce_bench shell: the ~1M-DOF QUAD4 tube through ffr-reduce, against a wall-time goal.
#include "bench.hpp"
#include "child_process.hpp"
#include "ffr_runs.hpp"
#include "meshes.hpp"
#include "report.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <sstream>

namespace ffr::bench {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double stage(const std::vector<std::pair<std::string, double>>& st, const std::string& name) {
  for (const auto& [k, v] : st)
    if (k == name) return v;
  return kNaN;
}

// First bending frequency of the tube as a clamped Euler-Bernoulli beam (beta_1 L = 1.8751),
// thin-walled annulus of mean radius R: only a plausibility check of the shell model (shear
// and shell flexibility make the FE value a few percent lower at L/R = 10).
double beam_f1(const IsoMaterial& m, double R, double t, double L) {
  const double ro = R + t / 2, ri = R - t / 2;
  const double A = M_PI * (ro * ro - ri * ri), I = M_PI / 4 * (std::pow(ro, 4) - std::pow(ri, 4));
  return 1.8751 * 1.8751 / (2 * M_PI * L * L) * std::sqrt(m.E * I / (m.rho * A));
}

}  // namespace

int run_shell(const Options& o) {
  const std::vector<std::int64_t> sizes = o.sizes.empty() ? std::vector<std::int64_t>{1000000} : o.sizes;
  const int modes = o.modes > 0 ? o.modes : 30;
  const IsoMaterial mat;
  Table head({"DOF", "elements", "thr", "wall s", "CPU s", "peak MiB", "goal", "f1 Hz", "f1 beam Hz", "load"});
  Table stages({"DOF", "thr", "mesh", "assembly", "constraints", "analyze", "factorize", "lanczos", "solves", "checks", "invariants",
                "visual", "other"});
  std::string notes, commands;
  int status = 0;
  for (auto target : sizes) {
    const MeshCase mesh = tube_mesh(o.workdir, target);
    const std::string stem = mesh.msh.stem().string();
    std::fprintf(stderr, "[%s DOF] mesh %s: %s nodes, %s DOF%s\n", grouped(target).c_str(), mesh.msh.filename().c_str(),
                 grouped(mesh.nodes).c_str(), grouped(mesh.dof).c_str(), mesh.reused ? " (cached)" : "");
    const fs::path json = o.workdir / (stem + ".json");
    write_shell_part(json, mesh.msh, mat, o.thickness, modes);
    const long long elements = static_cast<long long>(mesh.size) * (mesh.nodes / static_cast<long long>(mesh.size) - 1);
    for (int t : o.threads) {
      const fs::path dir = o.workdir / (stem + "_t" + std::to_string(t));
      fs::create_directories(dir);
      const ChildSpec f = ffr_reduce_run(o, json, dir, stem, t, commands);
      wait_for_quiet(o.wait_load, o.wait_max_s, true);
      const ChildResult r = run_child(f);
      const auto st = read_stage_times(f.err);
      std::vector<double> fr;
      if (r.ok()) fr = read_sid_frequencies(dir / (stem + ".sid.h5"));
      else {
        status = 1;
        notes += "- " + grouped(mesh.dof) + " DOF, " + std::to_string(t) + " thread(s): ffr-reduce failed (exit " +
                 std::to_string(r.exit_status) + ", signal " + std::to_string(r.signal) + (r.memory_capped ? ", memory cap" : "") +
                 "), see " + f.err.string() + "\n";
      }
      std::fprintf(stderr, "  ffr-reduce, %d thread(s): %s s wall, %s s CPU, %.0f MiB (load %.1f)\n", t,
                   secs(r.wall_s).c_str(), secs(r.cpu_s()).c_str(), static_cast<double>(r.peak_rss_kib) / 1024,
                   r.load_before);
      const double wall = r.ok() ? r.wall_s : kNaN;
      head.add({grouped(mesh.dof), grouped(elements), std::to_string(t), secs(wall), secs(r.ok() ? r.cpu_s() : kNaN),
                fixed(r.ok() ? static_cast<double>(r.peak_rss_kib) / 1024 : kNaN, 0),
                r.ok() ? (r.wall_s <= o.goal_s ? "met" : "missed") : "—", fr.empty() ? "—" : fixed(fr[0], 2),
                fixed(beam_f1(mat, 0.1, o.thickness, 1.0), 2), fixed(r.load_before, 1)});
      if (r.ok()) {
        double sum = 0;
        for (const char* k : {"mesh", "model", "assembly", "modes", "invariants", "stiffening", "visual"})
          if (!std::isnan(stage(st, k))) sum += stage(st, k);
        const double solves = stage(st, "solves");
        stages.add({grouped(mesh.dof), std::to_string(t), secs(stage(st, "mesh")), secs(stage(st, "assembly")),
                    secs(stage(st, "constraints")), secs(stage(st, "analyze")), secs(stage(st, "factorize")), secs(stage(st, "lanczos")),
                    std::isnan(solves) ? "—" : std::to_string(static_cast<long>(solves)), secs(stage(st, "checks")),
                    secs(stage(st, "invariants")), secs(stage(st, "visual")), secs(r.wall_s - sum)});
        std::ostringstream fl;
        fl << "- " << grouped(mesh.dof) << " DOF, " << t << " thread(s): first frequencies [Hz]";
        for (std::size_t k = 0; k < fr.size() && k < 8; ++k) fl << (k ? ", " : " ") << fixed(fr[k], 2);
        fl << (fr.size() > 8 ? ", ..., " + fixed(fr.back(), 2) : "") << "\n";
        notes += fl.str();
      }
    }
  }
  std::printf("\nffr-reduce, QUAD4 tube R = 0.1 m, L = 1 m, t = %g m, clamped, %d modes; goal %s s\n%s", o.thickness, modes,
              secs(o.goal_s).c_str(), head.text().c_str());
  std::printf("\nstages [s]\n%s\n%s", stages.text().c_str(), notes.c_str());
  if (!o.md.empty()) {
    const std::time_t now = std::time(nullptr);
    char when[64];
    std::strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    std::ostringstream md;
    md << "\n## " << (o.title.empty() ? "1M-DOF shell model" : o.title) << "\n\n"
       << "Finished " << when << ". Steel tube, mean radius 0.1 m, length 1 m, wall " << o.thickness
       << " m, structured QUAD4 shell grid (gmsh), the ring x = 0 clamped, " << modes << " modes; goal: "
       << secs(o.goal_s) << " s wall. Per row, in `" << o.workdir.string() << "`:\n\n";
    md << commands << "\n`f1 beam` is the clamped Euler-Bernoulli beam value of the tube (a plausibility check only).\n\n"
       << head.markdown() << "\nStages (ffr-reduce's stderr) [s]:\n\n" << stages.markdown() << "\n" << notes;
    append_file(o.md, md.str());
  }
  return status;
}

}  // namespace ffr::bench
