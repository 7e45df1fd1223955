// The MSH 4.1 reader of ffr-reduce (preproc::detail::read_msh41, which reads ASCII MSH 4.1
// without gmsh and leaves every other file to gmsh) on arbitrary bytes. A bad file must come
// back as a FormatError or as "leave it to gmsh" (no mesh); anything else is a finding.
#include "scratch.hpp"

#include "ffr/formats/h5.hpp"
#include "mesh/msh41_reader.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ffr::fuzz::write_scratch("input.msh", data, size);
  try {
    ffr::preproc::MeshReport report;
    (void)ffr::preproc::detail::read_msh41(path.string(), &report);
  } catch (const ffr::formats::FormatError&) {
  }
  return 0;
}
