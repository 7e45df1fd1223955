#!/usr/bin/env bash
# Seed 003's clamped plate with a weight: a thin steel plate clamped along one edge, a rigid
# weight hinged under its free edge (spherical joints at two plate nodes), released flat under
# gravity: the plate bends far beyond its thickness and swings with the weight (ffr-sim), plotted
# as SVG (plot.py) and checked (check.py).
# Usage: run.sh [OUT_DIR [END_TIME]]   defaults: ./out and 2 s; the test runs 0.1 s.
# The binaries come from build/bin, or from $FFR_BIN.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bin=${FFR_BIN:-$here/../../build/bin}
out=${1:-$here/out}
end=${2:-2.0}
mkdir -p "$out"
python3 - "$here/model.json" "$end" > "$out/model.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["solver"]["end"] = float(sys.argv[2])
print(json.dumps(m, indent=1))
PY
echo "== the plate's static sag with the weight (the reference for the swing)"
python3 - "$out/model.json" > "$out/static.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["solver"] = {"analysis": "static"}
print(json.dumps(m, indent=1))
PY
"$bin/ffr-sim" "$out/static.json" -o "$out/static.h5" --csv "$out/static.csv" --quiet
echo "== simulate ${end} s: released flat, the plate and the weight swing down"
"$bin/ffr-sim" "$out/model.json" -o "$out/plate.h5" --csv "$out/plate.csv" --quiet
echo "== plot the free edge's deflection and the energy"
python3 "$here/plot.py" "$out/plate.csv" "$out/static.csv" "$out"
python3 "$here/check.py" "$out/plate.csv" "$out/static.csv" "$end"
echo "outputs in $out: model.json, plate.h5/.csv, static.h5/.csv, deflection.svg, energy.svg"
