#!/usr/bin/env python3
"""Plots of the washing-machine run as SVG (no plotting library needed): the tub's orbit (the
rear hub's and the front rim's y-z motion from where they settled) and the four feet's vertical
forces over the drum speed [rpm]. Usage: plot.py RESULTS.csv OUT_DIR"""
import csv
import os
import math
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from svg_plot import svg  # noqa: E402 (meshes/svg_plot.py)

rows = list(csv.DictReader(open(sys.argv[1])))
out = sys.argv[2]
col = lambda k: [float(r[k]) for r in rows]

mm = lambda k: [1e3 * (v - col(k)[0]) for v in col(k)]
svg(f"{out}/orbit.svg", "Tub orbit (y-z, from the settled position)", "y [mm]", "z [mm]",
    [("rear hub", mm("hub[1]"), mm("hub[2]")), ("front rim", mm("rim[1]"), mm("rim[2]"))], equal=True)
rpm = [abs(v) * 30 / math.pi for v in col("drum_speed[0]")]
feet = ["foot_front_left", "foot_front_right", "foot_rear_left", "foot_rear_right"]
svg(f"{out}/foot_forces.svg", "Vertical foot forces over drum speed", "drum speed [rpm]", "force on the cabinet [N]",
    [(f, rpm, col(f"{f}[2]")) for f in feet])
