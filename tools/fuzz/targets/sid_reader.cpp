// The SID reader (formats::read_sid, what ffr-info, ffr-diff and ffr-sim call) on arbitrary
// bytes, then the identity checks of ffr-info (formats::validate) on what it returns. A bad file
// must come back as a FormatError; anything else (another exception, a crash, a sanitizer
// report, a hang) is a finding.
//
// The bytes are opened as an HDF5 file image in memory (read_sid_image: HDF5's core driver)
// rather than written to a file and opened by name: the reading after the open is the same
// code, and the file system's part (a file per input, HDF5's small reads through the kernel)
// took most of each execution's time.
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/validate.hpp"

#include <hdf5.h>

#include <cstddef>
#include <cstdint>

// HDF5 keeps freed blocks on free lists of its own, so an input's allocations outnumbered its
// frees and libFuzzer ran a full leak check after nearly every input. Without the lists, and with
// HDF5's garbage collection after each input, every block HDF5 frees goes back to the allocator,
// where AddressSanitizer sees a use after free as it sees ours.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  H5set_free_list_limits(0, 0, 0, 0, 0, 0);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const ffr::formats::Sid sid = ffr::formats::read_sid_image(data, size, "input.sid.h5");
    (void)ffr::formats::validate(sid);
  } catch (const ffr::formats::FormatError&) {
  }
  H5garbage_collect();
  return 0;
}
