#!/bin/sh
# Builds and runs the formulation benchmark (main.cpp): per-step time of the relative and the
# absolute formulation on the same models, side by side in one run; the table goes to stdout
# (RESULTS.md holds a measured one). Usage: tools/bench/formulations/run.sh [BUILD_DIR] [--quick]
set -eu
root=$(cd "$(dirname "$0")/../../.." && pwd)
build=${1:-$root/build}
[ $# -gt 0 ] && shift
cmake --build "$build" --target ffr-bench-formulations >/dev/null
exec "$build/bin/ffr-bench-formulations" "$@"
