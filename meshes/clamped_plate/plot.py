#!/usr/bin/env python3
"""Plots of the clamped plate with a weight as SVG (no plotting library needed): the free edge's
deflection (its middle and its corner node, and the weight's centre) over time against the static
sag, and the energy. Usage: plot.py RESULTS.csv STATIC.csv OUT_DIR"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from svg_plot import svg  # noqa: E402 (meshes/svg_plot.py)

rows = list(csv.DictReader(open(sys.argv[1])))
static = list(csv.DictReader(open(sys.argv[2])))[0]
out = sys.argv[3]
col = lambda k: [float(r[k]) for r in rows]

t = col("time")
sag = float(static["tip_mid[2]"])
svg(f"{out}/deflection.svg", "clamped plate with a weight: free edge, vertical position", "time [s]", "z [mm]",
    [("free edge, middle node", t, [1e3 * v for v in col("tip_mid[2]")]),
     ("free corner", t, [1e3 * v for v in col("tip_corner[2]")]),
     ("weight's centre", t, [1e3 * v for v in col("weight_com[2]")]),
     ("static sag (middle node)", [t[0], t[-1]], [1e3 * sag, 1e3 * sag])])
svg(f"{out}/energy.svg", "energy (strain-rate damping dissipates it)", "time [s]", "J",
    [("kinetic", t, col("energy[0]")), ("potential", t, col("energy[1]")), ("total", t, col("energy[2]"))])
