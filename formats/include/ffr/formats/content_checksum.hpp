#pragma once
// Content checksums of the SID and results files (formats/SPEC.md section 4): a SHA-256 of
// each dataset's values in a canonical byte form, and one over the list of all datasets.
//
// HDF5's own checks do not cover every way a file can be damaged: a damaged key in a chunk
// index (a version-1 B-tree, which has no checksum) makes the library treat the chunk as
// unallocated and return the fill value, so Fletcher-32 never runs. A checksum of the values
// as read closes that gap, whatever the storage layout.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace ffr::formats {

/// Attribute of every dataset of a checksummed file: hex SHA-256 of its canonical content.
inline constexpr const char* kChecksumAttribute = "sha256";
/// Root attribute: hex SHA-256 of the sorted list of (dataset path, dataset checksum).
inline constexpr const char* kManifestAttribute = "content_sha256";

/// Canonical content: the tag "ffr-content-1", the element type ("f64", "i64" or "str"), the
/// rank and each dimension (u64, little-endian), then the values in C order: doubles and
/// integers as their 8 little-endian bytes, a string as its length (u64 LE) and its bytes.
std::string checksum_doubles(const double* values, const std::vector<std::uint64_t>& shape);
std::string checksum_int64(const std::int64_t* values, const std::vector<std::uint64_t>& shape);
std::string checksum_strings(const std::vector<std::string>& values, const std::vector<std::uint64_t>& shape);

/// SHA-256 of "path\0checksum\n" for each (path, checksum), sorted by path.
std::string checksum_manifest(std::vector<std::pair<std::string, std::string>> entries);

}  // namespace ffr::formats
