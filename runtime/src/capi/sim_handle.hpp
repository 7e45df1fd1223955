#pragma once
// What an ffr_sim handle of the C interface (ffr_runtime.h) holds. Private to the project: the
// C interface's own source and the bindings built with it (the Python package's run(), which
// records like ffr-sim's time loop) read it; installed programs see only the opaque handle.
#include "ffr_runtime.h"

#include "ffr/runtime/runtime.hpp"

#include <memory>

struct ffr_sim {
  ffr::runtime::Model model;
  std::unique_ptr<ffr::runtime::Data> data;
  std::unique_ptr<ffr::runtime::State> last;  ///< the last accepted state, restored if a step fails
  std::unique_ptr<ffr::runtime::State> scratch;  ///< ffr_save_state / ffr_restore_state's copy
  /// "step": "auto": one ffr_step is one output interval of adaptive steps (step_control.hpp).
  std::unique_ptr<ffr::runtime::StepControl> control;
};
