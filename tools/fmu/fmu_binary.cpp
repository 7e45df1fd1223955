// The shared object of an ffr FMU (binaries/linux64/<id>.so): the FMI 2.0 Co-Simulation
// functions (fmi2.h) on one ffr_sim handle of the C interface per instance. The model and its
// SID files are in the FMU's resources/ (written by ffr-fmu). Messages go to the importer's
// logger only; nothing is printed.
#include "fmi2.h"
#include "sim_handle.hpp"
#include "variables.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#define FFR_FMI_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

using ffr::fmu::Variable;

struct Instance {
  std::string name;
  fmi2CallbackFunctions callbacks;
  std::string folder;      ///< the resources folder
  std::string model_path;  ///< its model.json
  ffr_sim* sim = nullptr;
  std::vector<Variable> vars;
  std::vector<double> inputs;        ///< per variable (inputs only are used)
  std::vector<char> motion_set;      ///< per motion: an input of it has been set
  std::vector<double> output_buffer;
  bool terminated = false;
  bool has_loads = false;  ///< some inputs are point loads (summed per slot at each step)
  bool initialized = false;  ///< after fmi2ExitInitializationMode: parameters are fixed
  int step_parameter = -1;   ///< the value reference of solver.step, -1 if none (adaptive steps)
  ~Instance() { ffr_close(sim); }
};

/// What fmi2GetFMUstate keeps: the integrator's state, the inputs and which motions they drive.
struct SavedState {
  std::vector<double> state, inputs;
  std::vector<char> motion_set;
};

void log(const Instance* c, fmi2Status status, const std::string& message) {
  if (c && c->callbacks.logger)
    c->callbacks.logger(c->callbacks.componentEnvironment, c->name.c_str(), status,
                        status == fmi2OK ? "logStatusOK" : "logStatusError", "%s", message.c_str());
}

fmi2Status error(const Instance* c, const std::string& message) {
  log(c, fmi2Error, message);
  return fmi2Error;
}

