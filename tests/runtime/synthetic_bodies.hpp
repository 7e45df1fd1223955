#pragma once
// Synthetic flexible bodies for runtime tests (built with ffr/formats/synthetic.hpp).

#include "ffr/formats/synthetic.hpp"

#include <filesystem>

namespace ffr::runtime::test {

/// A small 3-D body of point masses with rotary inertia, nq smooth but otherwise arbitrary mode
/// shapes (with node rotations), and nodes "A", "B", "C". Everything nonzero, so every term of
/// the formulation is exercised.
formats::Sid lumpy_body(int nq = 3, unsigned seed = 7, bool with_rotations = true, double damping = 0.02);

/// A free-free body about its mean axes: 3-D point masses with rotary inertia, centre of mass at
/// the frame origin, and nq shapes made mass-orthogonal to the six rigid-body motions, so
/// rdm = 0, Pdm = 0 and Cr.M0 = 0.
formats::Sid mean_axis_body(int nq = 3, unsigned seed = 5);

/// Writes a SID file and returns its path.
std::filesystem::path write_sid_file(const formats::Sid& sid, const std::filesystem::path& path);

}  // namespace ffr::runtime::test
