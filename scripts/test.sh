#!/usr/bin/env bash
# The test command (CI runs it through .ci/run). Three stages:
#  1. installs what is missing, builds Release in build/ and runs the whole test suite there;
#  2. a short run of every libFuzzer target, 20 s each (tools/fuzz/README.md);
#  3. builds the test suite again with AddressSanitizer and UndefinedBehaviorSanitizer
#     (cmake -DFFR_SANITIZE=ON, Debug at -O1, benchmarks off) in build-asan/ and runs it there,
#     stopping at the first report (scripts/sanitize/README.md: options, suppressions, subset).
# Arguments go to both ctest runs (e.g. -R formats). FFR_FUZZ_SECONDS=N gives each target N
# seconds in stage 2 (0 skips it), FFR_SANITIZE=0 skips stage 3.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=$(nproc)

bash "$here/scripts/setup.sh"
(cd "$here/build" && ctest --output-on-failure -j "$jobs" --timeout 900 "$@")

# ---- fuzzing (tools/fuzz/README.md) ------------------------------------------------------------
# A short run of every libFuzzer target (clang build in build-fuzz/ of the targets and what they
# link only, ASan + UBSan): a crash, a sanitizer report, a leak or a hang on any input fails the
# test command, with the input kept in build-fuzz/fuzz/crashes/TARGET/. FFR_FUZZ_SECONDS per
# target, 20 unless set (a smoke run: each target's corpus and regressions are also replayed by
# the suite's fuzz area); 0 skips the stage.
fuzz_seconds=${FFR_FUZZ_SECONDS:-20}
if [ "$fuzz_seconds" != 0 ]; then
  nice bash "$here/tools/fuzz/run.sh" --seconds "$fuzz_seconds"
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
# The damaged-SID corpus (tests/formats/damaged_corpus_test.cpp) at half its runs: each starts
# three instrumented programs, and the fuzz stage's sid_reader target covers the same reader.
export FFR_DAMAGED_CORPUS=thin

# The pass covers the formats, the runtime and the reducer: their libraries, the tools the tests
# start (ffr-reduce, ffr-sim, ffr-info, ffr-diff, ffr-synth) and the test areas chosen by what
# they exercise: formats, runtime; reduce (both factorization backends on solid, shell and beam
# parts, clamped, free and Craig-Bampton; the command line's refusals; meshing through the gmsh
# child), solver (block Lanczos, Spectra, ARPACK, dense; the factorizations), stiffening, fuzz
# (the fuzz targets' regressions and examples replayed). The
# element areas (shells, beams, solid_elements) run their kernels through the reduce area's
# parts; the tests labelled slow run only in the Release pass (scripts/sanitize/README.md).
cmake -S "$here" -B "$here/build-asan" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_C_FLAGS_DEBUG=-g1 -DCMAKE_CXX_FLAGS_DEBUG=-g1 \
  -DFFR_SANITIZE=ON -DFFR_BUILD_BENCH=OFF -DFFR_BUILD_PREPROC=ON \
  "-DFFR_TEST_AREAS=formats;runtime;reduce;solver;stiffening;fuzz" >/dev/null
cmake --build "$here/build-asan" -j "$jobs"
# Left out under the sanitizers: the installed-package check (label install), which compiles
# an outside project against an install of this tree with that project's own flags, so it
# cannot link an instrumented library; and the tests labelled slow. The Release pass runs both.
(cd "$here/build-asan" && ctest --output-on-failure -j "$jobs" --timeout 1800 -LE "install|slow" "$@")
