#pragma once
// A rigid body hung on one 6-DOF node (Wagner & Pfeiffer, 'On the Dynamics of Washing Machines'): every point P of the body,
// at p_node + e + s (e the offset of its centre of mass, s the position about the centre),
// moves with the node, u_P = u_p + theta_p x (e + s). No stiffness.
//
//   M = [ m 1       -m ẽ        ]
//       [ m ẽ   I_c - m ẽ ẽ     ]     (I_c - m ẽẽ = inertia about the node, parallel axes)
//
// Mass samples: six points s = ± a_k v_k (v_k the principal axes of S = int s s^T dm
// = tr(I_c)/2 1 - I_c, a_k^2 = 3 lambda_k(S) / m), m/6 each; they reproduce m, m (p + e) and
// every second moment exactly, and sum w N^T N = M (M_rotary is empty).

#include "ffr/preproc/elements/element.hpp"

#include <Eigen/Core>

namespace ffr::preproc {

/// Throws ElementError for m <= 0, a non-symmetric inertia, or one that is not the inertia
/// of a physical body (S not positive semi-definite, i.e. the triangle inequalities fail).
ElementMatrices attached_mass(const Eigen::Vector3d& p_node, double mass, const Eigen::Vector3d& com_offset,
                              const Eigen::Matrix3d& inertia_about_com);

}  // namespace ffr::preproc
