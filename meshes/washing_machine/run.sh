#!/usr/bin/env bash
# The washing machine: reduce its tub and cabinet (ffr-reduce), settle it statically and spin the drum up
# from washing speed through the suspension's resonances to 1400 rpm (ffr-sim), plot the tub's
# orbit and the foot forces over the drum speed (plot.py, SVG) and check the results (check.py).
# Usage: run.sh [OUT_DIR [END_TIME [FORMULATION]]]   defaults: ./out, 10 s, absolute; the tests run 0.3 s
# in both formulations ("relative": the shafts in bearing housings, their spin a joint angle; README.md).
# The binaries come from build/bin, or from $FFR_BIN.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bin=${FFR_BIN:-$here/../../build/bin}
out=${1:-$here/out}
end=${2:-10.0}
formulation=${3:-absolute}
mkdir -p "$out"
cp "$here/tub.geo" "$here/tub.json" "$here/cabinet.geo" "$here/cabinet.json" "$out/"
echo "== reduce the tub: 2 mm steel shell with motor and counterweight, 10 free modes with stiffening"
"$bin/ffr-reduce" "$out/tub.json" -o "$out/tub.sid.h5" --quiet
echo "== reduce the cabinet: 1.5 mm steel panels, free modes up to 70 Hz"
"$bin/ffr-reduce" "$out/cabinet.json" -o "$out/cabinet.sid.h5" --quiet
echo "== simulate ${end} s: settle on springs, dampers and feet, then the drum-speed profile to 1400 rpm"
python3 "$here/make_model.py" "$end" "$formulation" > "$out/model.json"
"$bin/ffr-sim" "$out/model.json" -o "$out/machine.h5" --csv "$out/machine.csv" --quiet
echo "== the tub's stress over the run (top, middle and bottom surface of every shell node)"
"$bin/ffr-info" "$out/machine.h5" --stress tub > "$out/tub_stress.txt"
awk 'NR > 2 && $6 + 0 > peak { peak = $6 + 0; node = $1; layer = $5; t = $7 }
     END { printf "peak von Mises %.3g MPa at node %s (%s surface) at t = %s s\n", peak / 1e6, node, layer, t }' \
  "$out/tub_stress.txt"
echo "== plot the tub's orbit and the foot forces over drum speed"
python3 "$here/plot.py" "$out/machine.csv" "$out"
python3 "$here/check.py" "$out/machine.csv" "$end" "$formulation"
echo "outputs in $out: tub.sid.h5, cabinet.sid.h5, model.json, machine.h5/.csv, tub_stress.txt, orbit.svg, foot_forces.svg"
