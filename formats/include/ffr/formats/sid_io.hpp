#pragma once
// Reading and writing SID files (layout: formats/SPEC.md).

#include "ffr/formats/h5.hpp"
#include "ffr/formats/sid.hpp"

#include <filesystem>

namespace ffr::formats {

/// Reads a SID file strictly: format and version checked, every required dataset present with
/// the right type and shape, every value finite, sizes checked before allocation. Throws
/// FormatError naming the file and the dataset on any problem.
Sid read_sid(const std::filesystem::path& path);

/// Writes a SID file atomically (temporary name, flush, fsync, rename): on any failure the
/// target is left untouched. Checks the in-memory sizes first (std::invalid_argument).
void write_sid(const Sid& sid, const std::filesystem::path& path);

/// Throws std::invalid_argument if the members' sizes are inconsistent with nq and the nodes.
void check_sizes(const Sid& sid);

}  // namespace ffr::formats
