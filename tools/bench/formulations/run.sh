#!/bin/sh
# Builds and runs the formulation study (main.cpp) as RESULTS.md was made: the chains, the loops,
# the vehicle (prepared here as meshes/vehicle/run.sh does: ffr-reduce, road.py, make_model.py)
# and the meshed rod (TET10 bars up to --max-dof, reduced once and cached in the work folder),
# the tables to stdout, the CSV files and the plot (plot.py, /usr/bin/python3 with matplotlib)
# into OUT. Usage: tools/bench/formulations/run.sh [BUILD_DIR [OUT [MAX_DOF]]]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$build/formulations}
max_dof=${3:-400000}
cmake --build "$build" --target ffr-bench-formulations ffr-reduce >/dev/null
mkdir -p "$out/vehicle"
cp "$root/meshes/vehicle/frame.geo" "$root/meshes/vehicle/frame.json" "$out/vehicle/"
"$build/bin/ffr-reduce" "$out/vehicle/frame.json" -o "$out/vehicle/frame.sid.h5" --quiet
python3 "$root/meshes/vehicle/road.py" 8608 > "$out/vehicle/road.json"
python3 "$root/meshes/vehicle/make_model.py" "$out/vehicle/road.json" 15 > "$out/vehicle/model.json"
bench="$build/bin/ffr-bench-formulations"
"$bench" --part chains --csv "$out/chains.csv"
"$bench" --part loops --csv "$out/loops.csv"
"$bench" --part vehicle --vehicle "$out/vehicle" --csv "$out/vehicle.csv"
"$bench" --part mesh --max-dof "$max_dof" --work "$out/work" --csv "$out/mesh.csv"
/usr/bin/python3 "$here/plot.py" "$out/chains.csv" "$out/mesh.csv" "$out/formulations.png"
