#!/usr/bin/env bash
# Installs what is missing, builds Release in build/ and runs the whole test suite.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/setup.sh"
cd "$here/build"
jobs=$(nproc)
ctest --output-on-failure -j "$jobs" --timeout 900 "$@"

# ---- fuzzing (tools/fuzz/README.md) ------------------------------------------------------------
# A short run of every libFuzzer target (clang build in build-fuzz/, ASan + UBSan): a crash, a
# sanitizer report or a hang on any input fails the test command. FFR_FUZZ_SECONDS per target
# (default 30; 0 skips it).
fuzz_seconds=${FFR_FUZZ_SECONDS:-30}
if [ "$fuzz_seconds" != 0 ]; then
  bash "$here/tools/fuzz/run.sh" --seconds "$fuzz_seconds"
fi
# ---- end of fuzzing ----------------------------------------------------------------------------
