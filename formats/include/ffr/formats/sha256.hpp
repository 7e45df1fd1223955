#pragma once
// SHA-256 (FIPS 180-4) for provenance hashes of input files and meshes.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace ffr::formats {

class Sha256 {
 public:
  Sha256();
  void update(const void* data, std::size_t n);
  /// Lower-case hex digest; the object is finished afterwards.
  std::string hex();

 private:
  void block(const std::uint8_t* p);
  std::uint32_t h_[8];
  std::uint8_t buf_[64];
  std::size_t fill_ = 0;
  std::uint64_t bits_ = 0;
};

/// Hex SHA-256 of a file's bytes ("" if it cannot be read).
std::string sha256_file(const std::filesystem::path& path);

}  // namespace ffr::formats
