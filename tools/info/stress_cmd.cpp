// ffr-info --stress RUN.h5 BODY [--model MODEL.json] [--json]: the stress over time at the nodes
// of a body's SID /stress group (formats/SPEC.md section 12.1), computed by
// formats::recover_stress (stress_history.hpp), which the Python package's ffr.stress() shares.
#include "summary.hpp"

#include "ffr/formats/stress_history.hpp"

#include <cstdio>
#include <iostream>

namespace ffr::info {

namespace fs = std::filesystem;

int run_stress(const fs::path& run, const std::string& body, const std::string& model_option, bool json) {
  const formats::StressHistory h = formats::recover_stress(run, body, model_option);
  const Eigen::Index nt = h.time.size(), ns = static_cast<Eigen::Index>(h.node.size());
  const auto& vm = h.von_mises;
  const auto& principal = h.principal;
  const std::string sid = h.sid.string();

  if (json) {
    nlohmann::ordered_json nodes = nlohmann::ordered_json::array();
    for (Eigen::Index i = 0; i < ns; ++i) {
      nlohmann::ordered_json p = nlohmann::ordered_json::array();
      for (Eigen::Index t = 0; t < nt; ++t) {
        const auto& P = principal[static_cast<std::size_t>(i)];
        p.push_back({P(t, 0), P(t, 1), P(t, 2)});
      }
      std::vector<double> v(vm.col(i).data(), vm.col(i).data() + nt);
      nodes.push_back({{"node", h.node[static_cast<std::size_t>(i)]},
                       {"position", {h.position(i, 0), h.position(i, 1), h.position(i, 2)}},
                       {"layer", formats::layer_name(h.layer[static_cast<std::size_t>(i)])},
                       {"von_mises", v},
                       {"principal", p}});
    }
    std::vector<double> time(h.time.data(), h.time.data() + nt);
    const nlohmann::ordered_json out = {{"body", body}, {"sid", sid}, {"output", h.output},
                                        {"selection", h.selection}, {"time", time}, {"nodes", nodes}};
    std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return 0;
  }
  // The layer column only when shells carry stress: a solid-only table reads as before.
  bool shells = false;
  long long nodes = 0;  // a node's rows are adjacent (SPEC.md section 12.1)
  for (Eigen::Index i = 0; i < ns; ++i) {
    shells = shells || h.layer[static_cast<std::size_t>(i)] != formats::kSolid;
    nodes += i == 0 || h.node[static_cast<std::size_t>(i)] != h.node[static_cast<std::size_t>(i - 1)];
  }
  const std::string rows = shells ? " in " + std::to_string(ns) + " rows (shells: top, middle, bottom)" : "";
  std::printf("%s: body %s, stress at %lld nodes%s (%s) from %s, modal coordinates '%s', %lld samples\n",
              run.string().c_str(), body.c_str(), nodes, rows.c_str(), h.selection.c_str(), sid.c_str(),
              h.output.c_str(), static_cast<long long>(nt));
  std::printf("%10s %12s %12s %12s%s %14s %12s %14s %14s %14s\n", "node", "x", "y", "z", shells ? "  layer " : "",
              "max von Mises", "at t [s]", "sigma_1", "sigma_2", "sigma_3");
  for (Eigen::Index i = 0; i < ns; ++i) {
    Eigen::Index t = 0;
    if (nt) vm.col(i).maxCoeff(&t);
    const auto& P = principal[static_cast<std::size_t>(i)];
    const std::string layer = shells ? "  " + std::string(formats::layer_name(h.layer[static_cast<std::size_t>(i)])) : "";
    std::printf("%10lld %12.6g %12.6g %12.6g%-8s %14.6g %12.6g %14.6g %14.6g %14.6g\n",
                static_cast<long long>(h.node[static_cast<std::size_t>(i)]), h.position(i, 0),
                h.position(i, 1), h.position(i, 2), layer.c_str(), nt ? vm(t, i) : 0.0, nt ? h.time(t) : 0.0,
                nt ? P(t, 0) : 0.0, nt ? P(t, 1) : 0.0, nt ? P(t, 2) : 0.0);
  }
  std::fflush(stdout);
  return 0;
}

}  // namespace ffr::info
