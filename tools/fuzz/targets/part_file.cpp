// The part-file parser of ffr-reduce (preproc::load_part) on arbitrary bytes. The parser first
// checks that the geometry file exists; so that inputs get past that check, an empty file of the
// name the input gives (a plain file name) is put next to it. A bad file must come back as a
// FormatError; anything else is a finding.
#include "scratch.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/preproc/part/part.hpp"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <fstream>

namespace {

// The geometry named by the input if it is a plain file name ("" otherwise).
std::string geometry_name(const std::uint8_t* data, std::size_t size) {
  const auto j = nlohmann::json::parse(data, data + size, nullptr, false);
  if (!j.is_object() || !j.contains("geometry") || !j["geometry"].is_string()) return "";
  const std::string g = j["geometry"].get<std::string>();
  if (g.empty() || g.size() > 64 || g == "." || g == "..") return "";
  for (char c : g)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-')) return "";
  return g;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string geometry = geometry_name(data, size);
  const auto dir = ffr::fuzz::scratch();
  if (!geometry.empty() && geometry != "part.json") std::ofstream(dir / geometry).close();
  const auto path = ffr::fuzz::write_scratch("part.json", data, size);
  try {
    (void)ffr::preproc::load_part(path);
  } catch (const ffr::formats::FormatError&) {
  }
  if (!geometry.empty() && geometry != "part.json") {
    std::error_code ec;
    std::filesystem::remove(dir / geometry, ec);
  }
  return 0;
}
