// Layout from the ZIP file format specification (PKWARE APPNOTE.TXT, sections 4.3.7 local file
// header, 4.3.12 central directory header, 4.3.16 end of central directory record).
#include "zip_writer.hpp"

#include <zlib.h>

#include <stdexcept>

namespace ffr::fmu {
namespace {

constexpr std::uint64_t kLimit = 0xFFFFFFFFull;
constexpr std::uint16_t kVersion = 20;     // 2.0: the features used here
constexpr std::uint16_t kDosDate = 0x21;   // 1980-01-01: fixed, so equal inputs give equal archives
constexpr std::uint16_t kDosTime = 0;

void put16(std::string& s, std::uint16_t v) {
  s += static_cast<char>(v & 0xFF);
  s += static_cast<char>(v >> 8);
}
void put32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s += static_cast<char>((v >> (8 * i)) & 0xFF);
}

}  // namespace

void ZipWriter::add(const std::string& name, const std::string& bytes) {
  if (bytes.size() > kLimit || offset_ + bytes.size() + name.size() + 30 > kLimit)
    throw std::runtime_error("the archive would pass 4 GiB with " + name + " (zip64 is not written)");
  const auto crc = static_cast<std::uint32_t>(
      crc32_z(crc32_z(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
  std::string h;
  put32(h, 0x04034b50);
  put16(h, kVersion);
  put16(h, 0);  // flags
  put16(h, 0);  // stored
  put16(h, kDosTime);
  put16(h, kDosDate);
  put32(h, crc);
  put32(h, static_cast<std::uint32_t>(bytes.size()));
  put32(h, static_cast<std::uint32_t>(bytes.size()));
  put16(h, static_cast<std::uint16_t>(name.size()));
  put16(h, 0);  // extra field length
  h += name;
  out_.write(h.data(), static_cast<std::streamsize>(h.size()));
  out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  entries_.push_back({name, crc, static_cast<std::uint32_t>(bytes.size()), static_cast<std::uint32_t>(offset_)});
  offset_ += h.size() + bytes.size();
}

void ZipWriter::finish() {
  std::string d;
  for (const auto& e : entries_) {
    put32(d, 0x02014b50);
    put16(d, (3 << 8) | kVersion);  // made by: UNIX
    put16(d, kVersion);
    put16(d, 0);
    put16(d, 0);
    put16(d, kDosTime);
    put16(d, kDosDate);
    put32(d, e.crc);
    put32(d, e.size);
    put32(d, e.size);
    put16(d, static_cast<std::uint16_t>(e.name.size()));
    put16(d, 0);  // extra
    put16(d, 0);  // comment
    put16(d, 0);  // disk
    put16(d, 0);  // internal attributes
    put32(d, 0100644u << 16);  // external: a regular file, rw-r--r--
    put32(d, e.offset);
    d += e.name;
  }
  if (offset_ + d.size() + 22 > kLimit || entries_.size() > 0xFFFF)
    throw std::runtime_error("the archive would pass 4 GiB or 65535 entries (zip64 is not written)");
  std::string end;
  put32(end, 0x06054b50);
  put16(end, 0);
  put16(end, 0);
  put16(end, static_cast<std::uint16_t>(entries_.size()));
  put16(end, static_cast<std::uint16_t>(entries_.size()));
  put32(end, static_cast<std::uint32_t>(d.size()));
  put32(end, static_cast<std::uint32_t>(offset_));
  put16(end, 0);
  out_.write(d.data(), static_cast<std::streamsize>(d.size()));
  out_.write(end.data(), static_cast<std::streamsize>(end.size()));
  out_.flush();
  if (!out_) throw std::runtime_error("writing the archive failed");
}

}  // namespace ffr::fmu
