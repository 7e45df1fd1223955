#!/usr/bin/env bash
# The build's cost with and without precompiled headers (FFR_PCH): configures the tree from
# scratch under OUT_DIR once per FFR_PCH value, builds each, one after the other, with JOBS jobs,
# and prints each build's wall time and its step times by layer (the sum of ninja's per-step
# times in .ninja_log, job-seconds: CPU-bound steps' CPU seconds while JOBS does not exceed the
# free cores).
# Usage: tools/bench/compile/run.sh [OUT_DIR [JOBS [CONFIG [PCH...]]]]
#   CONFIG: release (the set-up script's build) or asan (the test command's sanitizer build);
#   PCH: the FFR_PCH values to build, OFF ON unless given. Defaults: build-bench, nproc, release.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
out=${1:-$here/build-bench}
jobs=${2:-$(nproc)}
config=${3:-release}
shift $(( $# < 3 ? $# : 3 ))
values=("$@")
[ ${#values[@]} -gt 0 ] || values=(OFF ON)
case $config in
  release) flags=(-DCMAKE_BUILD_TYPE=Release) ;;
  asan) flags=(-DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG=-g1 -DCMAKE_CXX_FLAGS_DEBUG=-g1
               -DFFR_SANITIZE=ON -DFFR_BUILD_BENCH=OFF -DFFR_BUILD_PREPROC=ON
               "-DFFR_TEST_AREAS=formats;runtime;reduce;solver;stiffening;fuzz") ;;  # scripts/test.sh
  *) echo "run.sh: CONFIG is release or asan, not '$config'" >&2; exit 2 ;;
esac
mkdir -p "$out"
for pch in "${values[@]}"; do
  dir=$out/${config}_pch_$pch
  rm -rf "$dir"
  cmake -S "$here" -B "$dir" -G Ninja "${flags[@]}" -DFFR_PCH="$pch" >/dev/null
  start=$(date +%s.%N)
  cmake --build "$dir" -j "$jobs" >"$dir.log" 2>&1 || { echo "build with FFR_PCH=$pch failed: $dir.log" >&2; exit 1; }
  end=$(date +%s.%N)
  # .ninja_log: start and end (ms), mtime, output, command hash; a step with several outputs (a
  # test's link, which also writes its list of tests) has one line per output, counted once.
  # Steps are grouped by the output's top folder; everything under tests/ is "tests", links and
  # archives are "link".
  awk -v name="$config FFR_PCH=$pch" -v start="$start" -v end="$end" 'NR > 1 {
      if (seen[$1 " " $2 " " $5]++) next
      d = ($2 - $1) / 1000; total += d
      split($4, part, "/"); layer = part[1]
      if ($4 !~ /\.(o|gch)$/) layer = "link"; else if ($4 ~ /^tests\//) layer = "tests"
      sum[layer] += d
    } END {
      printf "%s: wall %.0f s, %.0f job-s:", name, end - start, total
      n = split("tests preproc runtime tools formats python link", order, " ")
      for (i = 1; i <= n; ++i) printf " %s %.0f", order[i], sum[order[i]]
      printf "\n"
    }' "$dir/.ninja_log"
done
