#!/usr/bin/env bash
# The precision chamber: reduce its frame (ffr-reduce), simulate it on its base in six-DOF
# motion (ffr-sim), plot the target's deviation with and without the frame's geometric
# stiffening (ffr-info --plot) and check the results (check.py).
# Usage: run.sh [OUT_DIR [END_TIME]]   defaults: ./out and 2 s; the test runs 0.3 s.
# The binaries come from build/bin, or from $FFR_BIN.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bin=${FFR_BIN:-$here/../../build/bin}
out=${1:-$here/out}
end=${2:-2.0}
mkdir -p "$out"
cp "$here/frame.geo" "$here/frame.json" "$out/"
echo "== reduce the frame: beams, clamped at the foot, 8 modes with stiffening"
"$bin/ffr-reduce" "$out/frame.json" -o "$out/frame.sid.h5" --quiet
echo "== simulate ${end} s: the base slides and tilts by millimetres and tenths of a degree and spins up to 6 rad/s"
python3 "$here/make_model.py" "$end" > "$out/model.json"
"$bin/ffr-sim" "$out/model.json" -o "$out/chamber.h5" --csv "$out/chamber.csv" --quiet
echo "== plot the target's deviation (x, z in the frame), stiffened and plain"
"$bin/ffr-info" "$out/chamber.h5" --plot "deviation[0],deviation_plain[0],deviation[2],deviation_plain[2]" --png "$out/deviation.png"
python3 "$here/check.py" "$out/chamber.csv" "$end"
echo "outputs in $out: frame.sid.h5, model.json, chamber.h5/.csv, deviation.png"
