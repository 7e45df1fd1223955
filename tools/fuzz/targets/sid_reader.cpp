// The SID reader (formats::read_sid, what ffr-info, ffr-diff and ffr-sim call) on arbitrary
// bytes, then the identity checks of ffr-info (formats::validate) on what it returns. A bad file
// must come back as a FormatError; anything else (another exception, a crash, a sanitizer
// report, a hang) is a finding.
#include "scratch.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/validate.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ffr::fuzz::write_scratch("input.sid.h5", data, size);
  try {
    const ffr::formats::Sid sid = ffr::formats::read_sid(path);
    (void)ffr::formats::validate(sid);
  } catch (const ffr::formats::FormatError&) {
  }
  return 0;
}
