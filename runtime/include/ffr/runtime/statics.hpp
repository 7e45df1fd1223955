#pragma once
// Static equilibrium (FORMULATION.md section 14): "solver": {"analysis": "static"} and
// "initial_equilibrium": true.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

#include <string>
#include <vector>

namespace ffr::runtime {

/// Moves data's consistent state (after initialize's assembly) to the static equilibrium at
/// data.state.t: Q(q, 0, t) = Phi_q^T lambda, Phi(q, t) = 0 under gravity, the force elements, the
/// loads' values at t and the motions' prescribed coordinates at t, by Newton's method on the
/// augmented Lagrangian. Velocities and accelerations are left zero (the caller makes the
/// state consistent again). Checks that the equilibrium is stable: the stiffness on the motions
/// the constraints leave free (the Lagrangian's Hessian reduced to the null space of Phi_q) must
/// be positive semi-definite; its null directions (neutral motions: a vehicle's rolling on its
/// tyres) are accepted when no force remains along them. Throws SolverError naming what failed
/// and what to try when Newton does not converge, the reduced stiffness is indefinite, or a force
/// drives a neutral motion. Returns a note on what moved, and one naming the neutral motions.
/// Allocates (a set-up step, not a time step).
std::vector<std::string> settle_statically(const Model& model, Data& data);

}  // namespace ffr::runtime