// The resources folder from the importer's URI: file:///abs/path, file:/abs/path or a plain path.
std::string folder_of(const char* uri) {
  std::string s = uri ? uri : "";
  if (s.rfind("file://", 0) == 0) s = s.substr(7);
  else if (s.rfind("file:", 0) == 0) s = s.substr(5);
  if (s.rfind("localhost/", 0) == 0) s = s.substr(9);
  std::string out;  // percent-decoding (a space is %20 in a URI)
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size()) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  while (out.size() > 1 && out.back() == '/') out.pop_back();
  return out;
}

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  std::string s = ss.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// The inputs into the handle: each set motion's value, rate and acceleration; each point load's
// added force or torque (summed per body and slot: the C interface holds one load per slot).
fmi2Status apply_inputs(Instance* c) {
  const auto& model = c->sim->model;
  for (std::size_t i = 0; i < c->vars.size(); ++i) {
    const Variable& v = c->vars[i];
    if (v.kind == Variable::Kind::Motion && v.component == 0 && c->motion_set[v.index]) {
      const std::string& joint = model.joints[model.motions[v.index].joint].name;
      if (ffr_set_motion(c->sim, joint.c_str(), c->inputs[i], c->inputs[i + 1], c->inputs[i + 2]) != FFR_OK)
        return error(c, ffr_last_error());
    }
  }
  if (!c->has_loads) return fmi2OK;
  std::vector<std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>> slots(model.bodies.size());
  std::vector<std::vector<char>> used(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    slots[b].assign(1 + model.bodies[b].nodes.size(), {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
    used[b].assign(slots[b].size(), 0);
  }
  for (std::size_t i = 0; i < c->vars.size(); ++i) {
    const Variable& v = c->vars[i];
    if (v.kind == Variable::Kind::Load) {
      const auto& load = model.loads[v.index];
      const auto s = ffr::fmu::load_slot(model, load);
      auto& fm = slots[s.body][s.slot];
      (load.torque ? fm.second : fm.first)[v.component] += c->inputs[i];
      used[s.body][s.slot] = 1;
    }
  }
  for (std::size_t b = 0; b < slots.size(); ++b)
    for (std::size_t s = 0; s < slots[b].size(); ++s) {
      if (!used[b][s]) continue;
      const char* node = s == 0 ? nullptr : model.bodies[b].nodes[s - 1].name.c_str();
      if (ffr_set_load(c->sim, model.bodies[b].name.c_str(), node, slots[b][s].first.data(),
                       slots[b][s].second.data()) != FFR_OK)
        return error(c, ffr_last_error());
    }
  return fmi2OK;
}

Instance* as(fmi2Component c) { return static_cast<Instance*>(c); }

// The values of a new instance: inputs 0, solver.step the model file's.
void reset_values(Instance* c) {
  std::fill(c->inputs.begin(), c->inputs.end(), 0.0);
  std::fill(c->motion_set.begin(), c->motion_set.end(), 0);
  if (c->step_parameter >= 0) c->inputs[c->step_parameter] = c->sim->model.settings.step;
  c->terminated = false;
  c->initialized = false;
}

// solver.step set to another value than the model file's: the model is opened again from its
// text with that step, so that the run is the one of ffr-sim on the model file holding it
// (the parser checks the step against the output interval and the rest as it does there).
fmi2Status apply_step_parameter(Instance* c) {
  if (c->step_parameter < 0 || c->inputs[c->step_parameter] == c->sim->model.settings.step) return fmi2OK;
  std::string text;
  try {
    std::ifstream f(c->model_path, std::ios::binary);
    nlohmann::json model = nlohmann::json::parse(f);
    model["solver"]["step"] = c->inputs[c->step_parameter];
    text = model.dump();
  } catch (const std::exception& e) {
    return error(c, "fmi2ExitInitializationMode: " + c->model_path + ": " + e.what());
  }
  ffr_sim* sim = nullptr;
  if (ffr_open_json(text.c_str(), c->folder.c_str(), c->model_path.c_str(), &sim) != FFR_OK)
    return error(c, "solver.step = " + std::to_string(c->inputs[c->step_parameter]) + " refused: " + ffr_last_error());
  ffr_close(c->sim);
  c->sim = sim;
  return fmi2OK;
}

}  // namespace

FFR_FMI_EXPORT const char* fmi2GetTypesPlatform(void) { return "default"; }
FFR_FMI_EXPORT const char* fmi2GetVersion(void) { return "2.0"; }

FFR_FMI_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean, size_t, const fmi2String[]) {
  return c ? fmi2OK : fmi2Error;
}

FFR_FMI_EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                                             fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                                             fmi2Boolean, fmi2Boolean) {
  if (!functions || !functions->logger) return nullptr;
  std::unique_ptr<Instance> c;
  try {
    c.reset(new Instance{instanceName ? instanceName : "", *functions, {}, {}, nullptr, {}, {}, {}, {}, false, false, false, -1});
    if (fmuType != fmi2CoSimulation) {
      error(c.get(), "this FMU is for co-simulation only (fmuType fmi2CoSimulation)");
      return nullptr;
    }
    const std::string folder = folder_of(fmuResourceLocation);
    const std::string guid = read_text(folder + "/ffr_guid.txt");
    if (!fmuGUID || guid != fmuGUID) {
      error(c.get(), "the GUID " + std::string(fmuGUID ? fmuGUID : "(null)") + " is not this FMU's (" + guid +
                         " in " + folder + "/ffr_guid.txt): is the resource location " +
                         (fmuResourceLocation ? fmuResourceLocation : "(null)") + " right?");
      return nullptr;
    }
    c->folder = folder;
    c->model_path = folder + "/model.json";
    if (ffr_open(c->model_path.c_str(), &c->sim) != FFR_OK) {
      error(c.get(), ffr_last_error());
      return nullptr;
    }
    c->vars = ffr::fmu::variables(c->sim->model);
    c->inputs.assign(c->vars.size(), 0.0);
    for (std::size_t i = 0; i < c->vars.size(); ++i) {
      c->has_loads = c->has_loads || c->vars[i].kind == Variable::Kind::Load;
      if (c->vars[i].kind == Variable::Kind::Parameter) c->step_parameter = static_cast<int>(i);
    }
    c->motion_set.assign(c->sim->model.motions.size(), 0);
    reset_values(c.get());
    int largest = 1;
    for (const auto& o : c->sim->model.outputs) largest = std::max(largest, o.size);
    c->output_buffer.assign(largest, 0.0);
  } catch (const std::exception& e) {
    error(c.get(), std::string("fmi2Instantiate: ") + e.what());
    return nullptr;
  }
  return c.release();
}

