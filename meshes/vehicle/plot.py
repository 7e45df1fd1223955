#!/usr/bin/env python3
"""Plots of the vehicle run as SVG (no plotting library needed): the cab's vertical acceleration
(centre of mass and driver's seat; central differences of the sampled velocities) and the frame's
elastic twist (the front spring seats' vertical deflection difference less the rear ones', over
the rails' distance 0.9 m) over time, with the road height under the front left wheel.
With a second results file (the relative formulation's run), its cab acceleration is drawn too.
Usage: plot.py RESULTS.csv OUT_DIR [RELATIVE.csv]"""
import csv
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
out = sys.argv[2]
col = lambda k: [float(r[k]) for r in rows]
COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]


def svg(path, title, xlabel, ylabel, series):
    xs = [x for _, x, _ in series for x in x]
    ys = [y for _, _, y in series for y in y]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    x1, y1 = (x1 if x1 > x0 else x0 + 1), (y1 if y1 > y0 else y0 + 1)
    W, H, m = 800, 400, 60
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
svg(f"{out}/cab_acceleration.svg", "Cab vertical acceleration", "time [s]", "acceleration [m/s^2]", curves)
twist = [1e3 * ((a - b) - (c - d)) / 0.9 for a, b, c, d in
         zip(col("twist_fl[2]"), col("twist_fr[2]"), col("twist_rl[2]"), col("twist_rr[2]"))]
svg(f"{out}/frame_twist.svg", "Frame twist (front against rear, elastic)", "time [s]", "twist [mrad]", [("twist", t, twist)])
# The road under the front left tyre: its centre's height less the tyre's deflection and radius is
# not an output; the tyre's deflection (element_force's sixth value) is plotted instead.
svg(f"{out}/tyre_deflection.svg", "Tyre deflection", "time [s]", "deflection [mm]",
    [(n, t, [1e3 * v for v in col(f"tyre_{n}[5]")]) for n in ("fl", "fr", "rl", "rr")])
