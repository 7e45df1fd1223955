#include "variables.hpp"

namespace ffr::fmu {

LoadSlot load_slot(const runtime::Model& model, const runtime::PointLoad& load) {
  const runtime::Marker& m = model.markers[load.marker];
  if (m.body < 0) return {};
  if (m.node >= 0) return {m.body, 1 + m.node};
  if (m.c.isZero(0.0)) return {m.body, 0};
  return {};
}

std::vector<Variable> variables(const runtime::Model& model) {
  std::vector<Variable> v;
  for (std::size_t o = 0; o < model.outputs.size(); ++o) {
    const auto& out = model.outputs[o];
    for (int k = 0; k < out.size; ++k)
      v.push_back({out.size == 1 ? out.name : out.name + "[" + std::to_string(k) + "]",
                   "model output " + out.name, Variable::Kind::Output, static_cast<int>(o), k});
  }
  static const char* const kMotion[3] = {"value", "rate", "acceleration"};
  for (std::size_t m = 0; m < model.motions.size(); ++m) {
    const std::string& joint = model.joints[model.motions[m].joint].name;
    for (int k = 0; k < 3; ++k)
      v.push_back({joint + "." + kMotion[k],
                   "prescribed " + std::string(kMotion[k]) + " of joint " + joint + " (replaces its table once set)",
                   Variable::Kind::Motion, static_cast<int>(m), k});
  }
  for (std::size_t l = 0; l < model.loads.size(); ++l) {
    const auto& load = model.loads[l];
    if (load.name.empty() || load_slot(model, load).body < 0) continue;
    for (int k = 0; k < 3; ++k)
      v.push_back({load.name + "[" + std::to_string(k) + "]",
                   std::string(load.torque ? "torque" : "force") + " added to " + load.name + "'s table (global)",
                   Variable::Kind::Load, static_cast<int>(l), k});
  }
  if (!model.settings.adaptive)
    v.push_back({"solver.step", "the integrator's step [s] (solver.step of the model file); a communication step is a "
                 "whole number of it", Variable::Kind::Parameter, 0, 0});
  return v;
}

}  // namespace ffr::fmu