FFR_FMI_EXPORT void fmi2FreeInstance(fmi2Component c) { delete as(c); }

FFR_FMI_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component comp, fmi2Boolean, fmi2Real, fmi2Real startTime,
                                              fmi2Boolean, fmi2Real) {
  Instance* c = as(comp);
  if (!c) return fmi2Error;
  const double t0 = c->sim->model.settings.start;
  if (std::abs(startTime - t0) > 1e-12 * std::max(1.0, std::abs(t0)))
    return error(c, "startTime " + std::to_string(startTime) + " is not the model's start " + std::to_string(t0) +
                        " (solver.start of " + c->model_path + ")");
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) { return c ? fmi2OK : fmi2Error; }
// Inputs set before the end of initialization act from the start time: the initial
// accelerations are made consistent again with them.
FFR_FMI_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component comp) {
  Instance* c = as(comp);
  if (!c) return fmi2Error;
  if (c->initialized) return error(c, "fmi2ExitInitializationMode: the instance is initialized already");
  if (apply_step_parameter(c) != fmi2OK) return fmi2Error;
  c->initialized = true;
  bool any = false;
  for (std::size_t i = 0; i < c->vars.size(); ++i)
    any = any || ((c->vars[i].kind == Variable::Kind::Motion || c->vars[i].kind == Variable::Kind::Load) &&
                  c->inputs[i] != 0.0);
  for (char m : c->motion_set) any = any || m;
  if (!any) return fmi2OK;
  if (apply_inputs(c) != fmi2OK) return fmi2Error;
  if (ffr_reinitialize(c->sim) != FFR_OK) return error(c, ffr_last_error());
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2Terminate(fmi2Component comp) {
  if (!comp) return fmi2Error;
  as(comp)->terminated = true;
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2Reset(fmi2Component comp) {
  Instance* c = as(comp);
  if (!c) return fmi2Error;
  ffr_close(c->sim);
  c->sim = nullptr;
  if (ffr_open(c->model_path.c_str(), &c->sim) != FFR_OK) return error(c, ffr_last_error());
  reset_values(c);
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2GetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                                      fmi2Real value[]) {
  Instance* c = as(comp);
  if (!c || (nvr && (!vr || !value))) return fmi2Error;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= c->vars.size()) return error(c, "fmi2GetReal: no variable of value reference " + std::to_string(vr[i]));
    const Variable& v = c->vars[vr[i]];
    if (v.kind != Variable::Kind::Output) {
      value[i] = c->inputs[vr[i]];
      continue;
    }
    const auto& out = c->sim->model.outputs[v.index];
    if (ffr_get_output(c->sim, out.name.c_str(), c->output_buffer.data(), static_cast<int>(c->output_buffer.size())) !=
        FFR_OK)
      return error(c, ffr_last_error());
    value[i] = c->output_buffer[v.component];
  }
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2SetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                                      const fmi2Real value[]) {
  Instance* c = as(comp);
  if (!c || (nvr && (!vr || !value))) return fmi2Error;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= c->vars.size()) return error(c, "fmi2SetReal: no variable of value reference " + std::to_string(vr[i]));
    const Variable& v = c->vars[vr[i]];
    if (v.kind == Variable::Kind::Output) return error(c, "fmi2SetReal: " + v.name + " is an output");
    if (!std::isfinite(value[i])) return error(c, "fmi2SetReal: " + v.name + " must be finite");
    if (v.kind == Variable::Kind::Parameter && c->initialized)
      return error(c, "fmi2SetReal: " + v.name + " is a fixed parameter: set it before fmi2ExitInitializationMode");
    if (v.kind == Variable::Kind::Parameter && !(value[i] > 0))
      return error(c, "fmi2SetReal: " + v.name + " must be positive, not " + std::to_string(value[i]));
  }
  for (size_t i = 0; i < nvr; ++i) {
    c->inputs[vr[i]] = value[i];
    const Variable& v = c->vars[vr[i]];
    if (v.kind == Variable::Kind::Motion) c->motion_set[v.index] = 1;
  }
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Integer[]) {
  return nvr ? error(as(c), "this FMU has no Integer variables") : fmi2OK;
}
FFR_FMI_EXPORT fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Boolean[]) {
  return nvr ? error(as(c), "this FMU has no Boolean variables") : fmi2OK;
}
FFR_FMI_EXPORT fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2String[]) {
  return nvr ? error(as(c), "this FMU has no String variables") : fmi2OK;
}
FFR_FMI_EXPORT fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Integer[]) {
  return nvr ? error(as(c), "this FMU has no Integer variables") : fmi2OK;
}
FFR_FMI_EXPORT fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Boolean[]) {
  return nvr ? error(as(c), "this FMU has no Boolean variables") : fmi2OK;
}
FFR_FMI_EXPORT fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2String[]) {
  return nvr ? error(as(c), "this FMU has no String variables") : fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate* state) {
  Instance* c = as(comp);
  if (!c || !state) return fmi2Error;
  try {
    auto* s = static_cast<SavedState*>(*state);
    if (!s) s = new SavedState;
    int n = 0;
    ffr_state_size(c->sim, &n);
    s->state.resize(n);
    if (ffr_save_state(c->sim, s->state.data(), n) != FFR_OK) {
      if (!*state) delete s;
      return error(c, ffr_last_error());
    }
    s->inputs = c->inputs;
    s->motion_set = c->motion_set;
    *state = s;
  } catch (const std::bad_alloc&) {
    return error(c, "fmi2GetFMUstate: out of memory");
  }
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate state) {
  Instance* c = as(comp);
  const auto* s = static_cast<const SavedState*>(state);
  if (!c || !s) return fmi2Error;
  if (s->inputs.size() != c->inputs.size() || s->motion_set.size() != c->motion_set.size())
    return error(c, "fmi2SetFMUstate: the state is of another model");
  if (ffr_restore_state(c->sim, s->state.data(), static_cast<int>(s->state.size())) != FFR_OK)
    return error(c, ffr_last_error());
  c->inputs = s->inputs;
  c->motion_set = s->motion_set;
  // Motions no longer set from outside return to their tables (the state before the set).
  for (std::size_t m = 0; m < c->motion_set.size(); ++m)
    if (!c->motion_set[m])
      ffr_release_motion(c->sim, c->sim->model.joints[c->sim->model.motions[m].joint].name.c_str());
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component, fmi2FMUstate* state) {
  if (state) {
    delete static_cast<SavedState*>(*state);
    *state = nullptr;
  }
  return fmi2OK;
}

