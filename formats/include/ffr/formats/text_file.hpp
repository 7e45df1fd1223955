#pragma once
// A whole text file in memory (a user's JSON input, a reference code's output), with the refusals
// every reader of user files needs named once.

#include <filesystem>
#include <string>

namespace ffr::formats {

/// The file's bytes. FormatError naming the file if it does not exist, is a directory, or
/// cannot be read.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace ffr::formats
