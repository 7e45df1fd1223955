// reduce_bench solid: ffr-reduce and CalculiX *FREQUENCY on the identical TET10 plate meshes.
#include "bench.hpp"
#include "ffr/calculix/deck.hpp"
#include "child_process.hpp"
#include "ffr_runs.hpp"
#include "meshes.hpp"
#include "report.hpp"

#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/part/part.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace ffr::bench {
namespace fs = std::filesystem;
using calculix::read_frequencies;
using calculix::write_frequency_deck;

std::vector<std::pair<std::string, std::string>> thread_env(int t, bool calculix) {
  const std::string n = std::to_string(t);
  std::vector<std::pair<std::string, std::string>> env{{"OMP_NUM_THREADS", n}, {"OPENBLAS_NUM_THREADS", n}};
  if (calculix) {
    // CalculiX takes its thread counts from these (ccx 2.20, ccx_2.20.c); it prints what it used.
    env.emplace_back("CCX_NPROC_EQUATION_SOLVER", n);
    env.emplace_back("CCX_NPROC_STIFFNESS", n);
    env.emplace_back("CCX_NPROC_RESULTS", n);
    env.emplace_back("NUMBER_OF_CPUS", n);
  }
  return env;
}

std::string env_text(const std::vector<std::pair<std::string, std::string>>& env) {
  std::string s;
  for (const auto& [k, v] : env) s += k + "=" + v + " ";
  return s;
}

std::int64_t memory_cap_kib(const Options& o) {
  if (o.mem_cap_mib > 0) return o.mem_cap_mib * 1024;
  return std::max<std::int64_t>(mem_available_kib() - (1 << 20), 1 << 20);
}

fs::path ffr_sid(const fs::path& dir, const std::string& stem, const std::string& factorization) {
  return dir / (stem + (factorization.empty() ? "" : "-" + factorization) + ".sid.h5");
}

