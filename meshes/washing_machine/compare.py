#!/usr/bin/env python3
"""The spin-up's figures by which runs of the washing machine are compared (different steps,
formulations): the tub's tilt at the end (the rim-to-hub axis against x, degrees), the
amplitude of the rim's orbit in y and z (half its range over the last 0.2 s, mm), the range of
the front-left foot's vertical force over the same time (N), and, given a reference run, each
run's deviation from it relative to the quantity (the tilt's change from rest, the amplitudes,
the force's swing).
Usage: compare.py REFERENCE.csv [RUN.csv ...]"""
import csv
import math
import sys


def figures(path):
    rows = list(csv.DictReader(open(path)))
    t_end = float(rows[-1]["time"])
    last = [r for r in rows if float(r["time"]) >= t_end - 0.2 - 1e-9]

    def tilt(r):
        a = [float(r[f"rim[{i}]"]) - float(r[f"hub[{i}]"]) for i in range(3)]
        return math.degrees(math.acos(a[0] / math.hypot(*a)))

    def half_range(key):
        v = [float(r[key]) for r in last]
        return 0.5 * (max(v) - min(v))

    f = [float(r["foot_front_left[2]"]) for r in last]
    return {"t": t_end, "tilt0": tilt(rows[0]), "tilt": tilt(rows[-1]), "y": 1e3 * half_range("rim[1]"),
            "z": 1e3 * half_range("rim[2]"), "fmin": min(f), "fmax": max(f)}


ref = figures(sys.argv[1])
for path in sys.argv[1:]:
    g = figures(path)
    dev = max(abs(g["tilt"] - ref["tilt"]) / abs(ref["tilt"] - ref["tilt0"]), abs(g["y"] - ref["y"]) / ref["y"],
              abs(g["z"] - ref["z"]) / ref["z"],
              (abs(g["fmin"] - ref["fmin"]) + abs(g["fmax"] - ref["fmax"])) / (ref["fmax"] - ref["fmin"]))
    print(f"{path}: t = {g['t']:g} s, tilt {g['tilt0']:.3f} -> {g['tilt']:.3f} deg, rim orbit y / z {g['y']:.2f} / {g['z']:.2f} mm, "
          f"foot force {g['fmin']:.1f} - {g['fmax']:.1f} N; largest deviation from the reference {100 * dev:.1f} %")
