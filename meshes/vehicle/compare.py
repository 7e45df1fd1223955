#!/usr/bin/env python3
"""The vehicle in both formulations (runtime/FORMULATION.md sections 2-9 and 18): the cab's
vertical acceleration and the frame's twist, each as its rms over the rough road (plot.py's
definitions), from the absolute and the relative run; two discretisations of the same equations,
so they must agree to the step's error. Exits 1 if an rms differs by more than 1 %.
Usage: compare.py ABSOLUTE.csv RELATIVE.csv FROM_TIME"""
import csv
import math
import sys


def measures(path, t0):
    rows = list(csv.DictReader(open(path)))
    col = lambda k: [float(r[k]) for r in rows]
    t, v = col("time"), col("cab_velocity[2]")
    acc = [(v[i + 1] - v[i - 1]) / (t[i + 1] - t[i - 1]) for i in range(1, len(t) - 1) if t[i] >= t0]
    twist = [1e3 * ((a - b) - (c - d)) / 0.9 for s, a, b, c, d in
             zip(t, col("twist_fl[2]"), col("twist_fr[2]"), col("twist_rl[2]"), col("twist_rr[2]")) if s >= t0]
    rms = lambda x: math.sqrt(sum(y * y for y in x) / len(x))
    return {"cab vertical acceleration rms [m/s^2]": rms(acc), "frame twist rms [mrad]": rms(twist)}


a, r, t0 = measures(sys.argv[1], float(sys.argv[3])), measures(sys.argv[2], float(sys.argv[3])), float(sys.argv[3])
worst = 0.0
for k in a:
    d = abs(r[k] - a[k]) / abs(a[k])
    worst = max(worst, d)
    print(f"{k} from {t0:g} s: absolute {a[k]:.6g}, relative {r[k]:.6g} (apart {100 * d:.3f} %)")
if not worst < 0.01:
    print(f"compare.py: the formulations differ by {100 * worst:.3f} % (> 1 %)")
    sys.exit(1)
