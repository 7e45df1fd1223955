// What a Newton failure of a step suggests trying (both formulations' steps), leaving out what a
// setting already at its bound could not give.
#pragma once

#include "ffr/runtime/model.hpp"
#include "../number_text.hpp"

#include <string>

namespace ffr::runtime::detail {

// "Try a smaller step (solver.step = h/2)", then a larger newton_tolerance where it lies below
// round-off and more iterations where max_iterations is below its bound.
inline std::string newton_remedies(const SolverSettings& s, double h) {
  std::string out = "Try a smaller step (" + std::string(s.adaptive ? "solver.max_step = " : "solver.step = ") + fmt(0.5 * h) + ")";
  if (s.newton_tolerance < kRoundOffTolerance)
    out += ", a newton_tolerance of at least " + fmt(kRoundOffTolerance) + " (" + fmt(s.newton_tolerance) +
           " is below what the coordinates' rounding resolves)";
  if (s.max_iterations < kMaxNewtonIterations) out += ", more iterations (solver.max_iterations)";
  return out;
}

}  // namespace ffr::runtime::detail
