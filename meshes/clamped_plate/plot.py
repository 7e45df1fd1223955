#!/usr/bin/env python3
"""Plots of the clamped plate with a weight as SVG (no plotting library needed): the free edge's
deflection (its middle and its corner node, and the weight's centre) over time against the static
sag, and the energy. Usage: plot.py RESULTS.csv STATIC.csv OUT_DIR"""
import csv
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
static = list(csv.DictReader(open(sys.argv[2])))[0]
out = sys.argv[3]
col = lambda k: [float(r[k]) for r in rows]
COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]


def svg(path, title, xlabel, ylabel, series):
    xs = [x for _, x, _ in series for x in x]
    ys = [y for _, _, y in series for y in y]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    x1, y1 = (x1 if x1 > x0 else x0 + 1), (y1 if y1 > y0 else y0 + 1)
    W, H, m = 640, 480, 60
    X = lambda x: m + (x - x0) / (x1 - x0) * (W - 2 * m)
    Y = lambda y: H - m - (y - y0) / (y1 - y0) * (H - 2 * m)
    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
         f'<rect width="{W}" height="{H}" fill="white"/><rect x="{m}" y="{m}" width="{W-2*m}" height="{H-2*m}" fill="none" stroke="black"/>',
         f'<text x="{W/2}" y="25" text-anchor="middle" font-size="14">{title}</text>',
         f'<text x="{W/2}" y="{H-15}" text-anchor="middle">{xlabel}</text>',
         f'<text x="15" y="{H/2}" transform="rotate(-90 15 {H/2})" text-anchor="middle">{ylabel}</text>']
    for v, f in ((x0, 0), (x1, 0), (y0, 1), (y1, 1)):
        o.append(f'<text x="{X(v) if f == 0 else m - 5}" y="{H - m + 15 if f == 0 else Y(v)}" '
                 f'text-anchor="{"middle" if f == 0 else "end"}">{v:.4g}</text>')
    for k, (name, x, y) in enumerate(series):
        pts = " ".join(f"{X(a):.1f},{Y(b):.1f}" for a, b in zip(x, y))
        o.append(f'<polyline points="{pts}" fill="none" stroke="{COLORS[k % 4]}" stroke-width="1"/>')
        o.append(f'<text x="{W - m - 5}" y="{m + 15 + 15 * k}" text-anchor="end" fill="{COLORS[k % 4]}">{name}</text>')
    open(path, "w").write("\n".join(o) + "\n</svg>\n")


t = col("time")
sag = float(static["tip_mid[2]"])
svg(f"{out}/deflection.svg", "clamped plate with a weight: free edge, vertical position", "time [s]", "z [mm]",
    [("free edge, middle node", t, [1e3 * v for v in col("tip_mid[2]")]),
     ("free corner", t, [1e3 * v for v in col("tip_corner[2]")]),
     ("weight's centre", t, [1e3 * v for v in col("weight_com[2]")]),
     ("static sag (middle node)", [t[0], t[-1]], [1e3 * sag, 1e3 * sag])])
svg(f"{out}/energy.svg", "energy (strain-rate damping dissipates it)", "time [s]", "J",
    [("kinetic", t, col("energy[0]")), ("potential", t, col("energy[1]")), ("total", t, col("energy[2]"))])
