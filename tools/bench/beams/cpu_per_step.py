#!/usr/bin/env python3
"""Two builds of ffr-bench-beams side by side: CPU time per step (user + system) of each formulation
and element count, as the CPU of a run to END less that of a run to one step (set-up and loading
cancel), over the benchmark's three runs of the time loop, best of RUNS. On a shared, loaded
machine this is fairer than the benchmark's own wall-time figure.

Usage: cpu_per_step.py OLD_BIN_DIR NEW_BIN_DIR [RUNS] [END]"""
import os
import subprocess
import sys


def cpu(binary, form, n, end):
    p = subprocess.Popen([binary, "--elements", str(n), "--end", str(end), "--formulation", form], stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    if status != 0:
        sys.exit(f"{binary} failed")
    return usage.ru_utime + usage.ru_stime


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    bins = {w: os.path.join(d, "ffr-bench-beams") for w, d in (("old", sys.argv[1]), ("new", sys.argv[2]))}
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 2
    end = float(sys.argv[4]) if len(sys.argv) > 4 else 0.5
    steps = 3 * (round(end / 1e-3) - 1)
    print("| formulation | elements | CPU us/step before | after | after / before |")
    print("|---|---:|---:|---:|---:|")
    for form in ("ancf", "geometrically_exact"):
        for n in (4, 8, 16, 32):
            us = {}
            for w, b in bins.items():
                us[w] = min(cpu(b, form, n, end) - cpu(b, form, n, 0.001) for _ in range(runs)) * 1e6 / steps
            print(f"| {form} | {n} | {us['old']:.0f} | {us['new']:.0f} | {us['new'] / us['old']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
