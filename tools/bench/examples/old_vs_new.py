#!/usr/bin/env python3
"""Two builds of ffr-sim side by side on the same models, in one run: for each model the two
binaries run alternately RUNS times each (a burst of load on the shared machine then hits both),
and the table gives per binary the best integration time per step (ffr-sim's summary: its time
loop's wall time), the least CPU time of the whole process (user seconds, loading included; the
fairer figure on a loaded machine), Newton iterations per step, and how far the two runs' outputs
(the CSV, every column over every sample) differ, relative to each column's range.

Usage: old_vs_new.py OLD_BIN_DIR NEW_BIN_DIR RUNS NAME=MODEL.json [NAME=MODEL.json ...]
Each model is run in a scratch folder beside it (its SIDs are found relative to the model)."""
import csv
import os
import re
import subprocess
import sys
import tempfile


def run(binary, model, out_dir):
    h5, csv_path = os.path.join(out_dir, "out.h5"), os.path.join(out_dir, "out.csv")
    proc = subprocess.Popen([binary, model, "-o", h5, "--csv", csv_path], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    text = proc.stdout.read().decode()
    _, status, usage = os.wait4(proc.pid, 0)
    if status != 0:
        sys.exit(f"{binary} {model} failed:\n{text}")
    m = re.search(r"(\d+) steps, (\d+) Newton iterations, (?:\d+ tangents, \d+ solves, )?([0-9.eE+-]+) s integration", text)
    if not m:
        sys.exit(f"no summary line from {binary}:\n{text}")
    steps, newton, secs = int(m.group(1)), int(m.group(2)), float(m.group(3))
    return steps, newton, secs, usage.ru_utime, csv_path


def read_csv(path):
    with open(path) as f:
        rows = [r for r in csv.reader(f)]
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


def difference(a, b):
    """Largest difference of any column over all samples, relative to that column's range."""
    ha, ra = read_csv(a)
    hb, rb = read_csv(b)
    if ha != hb or len(ra) != len(rb):
        return float("inf")
    worst = 0.0
    for j in range(1, len(ha)):
        col_a = [r[j] for r in ra]
        col_b = [r[j] for r in rb]
        span = max(col_a) - min(col_a)
        if span == 0:
            span = max(1.0, max(abs(x) for x in col_a))
        worst = max(worst, max(abs(x - y) for x, y in zip(col_a, col_b)) / span)
    return worst


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    old_dir, new_dir, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
    print("| model | steps | old us/step (loop) | new us/step (loop) | old CPU s | new CPU s | CPU new/old | Newton it./step old / new | outputs differ by |")
    print("|---|---:|---:|---:|---:|---:|---:|---|---:|")
    for arg in sys.argv[4:]:
        name, model = arg.split("=", 1)
        best = {"old": None, "new": None}
        csvs = {}
        with tempfile.TemporaryDirectory(dir=os.path.dirname(os.path.abspath(model))) as scratch:
            for r in range(runs):
                for which, d in (("old", old_dir), ("new", new_dir)):
                    out = os.path.join(scratch, which)
                    os.makedirs(out, exist_ok=True)
                    steps, newton, secs, cpu, csv_path = run(os.path.join(d, "ffr-sim"), model, out)
                    b = best[which]
                    best[which] = (steps, newton, min(secs, b[2]) if b else secs, min(cpu, b[3]) if b else cpu)
                    csvs[which] = csv_path
            diff = difference(csvs["old"], csvs["new"])
        o, n = best["old"], best["new"]
        print(f"| {name} | {o[0]} | {1e6 * o[2] / o[0]:.0f} | {1e6 * n[2] / n[0]:.0f} | {o[3]:.2f} | {n[3]:.2f} | "
              f"{n[3] / o[3]:.2f} | {o[1] / o[0]:.2f} / {n[1] / n[0]:.2f} | {diff:.1e} |", flush=True)


if __name__ == "__main__":
    main()
