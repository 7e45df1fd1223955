#!/usr/bin/env bash
# Reduces the two parts of this example from their FE input decks (arm.inp: Abaqus/CalculiX,
# link.bdf: Nastran bulk data), simulates the double pendulum they form, checks that the total
# energy never rises (the bodies' 1 % modal damping only removes it) and stays within 1 % of
# the largest kinetic energy, and exports the reduced bodies for other tools.
#   run.sh [--quick] [BUILD_DIR]     --quick: 0.05 s of simulated time instead of 1 s (CI)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
quick=0
if [[ "${1:-}" == "--quick" ]]; then quick=1; shift; fi
bin="${1:-$here/../../build}/bin"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

"$bin/ffr-reduce" "$here/arm.json" -o "$out/arm.sid.h5" --quiet
"$bin/ffr-reduce" "$here/link.json" -o "$out/link.sid.h5" --quiet
cp "$here/model.json" "$out/model.json"
if [[ $quick == 1 ]]; then sed -i 's/"end": 1.0/"end": 0.05/' "$out/model.json"; fi
"$bin/ffr-sim" "$out/model.json" -o "$out/run.h5" --csv "$out/run.csv" --quiet
"$bin/ffr-info" "$out/run.h5"
# energy[0] kinetic, energy[1] potential, energy[2] total (runtime/MODEL_FILE.md); its change
# from the first sample.
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) { if ($i == "energy[0]") k = i; if ($i == "energy[2]") e = i }; next }
         NR == 2 { e0 = $e }
         { d = $e - e0; if ($k > kmax) kmax = $k; if (d > emax) emax = d; if (-d > lost) lost = -d }
         END { if (!k || !e) { print "fe_interop: no energy columns"; exit 1 }
               printf "fe_interop: largest kinetic energy %.4g J, energy gained %.3g J, lost %.3g J\n", kmax, emax, lost
               if (emax > 1e-6 * kmax || lost > 1e-2 * kmax) { print "fe_interop: energy not kept"; exit 1 } }' "$out/run.csv"
# The SIDs also leave as SID_FEM files and Matrix Market matrices for other tools.
"$bin/ffr-info" "$out/link.sid.h5" --export-fbi -o "$out/link.fbi"
"$bin/ffr-info" "$out/arm.sid.h5" --export-mtx -o "$out/arm_matrices"
# The arm once more from CalculiX's assembled K and M of its deck (*FREQUENCY,
# SOLVER=MATRIXSTORAGE: arm.sti, arm.mas, arm.dof) as "matrices": the SID of the deck itself
# without stiffening, to ffr-diff's 1e-5 (CalculiX's C3D10 mass takes 4 points, ffr's TET10 is
# exact: 2.5e-6 apart in the frequencies).
if command -v ccx > /dev/null; then
  sed '/^\*STEP/,$d' "$here/arm.inp" > "$out/arm.inp"
  printf '*STEP\n*FREQUENCY, SOLVER=MATRIXSTORAGE\n*END STEP\n' >> "$out/arm.inp"
  (cd "$out" && OMP_NUM_THREADS=1 ccx -i arm > ccx.log 2>&1) || { cat "$out/ccx.log"; exit 1; }
  common='"geometry": "arm.inp", "interfaces": [{"name": "root", "group": "root"}, {"name": "tip", "group": "tip"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 6}, "visual": false'
  echo "{$common}" > "$out/arm_deck.json"
  echo "{$common, \"matrices\": {\"format\": \"calculix\", \"K\": \"arm.sti\", \"M\": \"arm.mas\"}}" > "$out/arm_ccx.json"
  "$bin/ffr-reduce" "$out/arm_deck.json" -o "$out/arm_deck.sid.h5" --quiet
  "$bin/ffr-reduce" "$out/arm_ccx.json" -o "$out/arm_ccx.sid.h5" --quiet
  "$bin/ffr-diff" "$out/arm_deck.sid.h5" "$out/arm_ccx.sid.h5" --rtol 1e-5
fi
echo "fe_interop: reduced arm.inp and link.bdf, simulated $(tail -n 1 "$out/run.csv" | cut -d, -f1) s, exported link.fbi and arm_matrices/"
