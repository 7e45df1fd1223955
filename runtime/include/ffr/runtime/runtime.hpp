#pragma once
// ffr::runtime: integrates multibody systems of rigid bodies and reduced flexible bodies (SID
// files) in natural coordinates with preprocessed shape integrals. See runtime/FORMULATION.md.
//
//   Model model = load_model("model.json");   // built once, never changed by the algorithms
//   Data data(model);                           // every buffer, sized once
//   initialize(model, data);                    // consistent initial conditions
//   step(model, data);                          // allocation-free

#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/data.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/energy.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "ffr/runtime/load.hpp"
#include "ffr/runtime/model.hpp"
#include "ffr/runtime/outputs.hpp"
#include "ffr/runtime/relative.hpp"
#include "ffr/runtime/scheme.hpp"
#include "ffr/runtime/state.hpp"
#include "ffr/runtime/statics.hpp"
#include "ffr/runtime/step_control.hpp"

namespace ffr::runtime {
const char* version();
}  // namespace ffr::runtime
