#!/usr/bin/env bash
# The vehicle: reduce the elastic ladder frame (ffr-reduce), write an ISO 8608 class C road
# (road.py, fixed seed) and the model (make_model.py), settle the vehicle statically on the road's
# flat start, drive it up to 10 m/s and over 100 m of the rough road (ffr-sim), in the absolute and
# again in the relative formulation, plot the cab's vertical acceleration and the frame's twist
# (plot.py, SVG), check each run (check.py) and the two against each other (compare.py).
# Usage: run.sh [OUT_DIR [END_TIME]]   defaults: ./out and 15 s (at rest to 0.5 s, up to speed at
# 4.5 s, the wheels on the rough section from 4.8 s to 15 s); the test runs 6 s (at rest, speeding up, 1 s at speed).
# The binaries come from build/bin, or from $FFR_BIN.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bin=${FFR_BIN:-$here/../../build/bin}
out=${1:-$here/out}
end=${2:-15.0}
mkdir -p "$out"
cp "$here/frame.geo" "$here/frame.json" "$out/"
echo "== reduce the ladder frame: steel channel rails and tube cross members (beams), free modes up to 80 Hz (6)"
"$bin/ffr-reduce" "$out/frame.json" -o "$out/frame.sid.h5" --quiet
echo "== the road: ISO 8608 class C, seed 8608"
python3 "$here/road.py" 8608 > "$out/road.json"
python3 "$here/make_model.py" "$out/road.json" "$end" > "$out/model.json"
echo "== simulate ${end} s (absolute formulation): settle at rest, speed up to 10 m/s, 100 m of rough road"
"$bin/ffr-sim" "$out/model.json" -o "$out/vehicle.h5" --csv "$out/vehicle.csv" --quiet
echo "== simulate ${end} s again in the relative formulation (the wheels' spin as joint angles)"
python3 -c 'import json, sys; m = json.load(open(sys.argv[1])); m["solver"]["formulation"] = "relative"; json.dump(m, open(sys.argv[2], "w"), indent=1)' \
  "$out/model.json" "$out/model_relative.json"
"$bin/ffr-sim" "$out/model_relative.json" -o "$out/vehicle_relative.h5" --csv "$out/vehicle_relative.csv" --quiet
echo "== plot the cab's vertical acceleration and the frame's twist"
python3 "$here/plot.py" "$out/vehicle.csv" "$out" "$out/vehicle_relative.csv"
python3 "$here/check.py" "$out/vehicle.csv" "$out/model.json" "$end"
python3 "$here/check.py" "$out/vehicle_relative.csv" "$out/model_relative.json" "$end"
python3 "$here/compare.py" "$out/vehicle.csv" "$out/vehicle_relative.csv" 4.8
echo "outputs in $out: frame.sid.h5, road.json, model.json, model_relative.json, vehicle.h5/.csv, vehicle_relative.h5/.csv, cab_acceleration.svg, frame_twist.svg, tyre_deflection.svg"
