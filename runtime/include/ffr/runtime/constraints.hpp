#pragma once
// Constraint equations Phi(q, t) = 0 and their derivatives (FORMULATION.md section 5):
//  - per body, the six rigid-body conditions of its frame vectors (unit, orthogonal),
//  - per joint, conditions on its two markers (points coincide, axes perpendicular, ...),
//  - per motion, joint coordinate minus the prescribed value.
// Rows without a length unit are multiplied by the model length so every row is a length.
// The Jacobian is data.Phiq (dense, each block writing its bodies' columns); gamma is the acceleration bias
// (Phi_dd = Phi_q q_dd + gamma) including the prescribed accelerations.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

namespace ffr::runtime {

/// Phi, Phit, gamma and the Jacobian blocks at time t. Needs update_bodies and update_markers.
/// Scope::Unknowns: the rows of the unknowns alone (the first data.na); the others, among the
/// ground and driven bodies, keep their values (see Scope).
void evaluate_constraints(const Model& model, Data& data, double t, Scope scope = Scope::All);

/// Phi, Phit and gamma only, the Jacobian left as it is: for a change of the velocities at the
/// same q (needs update_body_rates and update_marker_rates). Only the rows of the unknowns
/// (the first data.na) are redone; the rows among driven bodies keep their last values.
void evaluate_constraint_biases(const Model& model, Data& data, double t);

/// out += Phi_q^T lam.
void add_constraint_forces(const Model& model, const Data& data, const VectorXd& lam, VectorXd& out);

/// out = Phi_q v.
void constraint_times(const Model& model, const Data& data, const VectorXd& v, VectorXd& out);

/// T += factor * Phi_q^T diag(alpha) Phi_q, assembled from the blocks.
void add_penalty_tangent(const Model& model, Data& data, const VectorXd& alpha, double factor, MatrixXd& T);

/// Penalty of each constraint row: factor times the mean body mass (W is the metric the rows act
/// against, kept for per-row schemes).
void penalty_weights(const Model& model, const Data& data, const MatrixXd& W, double factor, VectorXd& alpha);

/// M += factor * sum_i lam_i d2Phi_i/dq2 (the constraints' second derivatives; Newton tangent).
void add_constraint_hessian(const Model& model, Data& data, const VectorXd& lam, double factor, MatrixXd& M);

/// A joint's coordinate in the current state (angle unwrapped around data.state.angle_ref).
double joint_coordinate(const Model& model, const Data& data, int joint, JointCoordinate c);
/// Its rate in the current state (needs the markers' velocities, update_markers).
double joint_coordinate_rate(const Model& model, const Data& data, int joint, JointCoordinate c);

/// Records the current joint angles as the unwrapping references (after each accepted step).
void update_angle_references(const Model& model, Data& data);

/// Prescribed value, rate and acceleration of a motion at time t (table or external input).
Vector3d motion_target(const Model& model, const Data& data, int motion, double t);

}  // namespace ffr::runtime
