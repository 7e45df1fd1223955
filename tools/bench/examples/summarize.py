#!/usr/bin/env python3
"""One line of tools/bench/examples/RESULTS.md from ffr-sim's summary lines (stdin, one per run):
the best run's integration seconds, the real-time factor (simulated seconds per wall second),
steps, Newton iterations per step, and the model's size (bodies, modes, coordinates, joints,
motions, force elements). Usage: summarize.py NAME END MODEL.json SID=NQ ..."""
import json
import re
import sys

name, end, model_path = sys.argv[1], float(sys.argv[2]), sys.argv[3]
nq = {a.split("=")[0]: int(a.split("=")[1]) for a in sys.argv[4:]}
runs = []
for line in sys.stdin:
    m = re.search(r"(\d+) steps, (\d+) Newton iterations, (?:\d+ tangents, \d+ solves, )?([0-9.eE+-]+) s integration", line)
    if m:
        runs.append((float(m.group(3)), int(m.group(1)), int(m.group(2))))
if not runs:
    sys.exit("summarize.py: no ffr-sim summary line")
secs, steps, newton = min(runs)
model = json.load(open(model_path))
bodies = model["bodies"]
flexible = [b for b in bodies if b["type"] == "flexible"]
modes = sum(nq.get(b["sid"].split("/")[-1], 0) for b in flexible)
coords = 12 * len(bodies) + modes
print(f"| {name} | {end:g} s | {steps} | {newton / steps:.2f} | {secs:.3f} s | {end / secs:.2f} | "
      f"{len(bodies) - len(flexible)} rigid, {len(flexible)} flexible ({modes} modes) | {coords} | "
      f"{len(model.get('joints', []))} joints, {len(model.get('motions', []))} motions, {len(model.get('forces', []))} forces | "
      f"best of {len(runs)} |")
