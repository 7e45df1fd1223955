#!/usr/bin/env bash
# Mesh independence of the runtime step with real SID files: the rod of meshes/rod reduced by
# ffr-reduce (Craig-Bampton, 12 modes) from meshes of about 1k, 10k, 100k and 1M DOF, then the
# demo's slider-crank (meshes/models/slider_crank_rod.json, 3000 steps) run with each SID,
# interleaved, best of 15: the per-step time must not grow with the mesh (slowest / fastest
# <= 1.05). The 1M-DOF reduction takes a few minutes and about 12 GB.
#
#   tools/bench/runtime_step/mesh_independence.sh [--quick] [--workdir DIR]
#     --quick   only the 1k, 10k and 100k meshes
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../../.." && pwd)
quick=0 workdir="$root/build/bench-mesh-independence"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --workdir) workdir=$2; shift ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "mesh_independence.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
bin="$root/build/bin"
for tool in ffr-reduce ffr-bench-runtime-step; do
  [ -x "$bin/$tool" ] || { echo "mesh_independence.sh: $bin/$tool not built (scripts/test.sh builds it)" >&2; exit 2; }
done
mkdir -p "$workdir"
cp "$root/meshes/models/slider_crank_rod.json" "$workdir/model.json"

# order:size -> about 1k (TET4), 10k, 100k and 1M DOF (TET10)
cases="1:0.015 2:0.008 2:0.003"
[ $quick = 1 ] || cases="$cases 2:0.0013"
args=()
for c in $cases; do
  order=${c%%:*} size=${c#*:}
  part="$workdir/rod_${order}_${size}.json" sid="$workdir/rod_${order}_${size}.sid.h5" log="$workdir/rod_${order}_${size}.log"
  python3 - "$root/meshes/rod/rod.json" "$root/meshes/rod/rod.geo" "$order" "$size" "$part" <<'PY'
import json, sys
src, geo, order, size, out = sys.argv[1:]
part = json.load(open(src))
part["geometry"] = geo
part["mesh"] = {"size": float(size), "order": int(order)}
json.dump(part, open(out, "w"), indent=1)
PY
  if [ ! -f "$sid" ]; then
    echo "reducing the rod, mesh order $order size $size ..." >&2
    /usr/bin/time -f "  %e s wall, %M KB peak" "$bin/ffr-reduce" "$part" -o "$sid" 2>"$log" || { cat "$log" >&2; exit 1; }
    tail -1 "$log" >&2
  fi
  dof=$(sed -n 's/.*model: \([0-9]*\) DOF.*/\1/p' "$log" | head -1)
  args+=("$dof=$sid")
done
"$bin/ffr-bench-runtime-step" --sids "$workdir/model.json" rod.sid.h5 "${args[@]}"
