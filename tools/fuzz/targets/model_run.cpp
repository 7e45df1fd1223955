// The model-file parser and the time loop of ffr-sim on arbitrary bytes: runtime::load_model,
// then a short run as ffr-sim makes it (initialize, which settles a static equilibrium where the
// model asks for one, then simulate) over at most kSteps steps. The model file's own step and
// solver settings are kept; only its end time is brought forward. A bad file must come back as
// a ModelError and a run that cannot go on as a SolverError (ffr-sim's exit status 2 and 1);
// anything else (a crash, a sanitizer report, another exception, a hang) is a finding. As for
// model_file, SID files "chain.sid.h5" (clamped, stiffening) and "rod.sid.h5" (free) exist.
#include "chain_sids.hpp"
#include "scratch.hpp"

#include "ffr/runtime/runtime.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace {
constexpr double kSteps = 20;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ffr::fuzz::write_chain_sids();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ffr::runtime;
  const auto path = ffr::fuzz::write_scratch("model.json", data, size);
  Model model;
  try {
    model = load_model(path);
  } catch (const ModelError&) {
    return 0;
  }
  SolverSettings& s = model.settings;
  const double span = kSteps * (s.adaptive ? std::max(s.step, s.output_interval) : s.step);
  s.end = std::min(s.end, s.start + span);
  try {
    Data d(model);
    (void)initialize(model, d);
    Recorder rec(model, step_count(model) / std::max(1, s.output_every) + 2);
    (void)simulate(model, d, rec);
  } catch (const ModelError&) {
  } catch (const SolverError&) {
  }
  return 0;
}
