#pragma once
// Interface couplings and supports as a DOF transformation u_full = T u_ind.
//
// - rigid ("RBE2-like"): every DOF of the group's nodes follows the interface node r:
//   u_j = u_r + theta_r x (x_j - x_r), theta_j = theta_r. The group DOFs are dependent.
// - averaged ("RBE3-like"): r moves with the least-squares rigid fit of the group's
//   translations (equal weights): z_r = [u_r; theta_r] = G^-1 sum_j B_j^T u_j with
//   B_j = [I, -skew(x_j - x_r)], G = sum_j B_j^T B_j. While r is free, r is dependent. When
//   r is held or is a Craig–Bampton boundary, six group DOFs (pivoted QR of the map) become
//   dependent instead, so r's DOFs can be prescribed. That couples the group's DOFs densely
//   (rank 6), so it is limited to groups of moderate size.
// - held: the interface node's six DOFs are zero (with rigid coupling: the whole group).
// Interface groups must be disjoint.

#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/model/sparse.hpp"

#include <vector>

namespace ffr::preproc {

enum class InterfaceState {
  Free,      ///< not held (free-free body, or an interface not used by the reduction)
  Held,      ///< clamped: the interface node does not move
  Boundary,  ///< Craig–Bampton boundary: the interface node's six DOFs are independent
};

struct DofTransform {
  SparseMatrix T;                  ///< num_dofs x num_ind
  std::vector<Index> ind_of_full;  ///< independent index of each full DOF, -1 if dependent or held
  std::vector<Index> full_of_ind;  ///< full DOF of each independent DOF
  bool identity = false;           ///< T = I (no interface, nothing held)
  Index num_ind() const { return static_cast<Index>(full_of_ind.size()); }
};

/// Largest interface group (in DOFs) for which an averaged interface may be held or be a
/// Craig–Bampton boundary (dense rank-6 coupling of its DOFs).
inline constexpr Index kMaxDenseAveragedDofs = 6000;

/// Builds T for the given state of each interface (same order as FeModel::interfaces).
/// Throws formats::FormatError naming the part file for overlapping interface groups,
/// degenerate averaged groups (collinear nodes) or too large dense couplings.
DofTransform build_transform(const FeModel& model, const std::vector<InterfaceState>& state);

/// Rigid-body motions of the independent DOFs (num_ind x 6): translations x, y, z then
/// rotations about the x, y, z axes through the origin, for every independent DOF
/// (translation DOFs get e_a or e_a x x, rotation DOFs get 0 or e_a).
Eigen::MatrixXd rigid_body_modes(const FeModel& model, const DofTransform& t);

}  // namespace ffr::preproc
