#pragma once
// The State: what a step reads from the steps before it — the point of the trajectory
// (t, q, q_dot, q_ddot, lambda) and what the scheme and the step's policy need to go on from it
// (the generalized-alpha pseudo-acceleration, the predictor's previous step, Newton's measured
// contraction, the joint angles' unwrapping). Everything else in Data is workspace that a step
// rebuilds before reading it. Saved and restored, a State makes the run continue bit for bit as
// it did from there (tests/runtime/state_test.cpp): what a rejected adaptive step returns to,
// and what the C API's ffr_save_state / ffr_restore_state hold.

#include "ffr/runtime/model.hpp"
#include "ffr/runtime/scheme.hpp"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace ffr::runtime {

struct Data;

/// A friction damper's memory (friction_damper.cpp): the slip of its Jenkins element (with a
/// series spring), the energy it has dissipated since the start, and its power at the last
/// accepted step (for the trapezoidal rule on the regularised damper's dissipation).
struct FrictionState {
  double slip = 0, dissipated = 0, power = 0;
};

struct State {
  /// Sized for the model once (save_state and restore_state then allocate nothing).
  explicit State(const Model& model);

  double t = 0;
  VectorXd q, qd, qdd, lambda;   ///< coordinates, rates, accelerations, multipliers
  // The scheme (scheme.hpp).
  VectorXd a;                    ///< generalized-alpha pseudo-acceleration
  StepCoefficients k;            ///< the last step's coefficients (its size: the predictor's ratio)
  // The step's predictor (ali3p.cpp, predictor.cpp).
  VectorXd qdd_prev;             ///< accelerations at the start of the last step
  bool have_previous = false;    ///< a step has been taken (else the predictor starts afresh)
  std::vector<Vector3d> step_alpha;  ///< per body: angular acceleration at the last step's start
  // The step's policy memory (step_policy.hpp).
  bool predictor_far = false;
  double newton_kappa = std::numeric_limits<double>::infinity();  ///< infinite until first measured
  int kappa_age = 0;
  int last_iterations = 0;       ///< Newton iterations of the last step (reuse_jacobian)
  // Joints: the unwrapped angle of each revolute/cylindrical joint at the last step.
  std::vector<double> angle_ref;
  // Friction dampers: slip, dissipated energy and power, one each.
  std::vector<FrictionState> friction;
};

/// Copies data's state into `state`. Allocation-free.
void save_state(const Data& data, State& state);
/// Makes `state` data's state; the factorised tangent, built at another state, is dropped.
/// Allocation-free.
void restore_state(const State& state, Data& data);

/// The State as a flat array of doubles (the C API's form): its length for the model, and the
/// packing and unpacking. unpack_state throws std::invalid_argument on a wrong length or a
/// non-finite coordinate, leaving `state` unchanged.
int packed_state_size(const Model& model);
void pack_state(const State& state, double* out);
void unpack_state(const Model& model, const double* in, int size, State& state);

}  // namespace ffr::runtime
