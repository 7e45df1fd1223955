#pragma once
// Pieces shared by the beam kernel and its resultant / geometric-stiffness functions.

#include "beam_shape.hpp"

#include "ffr/preproc/elements/beam.hpp"

namespace ffr::preproc::beam {

/// Validates the section and the geometry; throws ElementError ("beam LINE2: ...").
void check_input(const Eigen::MatrixX3d& xe, const BeamSection& s);

ShapeParams shape_params(const Eigen::MatrixX3d& xe, const BeamSection& s);

/// 12 x 12 local stiffness (Przemieniecki's closed form with shear flexibility).
Eigen::Matrix<double, 12, 12> local_stiffness(const ShapeParams& p, const BeamSection& s);

/// blockdiag(R, R, R, R): d_local = T d_body.
Eigen::Matrix<double, 12, 12> local_transform(const Eigen::Matrix3d& R);

}  // namespace ffr::preproc::beam
