#pragma once
// Element sections from the part file's properties.
#include "ffr/preproc/elements/beam.hpp"
#include "ffr/preproc/elements/shell.hpp"
#include "ffr/preproc/part/part.hpp"

namespace ffr::preproc::detail {

inline ShellSection shell_section(const ShellProps& s) { return {s.thickness, s.mat}; }

inline BeamSection beam_section(const BeamProps& b) {
  BeamSection s;
  s.A = b.A;
  s.Iy = b.Iy;
  s.Iz = b.Iz;
  s.J = b.J;
  s.ky = b.ky.value_or(0.0);  // none given: shear-rigid (Euler–Bernoulli)
  s.kz = b.kz.value_or(0.0);
  s.y_axis = b.y_axis;
  s.material = b.mat;
  return s;
}

}  // namespace ffr::preproc::detail
