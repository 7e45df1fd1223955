// The JSON summary of an ffr-sim results file.
#include "summary.hpp"

namespace ffr::info {

nlohmann::json summarize_results(const formats::Results& r, const std::string& file) {
  using nlohmann::json;
  json outputs = json::array();
  for (const auto& o : r.outputs) {
    json last = json::array(), lo = json::array(), hi = json::array();
    if (o.values.rows() > 0)
      for (Eigen::Index c = 0; c < o.values.cols(); ++c) {
        last.push_back(o.values(o.values.rows() - 1, c));
        lo.push_back(o.values.col(c).minCoeff());
        hi.push_back(o.values.col(c).maxCoeff());
      }
    outputs.push_back({{"name", o.name}, {"type", o.type}, {"shape", {o.values.rows(), o.values.cols()}},
                       {"final", last}, {"min", lo}, {"max", hi}});
  }
  const auto nt = r.time.size();
  json summary = {{"file", file},
                  {"kind", "results"},
                  {"generator", r.generator},
                  {"time", {{"samples", nt}, {"start", nt ? json(r.time[0]) : json(nullptr)},
                            {"end", nt ? json(r.time[nt - 1]) : json(nullptr)}}},
                  {"steps", r.steps},
                  {"newton_iterations", r.newton_iterations},
                  {"integration_seconds", r.integration_seconds},
                  {"outputs", outputs},
                  {"complete", !r.stopped_at.has_value()}};
  if (r.stopped_at) {  // a run that stopped before its end (ffr-sim --keep-partial)
    summary["stopped_at"] = *r.stopped_at;
    summary["stop_reason"] = r.stop_reason;
  }
  return summary;
}

}  // namespace ffr::info
