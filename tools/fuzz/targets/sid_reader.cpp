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

// HDF5 keeps its own free lists (left on): HDF5 is not instrumented, so a reuse of its blocks is
// not a finding of ours either way, and with the lists off every HDF5 block went through the
// sanitizer's allocator and quarantine, which took most of an execution's time (about 3x the
// executions a second with them on). Their limits are raised once for the process: by default a
// list keeps at most 64 KiB, less than one block of a file's metadata cache (H5C_t, over
// 512 KiB with its hash table), so every open allocated that block afresh from the system
// (through the sanitizer's allocator: fresh pages, a page fault each) and every close gave it
// back. The limits are a memory policy of the library, not part of reading a file.
// libFuzzer's per-input leak check is off for this target (tools/fuzz/run.sh) because of the
// blocks HDF5 keeps from one file to the next; the replay of the regressions under
// LeakSanitizer (ctest -L fuzz) is the leak check.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool limits_raised = [] {
    constexpr int kGlobal = 64 << 20, kList = 16 << 20;  // bytes
    return H5set_free_list_limits(kGlobal, kList, kGlobal, kList, kGlobal, kList) >= 0;
  }();
  (void)limits_raised;
  try {
    const ffr::formats::Sid sid = ffr::formats::read_sid_image(data, size, "input.sid.h5");
    (void)ffr::formats::validate(sid);
  } catch (const ffr::formats::FormatError&) {
  }
  return 0;
}
