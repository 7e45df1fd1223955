#pragma once
// ffr-reduce side of the benchmarks: the part files, the stage times it prints on stderr, and
// the frequencies it wrote.

#include "ffr/calculix/deck.hpp"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ffr::bench {

using calculix::IsoMaterial;

/// Part file for the plate: material on "body", the "clamp" face held (rigid interface), clamped modes.
void write_solid_part(const std::filesystem::path& json, const std::filesystem::path& msh, const IsoMaterial& mat,
                      int modes);

/// Part file for the tube: QUAD4 shells on "skin" of the given thickness, the "clamp" ring held.
void write_shell_part(const std::filesystem::path& json, const std::filesystem::path& msh, const IsoMaterial& mat,
                      double thickness, int modes);

/// (stage, seconds) in the order ffr-reduce printed them: every "name: ... [t s]" line, and the
/// "name t s" items of its "timing:" line (the parts of the eigen-solve).
std::vector<std::pair<std::string, double>> read_stage_times(const std::filesystem::path& stderr_file);

/// /refmod/frequency_hz of a SID file.
std::vector<double> read_sid_frequencies(const std::filesystem::path& sid);

/// Largest |a_i / b_i - 1| over the common length (NaN if a or b is empty).
double max_relative_difference(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace ffr::bench
