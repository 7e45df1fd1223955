#pragma once
// Mass samples and rotary mass of a flat shell facet (see shell.hpp for the model).

#include "shell_frame.hpp"

#include "ffr/preproc/elements/element.hpp"
#include "ffr/preproc/elements/shell.hpp"

namespace ffr::preproc::shell {

/// Fills out.samples, out.M_rotary and out.M (= sum w N^T N + M_rotary).
void shell_mass(ElementType type, const Eigen::MatrixX3d& xe, const ShellFrame& frame, const ShellSection& s,
                ElementMatrices& out);

}  // namespace ffr::preproc::shell
