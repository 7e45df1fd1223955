#include "ffr/formats/text_file.hpp"

#include "ffr/formats/h5.hpp"  // FormatError

#include <fstream>

namespace ffr::formats {

std::string read_text_file(const std::filesystem::path& path, std::size_t max_stream_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw FormatError(path.string(), "", "no such file");
  if (fs::is_directory(st)) throw FormatError(path.string(), "", "is a directory, not a file");
  // A device has no end to wait for (/dev/zero, a terminal): reading it would hang or fill the
  // memory. A pipe ends when its writer closes it, so it is read, but only up to the bound.
  if (fs::is_character_file(st) || fs::is_block_file(st) || fs::is_socket(st))
    throw FormatError(path.string(), "", "is a device or socket, not a file");
  const bool stream = !fs::is_regular_file(st);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FormatError(path.string(), "", "cannot open for reading");
  std::string text;
  if (!stream) {
    const auto size = fs::file_size(path, ec);
    if (!ec) text.reserve(static_cast<std::size_t>(size));
  }
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    const auto n = static_cast<std::size_t>(in.gcount());
    if (stream && text.size() + n > max_stream_bytes)
      throw FormatError(path.string(), "", "a pipe that gives more than " + std::to_string(max_stream_bytes) +
                                               " bytes; give the input as a file");
    text.append(buffer, n);
  }
  if (in.bad()) throw FormatError(path.string(), "", "read error");
  return text;
}

}  // namespace ffr::formats
