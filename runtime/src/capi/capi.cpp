// The C interface (ffr_runtime.h): a Model and its Data behind an opaque handle; every entry
// point catches everything and turns it into a status and a thread-local message.
#include "ffr_runtime.h"

#include "ffr/runtime/runtime.hpp"
#include "ffr/version.hpp"

#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

#include "sim_handle.hpp"

namespace {

thread_local std::string g_error;

int fail(int status, std::string msg) {
  g_error = std::move(msg);
  return status;
}

template <class F>
int guarded(F&& f) {
  try {
    g_error.clear();
    return f();
  } catch (const ffr::runtime::ModelError& e) {
    return fail(FFR_ERROR_INPUT, e.what());
  } catch (const ffr::runtime::SolverError& e) {
    return fail(FFR_ERROR_SOLVER, e.what());
  } catch (const std::bad_alloc&) {
    return fail(FFR_ERROR_INTERNAL, "out of memory");
  } catch (const std::exception& e) {
    return fail(FFR_ERROR_INTERNAL, e.what());
  } catch (...) {
    return fail(FFR_ERROR_INTERNAL, "unknown failure");
  }
}

bool finite3(const double* v) { return !v || (std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2])); }

int motion_of(const ffr_sim* s, const char* joint) {
  const int j = s->model.find_joint(joint);
  if (j < 0) return -2;
  for (std::size_t m = 0; m < s->model.motions.size(); ++m)
    if (s->model.motions[m].joint == j) return static_cast<int>(m);
  return -1;
}

}  // namespace

namespace {

// The rest of opening, shared by ffr_open and ffr_open_json: state, workspace, step control.
template <class Load>
int open_with(Load&& load, ffr_sim** sim) {
  return guarded([&] {
    auto s = std::make_unique<ffr_sim>();
    s->model = load();
    s->data = std::make_unique<ffr::runtime::Data>(s->model);
    ffr::runtime::initialize(s->model, *s->data);
    s->last = std::make_unique<ffr::runtime::State>(s->model);
    s->scratch = std::make_unique<ffr::runtime::State>(s->model);
    if (s->model.settings.adaptive) s->control = std::make_unique<ffr::runtime::StepControl>(s->model, *s->data);
    *sim = s.release();
    return FFR_OK;
  });
}

// With adaptive steps: the next of the model's output times (the very times ffr-sim's run lands
// on, so that stepping here reproduces its samples bit for bit), then on past the end by whole
// output intervals.
double next_output_time(const ffr::runtime::Model& model, double t) {
  const auto& s = model.settings;
  const std::int64_t k = std::llround((t - s.start) / s.output_interval) + 1;
  return k <= ffr::runtime::output_count(model) ? ffr::runtime::output_time(model, k) : t + s.output_interval;
}

}  // namespace

