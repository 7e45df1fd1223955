#pragma once
// A minimal zip archive writer: entries stored uncompressed (method 0, which every unzip
// reads), CRC-32 from zlib; no zip64, so each entry and the archive stay below 4 GiB.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace ffr::fmu {

class ZipWriter {
 public:
  explicit ZipWriter(std::ostream& out) : out_(out) {}
  /// Appends a file entry; throws std::runtime_error if it would pass the 4 GiB limit.
  void add(const std::string& name, const std::string& bytes);
  /// Writes the central directory; the archive is complete after it.
  void finish();

 private:
  struct Entry {
    std::string name;
    std::uint32_t crc, size, offset;
  };
  std::ostream& out_;
  std::vector<Entry> entries_;
  std::uint64_t offset_ = 0;
};

}  // namespace ffr::fmu
