// The Nastran bulk-data reader of ffr-reduce (preproc::detail::read_bdf, read_bdf_sections and
// read_bdf_point_masses, as load_mesh, the part's properties and its point masses read a deck)
// on arbitrary bytes. A bad deck must come back as a FormatError naming the file; anything else
// is a finding.
#include "scratch.hpp"

#include "ffr/formats/h5.hpp"
#include "mesh/bdf_reader.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ffr::fuzz::write_scratch("input.bdf", data, size);
  try {
    ffr::preproc::MeshReport report;
    (void)ffr::preproc::detail::read_bdf(path.string(), &report);
    (void)ffr::preproc::detail::read_bdf_sections(path.string());
    (void)ffr::preproc::detail::read_bdf_point_masses(path.string());
  } catch (const ffr::formats::FormatError&) {
  }
  return 0;
}
