#include "ffr/formats/stress_history.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/formats/json_input.hpp"
#include "ffr/formats/results_io.hpp"

#include <optional>
#include <system_error>

namespace ffr::formats {
namespace {

namespace fs = std::filesystem;

// The model file: as given, else relative to the run's folder (ffr-sim records it as it was given).
fs::path locate_model(const fs::path& run, const std::string& given) {
  const fs::path p(given);
  std::error_code ec;
  if (p.is_absolute() || fs::exists(p, ec)) return p;
  const fs::path beside = run.parent_path() / p;
  if (fs::exists(beside, ec)) return beside;
  throw FormatError(run.string(), "/@model", "the model file '" + given +
                                                  "' the run names is not found (give it with --model MODEL.json)");
}

}  // namespace

StressHistory recover_stress(const fs::path& run, const std::string& body, const fs::path& model) {
  const Results res = read_results(run);
  fs::path model_path = model;
  if (model_path.empty()) {
    const h5::Reader r(run);
    if (!r.has_attr("/", "model")) r.fail("/@model", "the run names no model file (give it with --model MODEL.json)");
    model_path = locate_model(run, r.attr_string("/", "model"));
  }
  const auto doc = JsonDocument::load(model_path);
  const JsonNode root = doc.root();
  std::optional<fs::path> sid_path;
  for (const auto& b : root.at("bodies").items())
    if (b.has("name") && b.at("name").string() == body) {
      if (!b.has("sid")) b.fail("body '" + body + "' has no SID (stress is recovered for flexible bodies of a SID)");
      sid_path = model_path.parent_path() / b.at("sid").string();
    }
  if (!sid_path) root.at("bodies").fail("no body named '" + body + "'");
  std::string output;
  if (auto outs = root.find("outputs"))
    for (const auto& o : outs->items())
      if (o.has("type") && o.at("type").string() == "modal_coordinates" && o.has("body") && o.at("body").string() == body)
        output = o.at("name").string();
  if (output.empty())
    root.fail("no output of type modal_coordinates for body '" + body + "': add {\"name\": \"q_" + body +
              "\", \"type\": \"modal_coordinates\", \"body\": \"" + body + "\"} to \"outputs\" and run again");
  const auto* q = res.find(output);
  if (!q) throw FormatError(run.string(), "/outputs/" + output, "missing: the run is not of this model file");
  auto stress = read_modal_stress(*sid_path);
  if (!stress)
    throw FormatError(sid_path->string(), "/stress",
                      "the SID has no stress group: reduce the part with \"stress\": {\"group\": NAME} or "
                      "{\"surface\": true}");
  const auto nq = static_cast<Eigen::Index>(stress->modes.size());
  if (q->values.cols() != nq)
    throw FormatError(run.string(), "/outputs/" + output,
                      std::to_string(q->values.cols()) + " modal coordinates, the SID " + sid_path->string() + " has " +
                          std::to_string(nq) + " modes");

  StressHistory h;
  h.body = body;
  h.sid = *sid_path;
  h.output = output;
  h.selection = stress->selection;
  h.time = res.time;
  h.node = stress->node;
  h.position = stress->position;
  h.layer.resize(stress->node.size());
  for (Eigen::Index i = 0; i < stress->size(); ++i) h.layer[static_cast<std::size_t>(i)] = stress->layer_of(i);
  const Eigen::Index nt = res.time.size(), ns = stress->size();
  h.von_mises.resize(nt, ns);
  h.principal.assign(static_cast<std::size_t>(ns), Eigen::MatrixXd(nt, 3));
  for (Eigen::Index t = 0; t < nt; ++t) {
    ModalStress::RowsX6 S = ModalStress::RowsX6::Zero(ns, 6);
    for (Eigen::Index k = 0; k < nq; ++k) S += q->values(t, k) * stress->modes[static_cast<std::size_t>(k)];
    for (Eigen::Index i = 0; i < ns; ++i) {
      const Eigen::Matrix<double, 6, 1> s = S.row(i).transpose();
      h.von_mises(t, i) = formats::von_mises(s);
      h.principal[static_cast<std::size_t>(i)].row(t) = principal_stresses(s).transpose();
    }
  }
  return h;
}

}  // namespace ffr::formats
