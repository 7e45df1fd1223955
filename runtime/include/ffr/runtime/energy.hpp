#pragma once
// Energy and momenta of the whole system from the reduced quantities (FORMULATION.md 11).

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

namespace ffr::runtime {

struct Energy {
  double kinetic = 0, potential = 0;
  /// Energy the friction dampers have dissipated since the start (not part of the total: with
  /// conservative loads, total + dissipated is what stays constant).
  double dissipated = 0;
  double total() const { return kinetic + potential; }
};

/// Kinetic energy 1/2 q_d^T M q_d and potential energy of gravity, modal elasticity, springs,
/// bushings and the series springs of friction dampers (table loads and external inputs are not conservative and have none). Updates the
/// body kinematics and mass matrices in data.
Energy energy(const Model& model, Data& data);

/// Linear momentum int r_dot dm = sum m r0_dot + A_dot md + A Pdm y_dot.
Vector3d linear_momentum(const Model& model, Data& data);

/// Angular momentum about the global origin, from the invariants:
/// sum m r0 x r0_dot + r0 x (A_dot md + A Pdm y_dot) + (A md) x r0_dot
///     + sum_ab Jc_ab A_a x A_dot_b + sum_a A_a x (A S_a y_dot) + A PsiI^T y_dot.
Vector3d angular_momentum(const Model& model, Data& data);

}  // namespace ffr::runtime
