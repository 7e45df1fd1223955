#include "ffr/formats/content_checksum.hpp"

#include "ffr/formats/sha256.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace ffr::formats {
namespace {

// Values are hashed in blocks so that the bytes are put in little-endian order whatever the
// host, without a copy of the whole dataset.
class Hasher {
 public:
  Hasher(const char* type, const std::vector<std::uint64_t>& shape) {
    const char tag[] = "ffr-content-1";
    h_.update(tag, sizeof tag);  // with its NUL: the tag ends where the type begins
    h_.update(type, std::strlen(type) + 1);
    u64(shape.size());
    for (auto d : shape) u64(d);
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) buf_[fill_++] = static_cast<std::uint8_t>(v >> (8 * i));
    if (fill_ == buf_.size()) flush();
  }
  void bytes(const std::string& s) {
    flush();
    h_.update(s.data(), s.size());
  }
  std::string hex() {
    flush();
    return h_.hex();
  }

 private:
  void flush() {
    if (fill_) h_.update(buf_.data(), fill_);
    fill_ = 0;
  }
  Sha256 h_;
  std::array<std::uint8_t, 8 * 512> buf_{};
  std::size_t fill_ = 0;
};

std::uint64_t count(const std::vector<std::uint64_t>& shape) {
  std::uint64_t n = 1;
  for (auto d : shape) n *= d;
  return n;
}

}  // namespace

std::string checksum_doubles(const double* values, const std::vector<std::uint64_t>& shape) {
  Hasher h("f64", shape);
  const std::uint64_t n = count(shape);
  for (std::uint64_t i = 0; i < n; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, values + i, 8);
    h.u64(bits);
  }
  return h.hex();
}

std::string checksum_int64(const std::int64_t* values, const std::vector<std::uint64_t>& shape) {
  Hasher h("i64", shape);
  const std::uint64_t n = count(shape);
  for (std::uint64_t i = 0; i < n; ++i) h.u64(static_cast<std::uint64_t>(values[i]));
  return h.hex();
}

std::string checksum_strings(const std::vector<std::string>& values, const std::vector<std::uint64_t>& shape) {
  Hasher h("str", shape);
  for (const auto& s : values) {
    h.u64(s.size());
    h.bytes(s);
  }
  return h.hex();
}

std::string checksum_manifest(std::vector<std::pair<std::string, std::string>> entries) {
  std::sort(entries.begin(), entries.end());
  Sha256 h;
  for (const auto& [path, sum] : entries) {
    h.update(path.data(), path.size());
    h.update("", 1);
    h.update(sum.data(), sum.size());
    h.update("\n", 1);
  }
  return h.hex();
}

}  // namespace ffr::formats
