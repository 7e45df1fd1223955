#pragma once
// A whole text file in memory (a user's JSON input, a reference code's output), with the refusals
// every reader of user files needs named once.

#include <cstddef>
#include <filesystem>
#include <string>

namespace ffr::formats {

/// The most bytes read from a pipe (a regular file is read whole: its size is known).
inline constexpr std::size_t kMaxStreamBytes = std::size_t{1} << 30;

/// The file's bytes. FormatError naming the file if it does not exist, is a directory, a device
/// or a socket (reading /dev/zero would never end), cannot be read, or is a pipe that gives more
/// than `max_stream_bytes`.
std::string read_text_file(const std::filesystem::path& path, std::size_t max_stream_bytes = kMaxStreamBytes);

}  // namespace ffr::formats
