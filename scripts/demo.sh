#!/usr/bin/env bash
# The main job on built-in examples: reduce a flexible part to a SID file, simulate a
# multibody model that uses it, and print a summary. Outputs go to out/.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/setup.sh"
bin="$here/build/bin"
out="$here/out"
mkdir -p "$out"

echo "== 1. reduce the connecting rod (meshes/rod/rod.json): gmsh -> TET10 -> Craig-Bampton -> invariants"
"$bin/ffr-reduce" "$here/meshes/rod/rod.json" -o "$out/rod.sid.h5" --vtk "$out/rod_modes.vtk"
echo
echo "== 2. the reduced body"
"$bin/ffr-info" "$out/rod.sid.h5"
if [ -x "$bin/ffr-sim" ] && [ -f "$here/meshes/models/slider_crank.json" ]; then
  echo
  echo "== 3. simulate the slider-crank with the flexible rod (meshes/models/slider_crank.json)"
  "$bin/ffr-sim" "$here/meshes/models/slider_crank.json" -o "$out/slider_crank.h5" --csv "$out/slider_crank.csv"
  echo
  "$bin/ffr-info" "$out/slider_crank.h5"
fi
echo
echo "outputs in $out/ (open rod_modes.vtk in ParaView)"
