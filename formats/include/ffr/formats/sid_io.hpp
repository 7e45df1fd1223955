#pragma once
// Reading and writing SID files (layout: formats/SPEC.md).

#include "ffr/formats/h5.hpp"
#include "ffr/formats/sid.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ffr::formats {

/// Reads a SID file strictly: format and version checked, every required dataset present with
/// the right type and shape, every value finite, sizes checked before allocation. Throws
/// FormatError naming the file and the dataset on any problem, including values that differ
/// from the content checksums written with them. Things the caller should show but that do
/// not stop the read (a version 1 file has no content checksums) are appended to `warnings`.
Sid read_sid(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);
/// The same reading from a file opened by the caller (a file image: tools/fuzz's SID target).
Sid read_sid(h5::Reader& reader, std::vector<std::string>* warnings = nullptr);
/// read_sid of the bytes of a SID file held in memory, named `display_name` in messages.
Sid read_sid_image(const void* image, std::size_t size, const std::string& display_name,
                   std::vector<std::string>* warnings = nullptr);

/// The warning for a file of a version without content checksums.
std::string no_checksums_warning(const std::string& file, std::int64_t version);

/// Writes a SID file atomically (temporary name, flush, fsync, rename): on any failure the
/// target is left untouched. Checks the in-memory sizes first (std::invalid_argument).
void write_sid(const Sid& sid, const std::filesystem::path& path);

/// Throws std::invalid_argument if the members' sizes are inconsistent with nq and the nodes.
void check_sizes(const Sid& sid);

}  // namespace ffr::formats
