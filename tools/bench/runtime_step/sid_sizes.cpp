// ffr-bench-runtime-step --sids: the per-step time of one model run with SID files of the same
// part reduced from meshes of very different sizes (same modes). The runtime reads only the
// invariants and node data, so the step must cost the same whatever the mesh.
#include "sid_sizes.hpp"

#include "ffr/formats/text_file.hpp"
#include "models.hpp"
#include "ffr/runtime/runtime.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

using namespace ffr::runtime;

namespace bench {
namespace {

struct Run {
  double us_per_step = 0;
  double iterations_per_step = 0;
  std::vector<double> slider;  ///< first coordinate of the last body's origin, every step
};

Run run_once(const Model& model) {
  Run r;
  Data data(model);
  initialize(model, data);
  const StepTiming t = run_timed(model, data, &r.slider);
  r.us_per_step = t.us_per_step;
  r.iterations_per_step = t.iterations_per_step;
  return r;
}

}  // namespace

int run_sid_sizes(const std::filesystem::path& model_path, const std::string& placeholder,
                  const std::vector<SidCase>& sids, int rounds) {
  const std::string text = ffr::formats::read_text_file(model_path);
  const std::string key = "\"" + placeholder + "\"";
  const auto at = text.find(key);
  if (at == std::string::npos) throw std::runtime_error(model_path.string() + ": no \"" + placeholder + "\" to replace");
  std::vector<Model> models;
  for (const SidCase& c : sids) {
    std::string t = text;
    // (Quoted by appending: `"\"" + std::string&&` trips GCC 12's -Wrestrict false positive, PR105329.)
    std::string quoted = "\"";
    quoted += std::filesystem::absolute(c.path).string();
    quoted += '"';
    t.replace(at, key.size(), quoted);
    models.push_back(parse_model(t, model_path.parent_path(), model_path.string()));
  }
  std::printf("# per-step time vs the mesh the SID was reduced from (%s; %d rounds interleaved, best of each)\n",
              model_path.filename().string().c_str(), rounds);
  std::vector<Run> best(models.size());
  // The machine may be shared: every round runs every size, so a busy moment hits all alike.
  for (int round = 0; round < rounds; ++round)
    for (std::size_t i = 0; i < models.size(); ++i) {
      Run r = run_once(models[i]);
      if (round == 0 || r.us_per_step < best[i].us_per_step) best[i] = std::move(r);
    }
  std::printf("%12s %8s %12s %10s %14s %18s\n", "mesh DOF", "modes", "us/step", "ratio", "Newton/step",
              "slider vs finest");
  double lo = 1e300, hi = 0;
  for (const Run& r : best) lo = std::min(lo, r.us_per_step), hi = std::max(hi, r.us_per_step);
  const Run& finest = best.back();
  for (std::size_t i = 0; i < best.size(); ++i) {
    double dx = 0;
    for (std::size_t k = 0; k < best[i].slider.size() && k < finest.slider.size(); ++k)
      dx = std::max(dx, std::abs(best[i].slider[k] - finest.slider[k]));
    int nq = 0;
    for (const Body& b : models[i].bodies) nq += b.nq;
    std::printf("%12ld %8d %12.2f %10.3f %14.2f %16.3g m\n", sids[i].dof, nq, best[i].us_per_step,
                best[i].us_per_step / best[0].us_per_step, best[i].iterations_per_step, dx);
  }
  std::printf("slowest / fastest %.3f (required <= 1.05): %s\n", hi / lo, hi / lo <= 1.05 ? "met" : "NOT met");
  return 0;
}

}  // namespace bench
