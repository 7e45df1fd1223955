// ffr-info --stress RUN.h5 BODY [--model MODEL.json] [--json]: the stress over time at the nodes
// of a body's SID /stress group (formats/SPEC.md section 12.1), sigma(t) = sum_k q_k(t) S_k with
// q(t) the run's modal_coordinates output of that body, and its von Mises and principal stresses.
// The model file (to find the body's SID and its modal-coordinates output) is the one the run
// names in its root attribute `model`, unless --model gives it.
#include "summary.hpp"

#include "ffr/formats/json_input.hpp"
#include "ffr/formats/modal_stress.hpp"

#include <cstdio>
#include <iostream>

namespace ffr::info {
namespace {

namespace fs = std::filesystem;
using formats::FormatError;

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

int run_stress(const fs::path& run, const std::string& body, const std::string& model_option, bool json) {
  const formats::Results res = formats::read_results(run);
  std::string model_name = model_option;
  if (model_name.empty()) {
    const formats::h5::Reader r(run);
    if (!r.has_attr("/", "model")) r.fail("/@model", "the run names no model file (give it with --model MODEL.json)");
    model_name = r.attr_string("/", "model");
  }
  const fs::path model_path = model_option.empty() ? locate_model(run, model_name) : fs::path(model_option);
  const auto doc = formats::JsonDocument::load(model_path);
  const formats::JsonNode root = doc.root();
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
  const auto stress = formats::read_modal_stress(*sid_path);
  if (!stress)
    throw FormatError(sid_path->string(), "/stress",
                      "the SID has no stress group: reduce the part with \"stress\": {\"group\": NAME} or "
                      "{\"surface\": true}");
  const auto nq = static_cast<Eigen::Index>(stress->modes.size());
  if (q->values.cols() != nq)
    throw FormatError(run.string(), "/outputs/" + output,
                      std::to_string(q->values.cols()) + " modal coordinates, the SID " + sid_path->string() + " has " +
                          std::to_string(nq) + " modes");

  const Eigen::Index nt = res.time.size(), ns = stress->size();
  Eigen::MatrixXd vm(nt, ns);
  std::vector<Eigen::MatrixXd> principal(static_cast<std::size_t>(ns), Eigen::MatrixXd(nt, 3));
  for (Eigen::Index t = 0; t < nt; ++t) {
    formats::ModalStress::RowsX6 S = formats::ModalStress::RowsX6::Zero(ns, 6);
    for (Eigen::Index k = 0; k < nq; ++k) S += q->values(t, k) * stress->modes[static_cast<std::size_t>(k)];
    for (Eigen::Index i = 0; i < ns; ++i) {
      const Eigen::Matrix<double, 6, 1> s = S.row(i).transpose();
      vm(t, i) = formats::von_mises(s);
      principal[static_cast<std::size_t>(i)].row(t) = formats::principal_stresses(s).transpose();
    }
  }

  if (json) {
    nlohmann::ordered_json nodes = nlohmann::ordered_json::array();
    for (Eigen::Index i = 0; i < ns; ++i) {
      nlohmann::ordered_json p = nlohmann::ordered_json::array();
      for (Eigen::Index t = 0; t < nt; ++t) {
        const auto& P = principal[static_cast<std::size_t>(i)];
        p.push_back({P(t, 0), P(t, 1), P(t, 2)});
      }
      std::vector<double> v(vm.col(i).data(), vm.col(i).data() + nt);
      nodes.push_back({{"node", stress->node[static_cast<std::size_t>(i)]},
                       {"position", {stress->position(i, 0), stress->position(i, 1), stress->position(i, 2)}},
                       {"von_mises", v},
                       {"principal", p}});
    }
    std::vector<double> time(res.time.data(), res.time.data() + nt);
    const nlohmann::ordered_json out = {{"body", body}, {"sid", sid_path->string()}, {"output", output},
                                        {"selection", stress->selection}, {"time", time}, {"nodes", nodes}};
    std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return 0;
  }
  std::printf("%s: body %s, stress at %lld nodes (%s) from %s, modal coordinates '%s', %lld samples\n",
              run.string().c_str(), body.c_str(), static_cast<long long>(ns), stress->selection.c_str(),
              sid_path->string().c_str(), output.c_str(), static_cast<long long>(nt));
  std::printf("%10s %12s %12s %12s %14s %12s %14s %14s %14s\n", "node", "x", "y", "z", "max von Mises", "at t [s]",
              "sigma_1", "sigma_2", "sigma_3");
  for (Eigen::Index i = 0; i < ns; ++i) {
    Eigen::Index t = 0;
    if (nt) vm.col(i).maxCoeff(&t);
    const auto& P = principal[static_cast<std::size_t>(i)];
    std::printf("%10lld %12.6g %12.6g %12.6g %14.6g %12.6g %14.6g %14.6g %14.6g\n",
                static_cast<long long>(stress->node[static_cast<std::size_t>(i)]), stress->position(i, 0),
                stress->position(i, 1), stress->position(i, 2), nt ? vm(t, i) : 0.0, nt ? res.time(t) : 0.0,
                nt ? P(t, 0) : 0.0, nt ? P(t, 1) : 0.0, nt ? P(t, 2) : 0.0);
  }
  std::fflush(stdout);
  return 0;
}

}  // namespace ffr::info
