#!/usr/bin/env bash
# Real-time factor of the examples (the precision chamber; the washing machine's 10 s spin-up; the vehicle's 15 s drive):
# simulated machine time over the wall time of ffr-sim's time loop (its integration_seconds: no
# loading, no writing), on one core, best of N runs, with the model's size. Each example's run.sh
# is run once first (it reduces its parts and writes its model); then ffr-sim is timed on that
# model.
# Usage: tools/bench/examples/run.sh [RUNS]   (default 5); binaries from build/bin or $FFR_BIN.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../../.." && pwd)
bin=${FFR_BIN:-$root/build/bin}
runs=${1:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# One core: the time loop is single-threaded (no BLAS threads, no OpenMP in the runtime). Not
# pinned: on a shared machine a pinned run waits whenever that core is busy.

bench() {  # NAME DIR END: times DIR/model.json, prints one line of the table
  local name=$1 dir=$2 end=$3 times=()
  for _ in $(seq "$runs"); do
    # ffr-sim's summary line: "N steps, M Newton iterations, F tangents, V solves, S s integration (U us per step)".
    times+=("$("$bin/ffr-sim" "$dir/model.json" -o "$dir/bench.h5" 2>&1 | grep ' s integration' | tail -1)")
  done
  local modes=()
  for sid in "$dir"/*.sid.h5; do modes+=("$(basename "$sid")=$("$bin/ffr-info" "$sid" | awk '$1 == "modes" {print $2}')"); done
  printf '%s\n' "${times[@]}" | python3 "$here/summarize.py" "$name" "$end" "$dir/model.json" "${modes[@]}"
}

FFR_BIN=$bin bash "$root/meshes/precision_chamber/run.sh" "$work/precision_chamber" 2.0 > /dev/null
bench precision_chamber "$work/precision_chamber" 2.0
FFR_BIN=$bin bash "$root/meshes/washing_machine/run.sh" "$work/washing_machine" 10.0 > /dev/null
bench washing_machine "$work/washing_machine" 10.0
FFR_BIN=$bin bash "$root/meshes/vehicle/run.sh" "$work/vehicle" 15.0 > /dev/null
bench vehicle "$work/vehicle" 15.0