extern "C" {

const char* ffr_version(void) { return ffr::kVersion; }

const char* ffr_last_error(void) { return g_error.c_str(); }

int ffr_open(const char* path, ffr_sim** sim) {
  if (!sim) return fail(FFR_ERROR_ARGUMENT, "ffr_open: sim is NULL");
  *sim = nullptr;
  if (!path) return fail(FFR_ERROR_ARGUMENT, "ffr_open: model_path is NULL");
  return open_with([&] { return ffr::runtime::load_model(path); }, sim);
}

int ffr_open_json(const char* json_text, const char* base_dir, const char* name, ffr_sim** sim) {
  if (!sim) return fail(FFR_ERROR_ARGUMENT, "ffr_open_json: sim is NULL");
  *sim = nullptr;
  if (!json_text) return fail(FFR_ERROR_ARGUMENT, "ffr_open_json: json_text is NULL");
  const std::string dir = base_dir ? base_dir : ".";
  const std::string shown = name ? name : "<model text>";
  return open_with([&] { return ffr::runtime::parse_model(json_text, dir, shown); }, sim);
}

void ffr_close(ffr_sim* sim) { delete sim; }

int ffr_reinitialize(ffr_sim* sim) {
  if (!sim) return fail(FFR_ERROR_ARGUMENT, "ffr_reinitialize: sim is NULL");
  if (sim->data->stats.steps > 0 || sim->data->state.t != sim->model.settings.start)
    return fail(FFR_ERROR_ARGUMENT, "ffr_reinitialize: only at the start time, before the first step");
  return guarded([&] {
    ffr::runtime::initialize(sim->model, *sim->data);
    if (sim->control) *sim->control = ffr::runtime::StepControl(sim->model, *sim->data);
    return FFR_OK;
  });
}

int ffr_time(const ffr_sim* sim, double* t) {
  if (!sim || !t) return fail(FFR_ERROR_ARGUMENT, "ffr_time: NULL argument");
  *t = sim->data->state.t;
  return FFR_OK;
}

int ffr_step_size(const ffr_sim* sim, double* h) {
  if (!sim || !h) return fail(FFR_ERROR_ARGUMENT, "ffr_step_size: NULL argument");
  *h = sim->model.settings.adaptive ? sim->model.settings.output_interval : sim->model.settings.step;
  return FFR_OK;
}

int ffr_step(ffr_sim* sim, int n) {
  if (!sim) return fail(FFR_ERROR_ARGUMENT, "ffr_step: sim is NULL");
  if (n < 1) return fail(FFR_ERROR_ARGUMENT, "ffr_step: n must be at least 1");
  return guarded([&] {
    auto& d = *sim->data;
    for (int i = 0; i < n; ++i) {
      // Keep the last accepted state if a step fails (sized at open: no allocation).
      ffr::runtime::save_state(d, *sim->last);
      try {
        // (advance_to leaves the last accepted state itself when it gives up.)
        if (sim->control) ffr::runtime::advance_to(sim->model, d, *sim->control, next_output_time(sim->model, d.state.t));
        else ffr::runtime::step(sim->model, d);
      } catch (...) {
        ffr::runtime::restore_state(*sim->last, d);
        throw;
      }
    }
    return FFR_OK;
  });
}

// The run's packed state (step_control.hpp's pack_run: the State, then for adaptive steps the
// controller's next step and whether it has accepted a step).
int ffr_state_size(const ffr_sim* sim, int* size) {
  if (!sim || !size) return fail(FFR_ERROR_ARGUMENT, "ffr_state_size: NULL argument");
  *size = ffr::runtime::packed_run_size(sim->model);
  return FFR_OK;
}

int ffr_save_state(const ffr_sim* sim, double* buffer, int capacity) {
  if (!sim || !buffer) return fail(FFR_ERROR_ARGUMENT, "ffr_save_state: NULL argument");
  const int n = ffr::runtime::packed_run_size(sim->model);
  if (capacity < n)
    return fail(FFR_ERROR_ARGUMENT, "ffr_save_state: the state has " + std::to_string(n) + " values, capacity " + std::to_string(capacity));
  ffr::runtime::pack_run(sim->model, *sim->data, sim->control.get(), *sim->scratch, buffer);
  return FFR_OK;
}

int ffr_restore_state(ffr_sim* sim, const double* buffer, int size) {
  if (!sim || !buffer) return fail(FFR_ERROR_ARGUMENT, "ffr_restore_state: NULL argument");
  ffr::runtime::ResumePoint point;
  try {
    point = ffr::runtime::unpack_run(sim->model, buffer, size, *sim->scratch);
  } catch (const std::invalid_argument& e) {
    return fail(FFR_ERROR_ARGUMENT, std::string("ffr_restore_state: ") + e.what());
  }
  ffr::runtime::restore_state(*sim->scratch, *sim->data);
  if (sim->control) {
    sim->control->h_next = point.h_next;
    sim->control->accepted_any = point.accepted_any;
  }
  return FFR_OK;
}

int ffr_set_load(ffr_sim* sim, const char* body, const char* node, const double force[3], const double torque[3]) {
  if (!sim || !body) return fail(FFR_ERROR_ARGUMENT, "ffr_set_load: NULL argument");
  if (!finite3(force) || !finite3(torque)) return fail(FFR_ERROR_ARGUMENT, "ffr_set_load: force and torque must be finite");
  const int b = sim->model.find_body(body);
  if (b < 0) return fail(FFR_ERROR_NOT_FOUND, std::string("ffr_set_load: no body '") + body + "'");
  int slot = 0;
  if (node) {
    const int p = sim->model.bodies[b].find_node(node);
    if (p < 0) return fail(FFR_ERROR_NOT_FOUND, std::string("ffr_set_load: body '") + body + "' has no node '" + node + "'");
    slot = 1 + p;
  }
  const Eigen::Vector3d f = force ? Eigen::Vector3d(force[0], force[1], force[2]) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d tau = torque ? Eigen::Vector3d(torque[0], torque[1], torque[2]) : Eigen::Vector3d::Zero();
  set_external_load(*sim->data, b, slot, f, tau);
  return FFR_OK;
}

int ffr_clear_loads(ffr_sim* sim) {
  if (!sim) return fail(FFR_ERROR_ARGUMENT, "ffr_clear_loads: sim is NULL");
  clear_external_loads(*sim->data);
  return FFR_OK;
}

int ffr_set_motion(ffr_sim* sim, const char* joint, double value, double rate, double acceleration) {
  if (!sim || !joint) return fail(FFR_ERROR_ARGUMENT, "ffr_set_motion: NULL argument");
  if (!std::isfinite(value) || !std::isfinite(rate) || !std::isfinite(acceleration))
    return fail(FFR_ERROR_ARGUMENT, "ffr_set_motion: values must be finite");
  const int m = motion_of(sim, joint);
  if (m == -2) return fail(FFR_ERROR_NOT_FOUND, std::string("ffr_set_motion: no joint '") + joint + "'");
  if (m < 0) return fail(FFR_ERROR_NOT_FOUND, std::string("ffr_set_motion: joint '") + joint + "' has no motion in the model");
  sim->data->motion_external[m] = 1;
  sim->data->motion_value[m] = Eigen::Vector3d(value, rate, acceleration);
  return FFR_OK;
}

int ffr_release_motion(ffr_sim* sim, const char* joint) {
  if (!sim || !joint) return fail(FFR_ERROR_ARGUMENT, "ffr_release_motion: NULL argument");
  const int m = motion_of(sim, joint);
  if (m < 0) return fail(FFR_ERROR_NOT_FOUND, std::string("ffr_release_motion: no motion on joint '") + joint + "'");
  sim->data->motion_external[m] = 0;
  return FFR_OK;
}

int ffr_output_size(const ffr_sim* sim, const char* output, int* size) {
  if (!sim || !output || !size) return fail(FFR_ERROR_ARGUMENT, "ffr_output_size: NULL argument");
  const int o = sim->model.find_output(output);
  if (o < 0) return fail(FFR_ERROR_NOT_FOUND, std::string("ffr_output_size: no output '") + output + "'");
  *size = sim->model.outputs[o].size;
  return FFR_OK;
}

int ffr_get_output(ffr_sim* sim, const char* output, double* values, int capacity) {
  if (!sim || !output || !values) return fail(FFR_ERROR_ARGUMENT, "ffr_get_output: NULL argument");
  const int o = sim->model.find_output(output);
  if (o < 0) return fail(FFR_ERROR_NOT_FOUND, std::string("ffr_get_output: no output '") + output + "'");
  const auto& out = sim->model.outputs[o];
  if (capacity < out.size)
    return fail(FFR_ERROR_ARGUMENT, "ffr_get_output: output '" + out.name + "' has " + std::to_string(out.size) +
                                        " values, capacity " + std::to_string(capacity));
  return guarded([&] {
    ffr::runtime::evaluate_output(sim->model, *sim->data, out, values);
    return FFR_OK;
  });
}

int ffr_stats(const ffr_sim* sim, long long* steps, long long* iterations) {
  if (!sim) return fail(FFR_ERROR_ARGUMENT, "ffr_stats: sim is NULL");
  if (steps) *steps = sim->data->stats.steps;
  if (iterations) *iterations = sim->data->stats.newton_iterations;
  return FFR_OK;
}

}  // extern "C"