// Serialized: three counts (int64), then the state and the inputs (doubles), the motion flags.
FFR_FMI_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component comp, fmi2FMUstate state, size_t* size) {
  const auto* s = static_cast<const SavedState*>(state);
  if (!comp || !s || !size) return fmi2Error;
  *size = 3 * sizeof(std::int64_t) + (s->state.size() + s->inputs.size()) * sizeof(double) + s->motion_set.size();
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component comp, fmi2FMUstate state, fmi2Byte out[], size_t size) {
  const auto* s = static_cast<const SavedState*>(state);
  size_t need = 0;
  if (fmi2SerializedFMUstateSize(comp, state, &need) != fmi2OK || !out) return fmi2Error;
  if (size < need) return error(as(comp), "fmi2SerializeFMUstate: needs " + std::to_string(need) + " bytes");
  const std::int64_t counts[3] = {static_cast<std::int64_t>(s->state.size()), static_cast<std::int64_t>(s->inputs.size()),
                                  static_cast<std::int64_t>(s->motion_set.size())};
  char* p = out;
  std::memcpy(p, counts, sizeof counts), p += sizeof counts;
  std::memcpy(p, s->state.data(), s->state.size() * sizeof(double)), p += s->state.size() * sizeof(double);
  std::memcpy(p, s->inputs.data(), s->inputs.size() * sizeof(double)), p += s->inputs.size() * sizeof(double);
  std::memcpy(p, s->motion_set.data(), s->motion_set.size());
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component comp, const fmi2Byte in[], size_t size,
                                                  fmi2FMUstate* state) {
  Instance* c = as(comp);
  if (!c || !in || !state) return fmi2Error;
  std::int64_t counts[3];
  if (size < sizeof counts) return error(c, "fmi2DeSerializeFMUstate: too few bytes");
  std::memcpy(counts, in, sizeof counts);
  int n = 0;
  ffr_state_size(c->sim, &n);
  if (counts[0] != n || counts[1] != static_cast<std::int64_t>(c->inputs.size()) ||
      counts[2] != static_cast<std::int64_t>(c->motion_set.size()) ||
      size != sizeof counts + (counts[0] + counts[1]) * sizeof(double) + static_cast<size_t>(counts[2]))
    return error(c, "fmi2DeSerializeFMUstate: the bytes are not a state of this model");
  auto s = std::make_unique<SavedState>();
  s->state.resize(counts[0]);
  s->inputs.resize(counts[1]);
  s->motion_set.resize(counts[2]);
  const char* p = in + sizeof counts;
  std::memcpy(s->state.data(), p, s->state.size() * sizeof(double)), p += s->state.size() * sizeof(double);
  std::memcpy(s->inputs.data(), p, s->inputs.size() * sizeof(double)), p += s->inputs.size() * sizeof(double);
  std::memcpy(s->motion_set.data(), p, s->motion_set.size());
  fmi2FreeFMUstate(comp, state);
  *state = s.release();
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                                       const fmi2ValueReference[], size_t, const fmi2Real[], fmi2Real[]) {
  return error(as(c), "directional derivatives are not provided (providesDirectionalDerivative is false)");
}

