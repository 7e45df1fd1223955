#pragma once
// Synthetic flexible bodies for runtime tests (built with ffr/formats/synthetic.hpp).

#include "ffr/formats/synthetic.hpp"

#include <filesystem>

namespace ffr::runtime::test {

/// A small 3-D body of point masses with rotary inertia, nq smooth but otherwise arbitrary mode
/// shapes (with node rotations), and nodes "A", "B", "C". Everything nonzero, so every term of
/// the formulation is exercised.
formats::Sid lumpy_body(int nq = 3, unsigned seed = 7, bool with_rotations = true);

/// Writes a SID file and returns its path.
std::filesystem::path write_sid_file(const formats::Sid& sid, const std::filesystem::path& path);

}  // namespace ffr::runtime::test
