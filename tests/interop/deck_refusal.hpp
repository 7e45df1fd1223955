#pragma once
// The refusal tests of the deck readers: a deck written as `deck_name` with a part file that
// takes its materials from the deck and puts an interface on `group`, reduced by the pipeline.

#include "ffr/formats/h5.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "support.hpp"

#include <string>

namespace ffr::test {

/// The message of the FormatError the pipeline throws on the deck, or "" if it throws none.
inline std::string deck_refusal(const TempDir& dir, const std::string& deck_name, const std::string& deck,
                                const std::string& group) {
  write_text(dir / deck_name, deck);
  write_text(dir / "bad.json", R"({"geometry": ")" + deck_name + R"(", "visual": false,
    "interfaces": [{"name": "i", "group": ")" + group + R"("}],
    "reduction": {"method": "clamped", "interface": "i", "modes": 1}})");
  try {
    (void)preproc::run_pipeline(preproc::load_part(dir / "bad.json"));
  } catch (const formats::FormatError& e) {
    return e.what();
  }
  return "";
}

}  // namespace ffr::test
