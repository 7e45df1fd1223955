#!/usr/bin/env python3
"""Plots of the vehicle run as SVG (no plotting library needed): the cab's vertical acceleration
(centre of mass and driver's seat; central differences of the sampled velocities) and the frame's
elastic twist (the front spring seats' vertical deflection difference less the rear ones', over
the rails' distance 0.9 m) over time, with the road height under the front left wheel.
With a second results file (the relative formulation's run), its cab acceleration is drawn too.
Usage: plot.py RESULTS.csv OUT_DIR [RELATIVE.csv]"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from svg_plot import svg  # noqa: E402 (meshes/svg_plot.py)

rows = list(csv.DictReader(open(sys.argv[1])))
out = sys.argv[2]
col = lambda k: [float(r[k]) for r in rows]

t = col("time")


def accel(k):
    v = col(k)
    return t[1:-1], [(v[i + 1] - v[i - 1]) / (t[i + 1] - t[i - 1]) for i in range(1, len(t) - 1)]


ta, a_cab = accel("cab_velocity[2]")
_, a_seat = accel("seat_velocity[2]")
curves = [("driver's seat", ta, a_seat), ("cab centre of mass", ta, a_cab)]
if len(sys.argv) > 3:
    rel = list(csv.DictReader(open(sys.argv[3])))
    tr, vr = [float(r["time"]) for r in rel], [float(r["cab_velocity[2]"]) for r in rel]
    curves.append(("cab centre of mass, relative formulation", tr[1:-1],
                   [(vr[i + 1] - vr[i - 1]) / (tr[i + 1] - tr[i - 1]) for i in range(1, len(tr) - 1)]))
svg(f"{out}/cab_acceleration.svg", "Cab vertical acceleration", "time [s]", "acceleration [m/s^2]", curves, size=(800, 400))
twist = [1e3 * ((a - b) - (c - d)) / 0.9 for a, b, c, d in
         zip(col("twist_fl[2]"), col("twist_fr[2]"), col("twist_rl[2]"), col("twist_rr[2]"))]
svg(f"{out}/frame_twist.svg", "Frame twist (front against rear, elastic)", "time [s]", "twist [mrad]", [("twist", t, twist)], size=(800, 400))
# The road under the front left tyre: its centre's height less the tyre's deflection and radius is
# not an output; the tyre's deflection (element_force's sixth value) is plotted instead.
svg(f"{out}/tyre_deflection.svg", "Tyre deflection", "time [s]", "deflection [mm]",
    [(n, t, [1e3 * v for v in col(f"tyre_{n}[5]")]) for n in ("fl", "fr", "rl", "rr")], size=(800, 400))
