#!/usr/bin/env python3
"""Sanity checks of the precision-chamber run (the example's test): every sample finite, the run
reached its end, the target's deviation (its elastic displacement in the frame) within the
bounds a 80 Hz frame under millimetre vibrations and a 6 rad/s spin can give, the stiffened and
plain frames close to each other (the stiffening is a correction), the mount carrying the
frame's weight on average. The energy balance does not apply: the base's motions do work.
Usage: check.py RESULTS.csv END_TIME"""
import csv
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
end = float(sys.argv[2])
assert rows, "no samples"
for r in rows:
    for k, v in r.items():
        assert math.isfinite(float(v)), f"{k} is not finite at t = {r['time']}"
t_last = float(rows[-1]["time"])
assert abs(t_last - end) < 1e-9, f"the run stopped at {t_last}, not {end}"


def norm(r, name):
    return math.sqrt(sum(float(r[f"{name}[{i}]"]) ** 2 for i in range(3)))


dev = max(norm(r, "deviation") for r in rows)
plain = max(norm(r, "deviation_plain") for r in rows)
diff = max(math.sqrt(sum((float(r[f"deviation[{i}]"]) - float(r[f"deviation_plain[{i}]"])) ** 2 for i in range(3))) for r in rows)
# The mount's vertical force averaged over the run: the frame's weight (about 4.5 kg) plus the
# base's vertical vibration, which averages out.
fz = sum(float(r["mount_load[2]"]) for r in rows) / len(rows)
print(f"largest target deviation {dev * 1e6:.2f} um (plain frame {plain * 1e6:.2f} um, "
      f"difference {diff * 1e6:.3f} um); mean mount force {fz:.3f} N")
assert 1e-7 < dev < 1e-3, "deviation outside 0.1 um .. 1 mm"
assert diff < 0.2 * dev, "the stiffening changed the deviation by more than a fifth"
assert 20 < fz < 80, "the mount does not carry the frame's weight"
print("precision chamber: checks passed")
