// The JSON summary of a SID: rigid properties, modes, nodes, provenance, validation.
#include "summary.hpp"

#include "ffr/formats/validate.hpp"

#include <Eigen/Eigenvalues>

namespace ffr::info {
namespace {

using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json mat(const Eigen::Matrix3d& m) { return json::array({vec(m.row(0)), vec(m.row(1)), vec(m.row(2))}); }

json validation_json(const formats::ValidationReport& rep) {
  json failed = json::array(), checks = json::array();
  int applicable = 0;
  const formats::Check* worst = nullptr;
  for (const auto& c : rep.checks) {
    json j = {{"name", c.name}, {"where", c.where}, {"applicable", c.applicable}, {"pass", c.pass},
              {"abs", c.abs}, {"scale", c.scale}, {"rel", c.rel}, {"tol", c.tol}, {"note", c.note}};
    checks.push_back(j);
    if (!c.applicable) continue;
    ++applicable;
    if (!c.pass) failed.push_back(j);
    if (!worst || c.rel / std::max(c.tol, 1e-300) > worst->rel / std::max(worst->tol, 1e-300)) worst = &c;
  }
  json out = {{"ok", rep.ok()}, {"applicable", applicable}, {"failures", rep.failures()}, {"failed", failed},
              {"checks", checks}};
  if (worst) out["worst"] = {{"name", worst->name}, {"rel", worst->rel}, {"tol", worst->tol}};
  return out;
}

}  // namespace

json summarize_sid(const formats::Sid& s, const std::string& file, std::int64_t format_version) {
  const double m = s.refmod.mass;
  const Eigen::Vector3d com = s.mdCM.M0 / m;
  const Eigen::Matrix3d Jc = s.J.M0 - m * (com.squaredNorm() * Eigen::Matrix3d::Identity() - com * com.transpose());
  const Eigen::Vector3d principal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Jc, Eigen::EigenvaluesOnly).eigenvalues();

  json modes = json::array();
  for (Eigen::Index k = 0; k < s.nq(); ++k)
    modes.push_back({{"index", k}, {"frequency_hz", s.refmod.frequency_hz[k]}, {"type", formats::to_string(s.refmod.mode_type[k])}});
  json nodes = json::array();
  for (const auto& n : s.nodes) nodes.push_back({{"name", n.name}, {"origin", vec(n.origin)}});
  json interfaces = json::array();
  for (const auto& i : s.interfaces)
    interfaces.push_back({{"name", i.name}, {"node", s.nodes[static_cast<std::size_t>(i.node)].name},
                          {"coupling", i.coupling}, {"group", i.group}});
  json stiff = {{"present", s.stiffening.has_value()}, {"Ke_M1", !s.KeM1.empty()}};
  if (s.stiffening) {
    json names = json::array();
    for (const auto& i : s.stiffening->interfaces) names.push_back(i.name);
    stiff["interfaces"] = names;
  }
  const auto& p = s.provenance;
  json prov = {{"generator", p.generator}, {"part_sha256", p.part_sha256}, {"mesh_sha256", p.mesh_sha256},
               {"reduction_method", p.reduction_method}, {"reduction_parameters", p.reduction_parameters},
               {"damping_model", p.damping_model}, {"element_counts", p.element_counts},
               {"mass_model", p.mass_model}, {"extra", p.extra}};
  json out = {{"file", file},
              {"kind", "sid"},
              {"format_version", format_version},
              {"units", {{"length", s.units_length}, {"mass", s.units_mass}, {"time", s.units_time}}},
              {"mass", m},
              {"center_of_mass", vec(com)},
              {"inertia_about_O", mat(s.J.M0)},
              {"inertia_about_com", mat(Jc)},
              {"principal_moments_about_com", vec(principal)},
              {"reference", s.refmod.reference},
              {"nq", s.nq()},
              {"modes", modes},
              {"nodes", nodes},
              {"interfaces", interfaces},
              {"stiffening", stiff},
              {"provenance", prov},
              {"validation", validation_json(formats::validate(s))}};
  out["visual"] = s.visual.empty() ? json(nullptr)
                                   : json{{"vertices", s.visual.vertices.rows()}, {"triangles", s.visual.triangles.rows()}};
  return out;
}

}  // namespace ffr::info
