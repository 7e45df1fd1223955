#!/usr/bin/env bash
# Builds the fuzz targets (clang, libFuzzer, ASan + UBSan) in build-fuzz/ and runs each one.
#   tools/fuzz/run.sh                       every target for 60 s
#   tools/fuzz/run.sh --seconds 600 sid_reader
#   tools/fuzz/run.sh --runs 1000000 part_file    a fixed number of executions instead
# Exit status 1 if any target found a crash, a sanitizer report, a leak, a timeout (10 s on one
# input) or an allocation beyond 2 GB; the input is in build-fuzz/fuzz/crashes/TARGET/ and the
# log in build-fuzz/fuzz/logs/TARGET.log. README.md says how to make it a regression test.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${FFR_FUZZ_BUILD:-$here/build-fuzz}
seconds=60
runs=""
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
    *) targets+=("$1"); shift ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(sid_reader part_file model_file model_run msh_reader inp_reader bdf_reader)

if [ ! -f "$build/CMakeCache.txt" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  # -O1 with assertions (Eigen's bounds checks included): what fuzzing should see.
  cmake -S "$here" -B "$build" -G Ninja -DFFR_FUZZ=ON -DFFR_BUILD_PREPROC=OFF -DFFR_BUILD_TESTS=OFF \
    -DFFR_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1" \
    "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    "${launcher[@]}" >/dev/null
fi
build_targets=(ffr-synth)
for t in "${targets[@]}"; do build_targets+=("fuzz_$t"); done
cmake --build "$build" -j "$(nproc)" --target "${build_targets[@]}"

work=$build/fuzz
# The leaks that are not ours to fix (libhdf5's lost object header on a damaged file) are the
# sanitizer pass's: scripts/sanitize/lsan.supp.
export LSAN_OPTIONS="suppressions=$here/scripts/sanitize/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# Seeds: the repository's examples, and SID files written by ffr-synth (no SID is kept in the
# repository); the corpus each run grows is kept in corpus/TARGET for the next run.
seed() {
  local t=$1
  local dir=$work/seeds/$t
  rm -rf "$dir"
  mkdir -p "$dir" "$work/corpus/$t" "$work/crashes/$t" "$work/logs"
  case $t in
    sid_reader)
      local synth=$build/bin/ffr-synth
      ASAN_OPTIONS=detect_leaks=0 "$synth" --chain --points 5 --modes 2 -o "$dir/free.sid.h5" >/dev/null
      ASAN_OPTIONS=detect_leaks=0 "$synth" --chain --points 8 --modes 3 --clamped --stiffening --damping 0.02 \
        -o "$dir/clamped.sid.h5" >/dev/null
      ;;
    part_file)
      find "$here/meshes" -name '*.json' ! -path '*/models/*' -exec cp {} "$dir/" \; ;;
    model_file)
      cp "$here"/meshes/models/*.json "$dir/" ;;
    model_run)
      cp "$here"/meshes/models/*.json "$here"/tools/fuzz/models/*.json "$dir/" ;;
    msh_reader)
      cp "$here"/tests/solid_elements/data/*.msh "$dir/" ;;
    inp_reader)
      cp "$here"/meshes/*/*.inp "$here"/tools/fuzz/decks/*.inp "$dir/" ;;
    bdf_reader)
      cp "$here"/meshes/*/*.bdf "$here"/tools/fuzz/decks/*.bdf "$dir/" ;;
  esac
  cp "$here/tools/fuzz/regressions/$t/"* "$dir/" 2>/dev/null || true
  rm -f "$dir/README.md"
}
dict_of() {
  case $1 in
    part_file|model_file|model_run) echo "-dict=$here/tools/fuzz/dicts/json.dict" ;;
    msh_reader) echo "-dict=$here/tools/fuzz/dicts/msh.dict" ;;
    sid_reader) echo "-dict=$here/tools/fuzz/dicts/sid.dict" ;;
    inp_reader|bdf_reader) echo "-dict=$here/tools/fuzz/dicts/deck.dict" ;;
  esac
}

# libFuzzer checks for a leak after every input whose allocations outnumber its frees. HDF5
# keeps blocks from one file open to the next (caches, error records), so for the SID target that
# check ran after nearly every input (4 executions a second instead of hundreds). It is off for
# that target; the sanitizer pass of scripts/test.sh replays its regressions under LeakSanitizer
# (ctest -L fuzz).
extra_of() {
  case $1 in
    sid_reader) echo "-detect_leaks=0" ;;
  esac
}
# For the SID target, whose executions are mostly HDF5's allocations through the sanitizer's
# allocator: no stack trace recorded with each allocation (malloc_context_size=0). It changes
# what a report shows (no allocation and free stacks), not what is detected; a finding is run
# again with the defaults for the full report (README.md).
asan_of() {
  case $1 in
    sid_reader) echo "${ASAN_OPTIONS:+$ASAN_OPTIONS:}malloc_context_size=0" ;;
    *) echo "${ASAN_OPTIONS:-}" ;;
  esac
}

failed=()
for t in "${targets[@]}"; do
  seed "$t"
  limit=(-max_total_time="$seconds")
  [ -n "$runs" ] && limit=(-runs="$runs")
  echo "fuzz: $t (${runs:+$runs runs}${runs:-$seconds s})"
  set +e
  ASAN_OPTIONS=$(asan_of "$t") "$build/bin/fuzz_$t" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/crashes/$t/" "$(dict_of "$t")" $(extra_of "$t") "$work/corpus/$t" "$work/seeds/$t" \
    >"$work/logs/$t.log" 2>&1
  rc=$?
  set -e
  grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec' "$work/logs/$t.log" | sed "s/^/fuzz: $t: /" || true
  if [ $rc -ne 0 ]; then
    failed+=("$t")
    echo "fuzz: $t FAILED (status $rc); the input: $(ls -t "$work/crashes/$t/" | head -n1); log: $work/logs/$t.log"
    grep -E 'ERROR|SUMMARY|terminate|what\(\)' "$work/logs/$t.log" | head -n 5 || true
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: failed: ${failed[*]}"
  exit 1
fi
echo "fuzz: no crash in ${targets[*]}"
