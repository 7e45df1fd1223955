#pragma once
// Kinematics of bodies and markers from the state in Data (q, qd, qdd).

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

namespace ffr::runtime {

/// Body-frame angular velocity from the frame vectors and their rates: the symmetric form
/// omega = Gbar(A) a_dot with Gbar(A) = 1/2 [[0, w^T, -v^T], [-w^T, 0, u^T], [v^T, -u^T, 0]]
/// (exact on the constraint manifold A^T A = I). The same map gives the angular acceleration
/// from a_ddot because Gbar(a_dot) a_dot = 0.
Vector3d body_omega(const Matrix3d& A, const Matrix3d& Ad);

/// Gbar(A) as a 3 x 9 matrix acting on [u; v; w].
Eigen::Matrix<double, 3, 9> gbar(const Matrix3d& A);

/// Frames, deformed inertia integrals and frame rates of every body (FORMULATION.md 2-3); of an
/// ancf beam whose frame is known (held at rest) md only: its S_a and Jc come from
/// deformed_inertia, which the outputs that read them call.
void update_bodies(const Model& model, Data& data, Scope scope = Scope::All);
/// A flexible body's S_a(y) and Jc(y) (FORMULATION.md 3) into bd (bd.Py is work).
void deformed_inertia(const Body& b, BodyData& bd, const Eigen::Ref<const Eigen::VectorXd>& y);

/// Positions, axes, Jacobians and acceleration biases of every marker. Needs update_bodies.
void update_markers(const Model& model, Data& data, Scope scope = Scope::All);

/// After a change of the velocities only (q unchanged since update_bodies and update_markers):
/// the velocity-dependent parts of bodies (frame rates, angular velocity, PPdm y_dot) and of
/// markers (velocities, acceleration biases), without the Jacobians. The velocity
/// projection's change of q_dot is all the acceleration projection needs redone.
void update_body_rates(const Model& model, Data& data);
void update_marker_rates(const Model& model, Data& data);

/// One marker's kinematics (used for markers and for node loads). Allocation-free if md is sized.
void marker_kinematics(const Model& model, const Marker& marker, const Data& data, MarkerData& md);
/// Its velocity-dependent part alone (velocities and biases), from md's xbar and ebar.
void marker_rates(const Model& model, const Marker& marker, const Data& data, MarkerData& md);

/// Global position of a marker in the model's initial configuration (before any assembly).
Vector3d initial_marker_position(const Model& model, const Marker& marker);
/// Global axis k of a marker in the initial configuration.
Vector3d initial_marker_axis(const Model& model, const Marker& marker, int k);

}  // namespace ffr::runtime