FFR_FMI_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                                                      const fmi2Integer[], const fmi2Real[]) {
  return nvr ? error(as(c), "input derivatives are not used (canInterpolateInputs is false)") : fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                                                       const fmi2Integer[], fmi2Real[]) {
  return nvr ? error(as(c), "output derivatives are not provided (maxOutputDerivativeOrder is 0)") : fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real t, fmi2Real h, fmi2Boolean) {
  Instance* c = as(comp);
  if (!c) return fmi2Error;
  if (c->terminated) return error(c, "fmi2DoStep after fmi2Terminate");
  if (!c->initialized) return error(c, "fmi2DoStep before fmi2ExitInitializationMode");
  double now = 0, step = 0;
  ffr_time(c->sim, &now);
  ffr_step_size(c->sim, &step);
  const double tol = 1e-9 * std::max(step, 1e-3 * std::abs(now));
  if (std::abs(t - now) > tol)
    return error(c, "fmi2DoStep: currentCommunicationPoint " + std::to_string(t) + " is not the FMU's time " +
                        std::to_string(now));
  const double n = std::round(h / step);
  if (!(h > 0) || n < 1 || std::abs(n * step - h) > 1e-9 * h || n > 2e9)
    return error(c, "fmi2DoStep: the communication step " + std::to_string(h) +
                        " s is not a whole number of the model's steps of " + std::to_string(step) +
                        " s (solver.step of " + c->model_path + " or the parameter solver.step): choose a multiple");
  if (apply_inputs(c) != fmi2OK) return fmi2Error;
  if (ffr_step(c->sim, static_cast<int>(n)) != FFR_OK) return error(c, ffr_last_error());
  return fmi2OK;
}

FFR_FMI_EXPORT fmi2Status fmi2CancelStep(fmi2Component c) { return error(as(c), "fmi2DoStep never returns fmi2Pending"); }

FFR_FMI_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return error(as(c), "fmi2GetStatus: no asynchronous steps");
}
FFR_FMI_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Real* value) {
  Instance* c = as(comp);
  if (!c || !value || s != fmi2LastSuccessfulTime) return error(c, "fmi2GetRealStatus: only fmi2LastSuccessfulTime");
  ffr_time(c->sim, value);
  return fmi2OK;
}
FFR_FMI_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return error(as(c), "fmi2GetIntegerStatus: no integer status");
}
FFR_FMI_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Boolean* value) {
  Instance* c = as(comp);
  if (!c || !value || s != fmi2Terminated) return error(c, "fmi2GetBooleanStatus: only fmi2Terminated");
  *value = fmi2False;
  return fmi2OK;
}
FFR_FMI_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return error(as(c), "fmi2GetStringStatus: no string status");
}
