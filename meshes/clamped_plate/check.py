#!/usr/bin/env python3
"""Sanity checks of the clamped plate with a weight (the example's test):
- every sample finite, the run reached its end;
- the static sag: the free edge's middle sags far beyond the plate's thickness (a large
  deflection), and the hinge reactions carry the weight (their vertical forces on the weight add
  up to its weight, m g, within 1e-6);
- released flat, the plate swings down: the total energy (kinetic + gravity + strain) never
  rises by more than 1e-6 J (strain-rate damping only dissipates), and the free edge never goes
  more than 2.2 times the static sag below its start (a load applied suddenly deflects a linear
  system at most twice its static deflection; the margin covers the stiffening plate's
  nonlinearity, which only lowers it);
- in a run of at least a second, the free edge has gone below the static sag.
Usage: check.py RESULTS.csv STATIC.csv END_TIME"""
import csv
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
static = list(csv.DictReader(open(sys.argv[2])))
end = float(sys.argv[3])
assert rows and static, "no samples"
for r in rows + static:
    for k, v in r.items():
        assert math.isfinite(float(v)), f"{k} is not finite at t = {r['time']}"
t_last = float(rows[-1]["time"])
assert abs(t_last - end) < 1e-9, f"the run stopped at {t_last}, not {end}"

h, m, g = 0.001, 2.0, 9.81  # model.json: thickness, the weight's mass, gravity
s = static[0]
sag = float(s["tip_mid[2]"])
assert sag < -20 * h, f"static sag {sag} m is not a large deflection"
# joint_reaction: the force body1 (the plate) exerts on body2 (the weight); only hinge_a is
# recorded, the two hinges share the weight by symmetry.
fz = float(s["hinge_a[2]"])
assert abs(2 * fz - m * g) < 1e-6 * m * g, f"hinge reactions {2 * fz} N do not carry the weight {m * g} N"

e = [float(r["energy[2]"]) for r in rows]
rise = max(b - a for a, b in zip(e, e[1:])) if len(e) > 1 else 0.0
assert rise < 1e-6, f"the total energy rose by {rise} J in one output interval"
z = [float(r["tip_mid[2]"]) for r in rows]
assert min(z) > 2.2 * sag, f"the free edge went to {min(z)} m, beyond 2.2 times the static sag {sag} m"
if end >= 1.0:
    assert min(z) < sag, f"the free edge never reached the static sag {sag} m (lowest {min(z)} m)"
print(f"static sag {1e3 * sag:.2f} mm ({-sag / h:.1f} thicknesses); lowest in the swing {1e3 * min(z):.2f} mm; "
      f"energy {e[0]:.4f} -> {e[-1]:.4f} J")
