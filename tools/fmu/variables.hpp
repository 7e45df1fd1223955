#pragma once
// The variables of an ffr FMU, derived from the model alone, so that ffr-fmu (which writes them
// into modelDescription.xml) and the FMU's shared object (which serves them) number them alike:
// value reference = position in the list.
//   outputs: every component of every model output: "name" (one component) or "name[i]"
//   inputs:  every motion's joint: "<joint>.value", ".rate", ".acceleration" (the prescribed
//            coordinate from the first time the importer sets one of them, instead of the table);
//            every named point_force / point_torque at a node or a body's frame origin:
//            "<name>[i]", i = 0..2, global components added to its table's value.
//   parameter: "solver.step", the integrator's step (fixed-step models only), settable until
//            fmi2ExitInitializationMode; the instance then runs the model with that step.
#include "ffr/runtime/model.hpp"

#include <string>
#include <vector>

namespace ffr::fmu {

struct Variable {
  enum class Kind { Output, Motion, Load, Parameter };
  std::string name;
  std::string description;
  Kind kind = Kind::Output;
  int index = 0;      ///< the output, motion or point load (0 for the parameter)
  int component = 0;  ///< of the output; 0 value, 1 rate, 2 acceleration of a motion; of the load
};

std::vector<Variable> variables(const runtime::Model& model);

/// A point load's place for the external loads of the C interface: body and slot (0 the
/// frame origin, 1 + p node p), or body -1 if it acts at another point (then not an input).
struct LoadSlot {
  int body = -1;
  int slot = 0;
};
LoadSlot load_slot(const runtime::Model& model, const runtime::PointLoad& load);

}  // namespace ffr::fmu
