// The Abaqus/CalculiX deck reader of ffr-reduce (preproc::detail::read_inp, then
// read_inp_sections, as load_mesh and the part's properties read a deck) on arbitrary bytes. A
// bad deck must come back as a FormatError naming the file; anything else is a finding.
#include "scratch.hpp"

#include "ffr/formats/h5.hpp"
#include "mesh/inp_reader.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ffr::fuzz::write_scratch("input.inp", data, size);
  try {
    ffr::preproc::MeshReport report;
    (void)ffr::preproc::detail::read_inp(path.string(), &report);
    (void)ffr::preproc::detail::read_inp_sections(path.string());
  } catch (const ffr::formats::FormatError&) {
  }
  return 0;
}
