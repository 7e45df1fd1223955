#!/usr/bin/env bash
# The flexible beam pendulum (Berzeri & Shabana's benchmark, make_model.py): simulate it as a
# geometrically exact beam and as an ancf beam (ffr-sim), plot the tip's path and height
# (ffr-info --plot) and check the results (check.py: energy, the swing, the two formulations).
# Usage: run.sh [OUT_DIR [END_TIME]]   defaults: ./out and 1 s; the test runs 0.3 s.
# The binaries come from build/bin, or from $FFR_BIN.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bin=${FFR_BIN:-$here/../../build/bin}
out=${1:-$here/out}
end=${2:-1.0}
mkdir -p "$out"
for form in geometrically_exact ancf; do
  echo "== simulate ${end} s as a ${form} beam (16 elements, 1 ms steps)"
  python3 "$here/make_model.py" "$form" "$end" > "$out/$form.json"
  "$bin/ffr-sim" "$out/$form.json" -o "$out/$form.h5" --csv "$out/$form.csv" --quiet
  echo "== plot the tip (x, z) and the middle node's height"
  "$bin/ffr-info" "$out/$form.h5" --plot "tip[0],tip[2],middle[2]" --png "$out/$form.png"
done
python3 "$here/check.py" "$out/geometrically_exact.csv" "$out/ancf.csv" "$end"
echo "outputs in $out: <formulation>.json/.h5/.csv/.png"
