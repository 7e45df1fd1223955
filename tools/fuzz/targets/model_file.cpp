// The model-file parser of ffr-sim (runtime::load_model: the JSON, every field, the SID files it
// names and the model built from them) on arbitrary bytes. A flexible body's SID named
// "chain.sid.h5" or "rod.sid.h5" exists (a synthetic chain, as ffr-synth writes it), so inputs
// get past the file check. A bad file must come back as a ModelError, as ffr-sim expects (exit
// status 2); anything else is a finding.
#include "chain_sids.hpp"
#include "scratch.hpp"

#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/load.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ffr::fuzz::write_chain_sids();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ffr::fuzz::write_scratch("model.json", data, size);
  try {
    (void)ffr::runtime::load_model(path);
  } catch (const ffr::runtime::ModelError&) {
  }
  return 0;
}