ChildSpec ffr_reduce_run(const Options& o, const fs::path& json, const fs::path& dir, const std::string& stem, int t,
                         std::string& commands, const std::string& factorization) {
  ChildSpec f;
  const fs::path sid = ffr_sid(dir, stem, factorization);
  f.argv = {o.ffr.string(), json.string(), "-o", sid.string(), "--threads", std::to_string(t)};
  if (!factorization.empty()) {
    f.argv.push_back("--factorization");
    f.argv.push_back(factorization);
  }
  f.env = thread_env(t, false);
  f.cwd = dir;
  const std::string tag = factorization.empty() ? "ffr" : "ffr-" + factorization;
  f.out = dir / (tag + ".out");
  f.err = dir / (tag + ".err");
  f.max_rss_kib = memory_cap_kib(o);
  commands += "    " + env_text(f.env) + "ffr-reduce " + json.filename().string() + " -o " +
              (dir.filename() / sid.filename()).string() + " --threads " + std::to_string(t) +
              (factorization.empty() ? "" : " --factorization " + factorization) + "\n";
  return f;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
double mib(std::int64_t kib) { return static_cast<double>(kib) / 1024.0; }

struct Row {
  MeshCase mesh;
  int threads = 1;
  std::string factorization;  ///< ffr-reduce's --factorization ("": its default)
  ChildResult ffr;
  std::string ffr_note;
  std::vector<std::pair<std::string, double>> stages;
  std::vector<double> f_ffr;
  bool ccx_ran = false;
  ChildResult ccx;
  std::string ccx_note;
  std::vector<double> f_ccx;
  int ccx_cpus = 0;
};

double stage(const Row& r, const std::string& name) {
  for (const auto& [k, v] : r.stages)
    if (k == name) return v;
  return kNaN;
}

// Largest "Using up to N cpu(s)" CalculiX printed.
int ccx_cpus_used(const fs::path& out) {
  std::ifstream f(out);
  std::string line;
  int m = 0;
  while (std::getline(f, line)) {
    const auto p = line.find("Using up to ");
    if (p != std::string::npos) m = std::max(m, std::atoi(line.c_str() + p + 12));
  }
  return m;
}

// Power law through the last two successful CalculiX rows with these threads (or a default
// exponent through the last one) to skip runs that would exceed a cap anyway.
bool predict_ccx(const std::vector<Row>& rows, int threads, std::int64_t dof, double& t_pred, double& m_pred) {
  std::vector<const Row*> done;  // one a size: the rows of the backends share its CalculiX run
  for (const auto& r : rows)
    if (r.threads == threads && r.ccx_ran && r.ccx.ok() && (done.empty() || done.back()->mesh.dof != r.mesh.dof))
      done.push_back(&r);
  if (done.empty()) return false;
  const Row& b = *done.back();
  double pt = 1.5, pm = 1.3;
  if (done.size() >= 2) {
    const Row& a = *done[done.size() - 2];
    const double ln = std::log(static_cast<double>(b.mesh.dof) / static_cast<double>(a.mesh.dof));
    if (ln > 0.1) {
      pt = std::max(1.0, std::log(b.ccx.wall_s / a.ccx.wall_s) / ln);
      pm = std::max(1.0, std::log(static_cast<double>(b.ccx.peak_rss_kib) / static_cast<double>(a.ccx.peak_rss_kib)) / ln);
    }
  }
  const double x = static_cast<double>(dof) / static_cast<double>(b.mesh.dof);
  t_pred = b.ccx.wall_s * std::pow(x, pt);
  m_pred = static_cast<double>(b.ccx.peak_rss_kib) * std::pow(x, pm);
  return true;
}

std::string outcome(const ChildResult& r, const fs::path& err) {
  if (r.timed_out) return "killed at the time cap";
  if (r.memory_capped) return "killed at the memory cap";
  if (r.signal) return "killed by signal " + std::to_string(r.signal);
  if (r.exit_status != 0) return "exit " + std::to_string(r.exit_status) + " (see " + err.string() + ")";
  return "";
}

std::string plural(int t) { return std::to_string(t) + (t == 1 ? " thread" : " threads"); }

void run_size(const Options& o, std::int64_t target, int modes, const IsoMaterial& mat, std::vector<Row>& rows,
              std::string& commands) {
  MeshCase mesh = plate_mesh(o.workdir, target);
  std::fprintf(stderr, "[%s DOF] mesh %s: %s nodes, %s DOF%s\n", grouped(target).c_str(), mesh.msh.filename().c_str(),
               grouped(mesh.nodes).c_str(), grouped(mesh.dof).c_str(),
               mesh.reused ? " (cached)" : (", gmsh " + secs(mesh.mesh_seconds) + " s").c_str());
  const std::string stem = mesh.msh.stem().string();
  const fs::path json = o.workdir / (stem + ".json");
  write_solid_part(json, mesh.msh, mat, modes);

  // CalculiX decks, written from the mesh as ffr-reduce reads it (then the mesh is dropped).
  std::vector<fs::path> rundirs;
  std::vector<bool> want_ccx;
  for (int t : o.threads) {
    const fs::path dir = o.workdir / (stem + "_t" + std::to_string(t));
    fs::create_directories(dir);
    rundirs.push_back(dir);
    want_ccx.push_back(o.ccx_max_dof == 0 || mesh.dof <= o.ccx_max_dof);
  }
  {
    const preproc::PartSpec part = preproc::load_part(json);
    const preproc::Mesh m = preproc::load_mesh(part);
    for (std::size_t i = 0; i < rundirs.size(); ++i)
      if (want_ccx[i]) write_frequency_deck(m, "body", "clamp", mat, modes, rundirs[i] / (stem + ".inp"));
  }

  for (std::size_t i = 0; i < o.threads.size(); ++i) {
    const int t = o.threads[i];
    const fs::path dir = rundirs[i];
    // ffr-reduce once per factorization backend, one after the other, then CalculiX once; the
    // rows of this size and thread count share that CalculiX run.
    const std::size_t first = rows.size();
    for (const std::string& fact : o.factorizations) {
      Row fr;
      fr.mesh = mesh;
      fr.threads = t;
      fr.factorization = fact;
      const ChildSpec f = ffr_reduce_run(o, json, dir, stem, t, commands, fact);
      wait_for_quiet(o.wait_load, o.wait_max_s, true);
      fr.ffr = run_child(f);
      fr.ffr_note = outcome(fr.ffr, f.err);
      fr.stages = read_stage_times(f.err);
      if (fr.ffr.ok()) fr.f_ffr = read_sid_frequencies(ffr_sid(dir, stem, fact));
      std::fprintf(stderr, "  ffr-reduce%s, %s: %s s wall, %s s CPU, %.0f MiB %s(load %.1f)\n",
                   fact.empty() ? "" : (" --factorization " + fact).c_str(), plural(t).c_str(), secs(fr.ffr.wall_s).c_str(),
                   secs(fr.ffr.cpu_s()).c_str(), mib(fr.ffr.peak_rss_kib), fr.ffr_note.c_str(), fr.ffr.load_before);
      rows.push_back(std::move(fr));
    }
    Row r = rows[first];
    double tp = 0, mp = 0;
    const std::int64_t cap = memory_cap_kib(o);
    if (!want_ccx[i]) {
      r.ccx_note = "not run (above --ccx-max-dof)";
    } else if (predict_ccx(rows, t, mesh.dof, tp, mp) && (tp > o.ccx_timeout_s || mp > static_cast<double>(cap))) {
      std::ostringstream n;
      n << "not run: extrapolated " << secs(tp) << " s, " << fixed(mp / 1024, 0) << " MiB exceeds the cap ("
        << secs(o.ccx_timeout_s) << " s, " << fixed(mib(cap), 0) << " MiB)";
      r.ccx_note = n.str();
    } else {
      ChildSpec c;
      c.argv = {o.ccx, "-i", stem};
      c.env = thread_env(t, true);
      c.cwd = dir;
      c.out = dir / "ccx.out";
      c.err = dir / "ccx.err";
      c.timeout_s = o.ccx_timeout_s;
      c.max_rss_kib = cap;
      commands += "    (cd " + dir.filename().string() + " && " + env_text(c.env) + "ccx -i " + stem + ")\n";
      wait_for_quiet(o.wait_load, o.wait_max_s, true);
      r.ccx = run_child(c);
      r.ccx_ran = true;
      r.ccx_note = outcome(r.ccx, c.err);
      r.ccx_cpus = ccx_cpus_used(c.out);
      r.f_ccx = read_frequencies(dir / (stem + ".dat"));
      if (r.ccx.ok() && r.f_ccx.empty()) {
        r.ccx.exit_status = 1;
        r.ccx_note = "no eigenvalue table in " + (dir / (stem + ".dat")).string();
      }
      std::fprintf(stderr, "  ccx, %s: %s s wall, %s s CPU, %.0f MiB %s(load %.1f)\n", plural(t).c_str(),
                   secs(r.ccx.wall_s).c_str(), secs(r.ccx.cpu_s()).c_str(), mib(r.ccx.peak_rss_kib),
                   r.ccx_note.c_str(), r.ccx.load_before);
    }
    for (std::size_t k = first; k < rows.size(); ++k) {
      Row& fr = rows[k];
      fr.ccx_ran = r.ccx_ran;
      fr.ccx = r.ccx;
      fr.ccx_note = k == first ? r.ccx_note : "";
      fr.f_ccx = r.f_ccx;
      fr.ccx_cpus = r.ccx_cpus;
      if (!fr.f_ffr.empty() && !fr.f_ccx.empty())
        std::fprintf(stderr, "  %s: max |f_ffr / f_ccx - 1| over %zu modes: %.2e\n",
                     fr.factorization.empty() ? "default" : fr.factorization.c_str(),
                     std::min(fr.f_ffr.size(), fr.f_ccx.size()), max_relative_difference(fr.f_ffr, fr.f_ccx));
    }
  }
}

std::string exponent(double a, double b, double na, double nb) {
  if (!(a > 0) || !(b > 0)) return "—";
  return fixed(std::log(b / a) / std::log(nb / na), 2);
}

}  // namespace

