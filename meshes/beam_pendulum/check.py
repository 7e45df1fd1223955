#!/usr/bin/env python3
"""Sanity checks of the beam pendulum runs (the example's test): every sample finite, each run
reached its end, the energy (kinetic + gravity + strain) kept to 1 % of the potential it swings
through (no damping: the trapezoidal rule's drift is O(h^2)), the tip fell (it swings down), and
during the fall (the first 0.4 s) the two formulations' tips within 2 cm of each other. Past the
bottom the very soft beam whips and the two part: they are different beam theories (shear and
the Biot axial strain in the geometrically exact beam, Green's strain and no shear in the ancf
beam), which this benchmark's 12 % stretches tell apart.
Usage: check.py GE.csv ANCF.csv END_TIME"""
import csv
import math
import sys

end = float(sys.argv[3])
runs = {}
for name, path in (("geometrically_exact", sys.argv[1]), ("ancf", sys.argv[2])):
    rows = list(csv.DictReader(open(path)))
    assert rows, f"{name}: no samples"
    for r in rows:
        for k, v in r.items():
            assert math.isfinite(float(v)), f"{name}: {k} is not finite at t = {r['time']}"
    assert abs(float(rows[-1]["time"]) - end) < 1e-9, f"{name}: the run stopped at {rows[-1]['time']}"
    e = [float(r["energy[0]"]) + float(r["energy[1]"]) for r in rows]
    scale = 0.0018 * 5540 * 1.2 * 9.81 * 0.6  # the weight times the centre's fall to the bottom
    drift = max(abs(x - e[0]) for x in e)
    low = min(float(r["tip[2]"]) for r in rows)
    print(f"{name}: energy drift {drift:.3e} J ({100 * drift / scale:.3f} % of {scale:.2f} J); lowest tip z {low:.4f} m")
    assert drift < 1e-2 * scale, f"{name}: energy drift above 1 %"
    if end >= 0.3:
        assert low < -0.3, f"{name}: the tip did not swing down"
    runs[name] = rows
diff = max(math.hypot(float(a["tip[0]"]) - float(b["tip[0]"]), float(a["tip[2]"]) - float(b["tip[2]"]))
           for a, b in zip(runs["geometrically_exact"], runs["ancf"]) if float(a["time"]) <= 0.4 + 1e-9)
print(f"largest distance between the two formulations' tips over the fall (t <= 0.4 s) {diff:.4f} m")
assert diff < 0.02, "the formulations' tips more than 2 cm apart during the fall"
print("beam pendulum: checks passed")
