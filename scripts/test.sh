#!/usr/bin/env bash
# The test command (CI runs it through .ci/run). Three stages:
#  1. installs what is missing, builds Release in build/ and runs the whole test suite there;
#  2. with FFR_FUZZ_SECONDS set, a short run of every libFuzzer target (tools/fuzz/README.md);
#  3. builds the test suite again with AddressSanitizer and UndefinedBehaviorSanitizer
#     (cmake -DFFR_SANITIZE=ON, Debug at -O1, benchmarks off) in build-asan/ and runs it there,
#     stopping at the first report (scripts/sanitize/README.md: options, suppressions, subset).
# Arguments go to both ctest runs (e.g. -R formats). FFR_FUZZ_SECONDS=30 runs stage 2,
# FFR_SANITIZE=0 skips stage 3.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=$(nproc)

bash "$here/scripts/setup.sh"
(cd "$here/build" && ctest --output-on-failure -j "$jobs" --timeout 900 "$@")

# ---- fuzzing (tools/fuzz/README.md) ------------------------------------------------------------
# A short run of every libFuzzer target (clang build in build-fuzz/, ASan + UBSan): a crash, a
# sanitizer report or a hang on any input fails the test command. FFR_FUZZ_SECONDS per target
# (e.g. 30). Off by default: the targets have run end to end once, clean, but not yet from a
# fresh clone in CI; the Release suite replays the seeds and regressions through the same entry
# points (ctest -L fuzz).
fuzz_seconds=${FFR_FUZZ_SECONDS:-0}
if [ "$fuzz_seconds" != 0 ]; then
  bash "$here/tools/fuzz/run.sh" --seconds "$fuzz_seconds"
fi
# ---- end of fuzzing ----------------------------------------------------------------------------

[ "${FFR_SANITIZE:-1}" = "0" ] && exit 0

# Every report ends the process with a non-zero status (halt_on_error, no recovery), so a
# finding fails its test; leaks count. The same options hold while building, since
# gtest_discover_tests runs each test binary once to list its tests.
san="$here/scripts/sanitize"
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$san/lsan.supp:print_suppressions=0"

# The pass covers the formats, the runtime and the tools (their tests and the executables they
# start). The reducer (preproc/, its tests) is not in it yet: it has not been run clean under the
# sanitizers (scripts/sanitize/README.md).
cmake -S "$here" -B "$here/build-asan" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_C_FLAGS_DEBUG=-g1 -DCMAKE_CXX_FLAGS_DEBUG=-g1 \
  -DFFR_SANITIZE=ON -DFFR_BUILD_BENCH=OFF -DFFR_BUILD_PREPROC=OFF "-DFFR_TEST_AREAS=formats;runtime" >/dev/null
cmake --build "$here/build-asan" -j "$jobs"
# Left out under the sanitizers: the installed-package check (label install), which compiles
# an outside project against an install of this tree with that project's own flags, so it
# cannot link an instrumented library; the Release pass runs it.
(cd "$here/build-asan" && ctest --output-on-failure -j "$jobs" --timeout 1800 -LE install "$@")