int run_solid(const Options& o) {
  const std::vector<std::int64_t> sizes = o.sizes.empty() ? std::vector<std::int64_t>{100000, 265000, 500000, 1000000} : o.sizes;
  const int modes = o.modes > 0 ? o.modes : 20;
  const IsoMaterial mat;  // steel
  std::vector<Row> rows;
  std::string commands;
  for (auto target : sizes) run_size(o, target, modes, mat, rows, commands);

  Table head({"DOF", "thr", "factorization", "ffr wall s", "ffr CPU s", "ffr MiB", "ccx wall s", "ccx CPU s", "ccx MiB", "ccx/ffr wall",
              "ccx/ffr CPU", "ffr/ccx mem", "max df/f", "load"});
  Table stages({"DOF", "thr", "factorization", "mesh", "assembly", "constraints", "analyze", "factorize", "lanczos", "solves", "checks", "invariants",
                "visual", "other", "total"});
  Table growth({"DOF from", "DOF to", "thr", "ffr wall", "ffr CPU", "ffr mem", "ccx wall", "ccx CPU", "ccx mem"});
  std::string notes;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const bool fo = r.ffr.ok(), co = r.ccx_ran && r.ccx.ok();
    auto pick = [](bool ok, double v) { return ok ? v : kNaN; };
    const double fw = pick(fo, r.ffr.wall_s), fc = pick(fo, r.ffr.cpu_s()), fm = pick(fo, mib(r.ffr.peak_rss_kib));
    const double cw = pick(co, r.ccx.wall_s), cc = pick(co, r.ccx.cpu_s()), cm = pick(co, mib(r.ccx.peak_rss_kib));
    std::string load = fixed(r.ffr.load_before, 1);
    if (r.ccx_ran) load += " / " + fixed(r.ccx.load_before, 1);
    const std::string fact = r.factorization.empty() ? "default" : r.factorization;
    head.add({grouped(r.mesh.dof), std::to_string(r.threads), fact, secs(fw), secs(fc), fixed(fm, 0), secs(cw), secs(cc),
              fixed(cm, 0), fixed(cw / fw, 2), fixed(cc / fc, 2), fixed(fm / cm, 2),
              sig3(max_relative_difference(r.f_ffr, r.f_ccx)), load});
    if (fo) {
      double sum = 0;
      for (const char* k : {"mesh", "model", "assembly", "modes", "invariants", "stiffening", "visual"})
        if (!std::isnan(stage(r, k))) sum += stage(r, k);
      const double solves = stage(r, "solves");
      stages.add({grouped(r.mesh.dof), std::to_string(r.threads), fact, secs(stage(r, "mesh")), secs(stage(r, "assembly")),
                  secs(stage(r, "constraints")), secs(stage(r, "analyze")), secs(stage(r, "factorize")), secs(stage(r, "lanczos")),
                  std::isnan(solves) ? "—" : std::to_string(static_cast<long>(solves)), secs(stage(r, "checks")),
                  secs(stage(r, "invariants")), secs(stage(r, "visual")), secs(r.ffr.wall_s - sum), secs(r.ffr.wall_s)});
    }
    if (!r.ffr_note.empty())
      notes += "- " + grouped(r.mesh.dof) + " DOF, " + plural(r.threads) + ": ffr-reduce (" + fact + ") " + r.ffr_note + "\n";
    if (!r.ccx_note.empty()) notes += "- " + grouped(r.mesh.dof) + " DOF, " + plural(r.threads) + ": CalculiX " + r.ccx_note + "\n";
    if (r.ccx_ran && r.ccx_cpus != r.threads && !r.ccx_note.empty())
      notes += "- " + grouped(r.mesh.dof) + " DOF: CalculiX reported using up to " + std::to_string(r.ccx_cpus) + " cpu(s)\n";
    for (std::size_t j = i; j-- > 0;) {
      const Row& a = rows[j];
      if (a.threads != r.threads || a.factorization != r.factorization || a.mesh.dof == r.mesh.dof) continue;
      const double na = static_cast<double>(a.mesh.dof), nb = static_cast<double>(r.mesh.dof);
      const bool ca = a.ccx_ran && a.ccx.ok();
      growth.add({grouped(a.mesh.dof), grouped(r.mesh.dof), std::to_string(r.threads),
                  exponent(a.ffr.ok() ? a.ffr.wall_s : kNaN, fw, na, nb), exponent(a.ffr.ok() ? a.ffr.cpu_s() : kNaN, fc, na, nb),
                  exponent(a.ffr.ok() ? mib(a.ffr.peak_rss_kib) : kNaN, fm, na, nb),
                  exponent(ca ? a.ccx.wall_s : kNaN, cw, na, nb), exponent(ca ? a.ccx.cpu_s() : kNaN, cc, na, nb),
                  exponent(ca ? mib(a.ccx.peak_rss_kib) : kNaN, cm, na, nb)});
      break;
    }
  }

  std::printf("\nffr-reduce vs CalculiX *FREQUENCY, TET10 plate, clamped, %d modes (wall/CPU s, peak RSS MiB)\n%s", modes,
              head.text().c_str());
  std::printf("\nffr-reduce stages [s]\n%s", stages.text().c_str());
  if (!growth.empty()) std::printf("\ngrowth exponents p (time or memory ~ DOF^p between successive sizes)\n%s", growth.text().c_str());
  if (!notes.empty()) std::printf("\n%s", notes.c_str());

  if (!o.md.empty()) {
    std::ostringstream md;
    const std::time_t now = std::time(nullptr);
    char when[64];
    std::strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    md << "\n## " << (o.title.empty() ? "ffr-reduce vs CalculiX, TET10 plate" : o.title) << "\n\n"
       << "Finished " << when << ". Plate 240 x 120 x 30 mm with four holes, steel, TET10 (gmsh), the face x = 0 "
       << "clamped, " << modes << " modes. Commands, in `" << o.workdir.string() << "`:\n\n" << commands;
    md << "\nWall and CPU (user + sys) seconds and peak RSS of each process; `max df/f` = max over the modes of "
       << "|f_ffr / f_ccx - 1|; `load` = 1-minute load average before the ffr / ccx run.\n\n"
       << head.markdown() << "\nffr-reduce stages (its stderr) [s]:\n\n" << stages.markdown();
    if (!growth.empty()) md << "\nGrowth exponents p (quantity ~ DOF^p between successive rows):\n\n" << growth.markdown();
    if (!notes.empty()) md << "\n" << notes;
    append_file(o.md, md.str());
  }
  for (const auto& r : rows)
    if (!r.ffr.ok()) return 1;
  return 0;
}

}  // namespace ffr::bench
