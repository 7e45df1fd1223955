#include "ffr/formats/text_file.hpp"

#include "ffr/formats/h5.hpp"  // FormatError

#include <fstream>
#include <sstream>

namespace ffr::formats {

std::string read_text_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FormatError(path.string(), "", "no such file");
  if (std::filesystem::is_directory(path, ec)) throw FormatError(path.string(), "", "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FormatError(path.string(), "", "cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw FormatError(path.string(), "", "read error");
  return ss.str();
}

}  // namespace ffr::formats
