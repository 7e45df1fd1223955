#!/usr/bin/env python3
"""Writes model.json: the precision chamber's frame on a base moving by a prescribed six-DOF
motion. (The device of 'Dynamic analysis of the reaction chamber for the ELIADE array', Sandu et al.)
The base hangs on a chain of six joints (three slides, three turns), each with a motion
table; the frame is fixed to it at its foot. The frame is there twice, with and without its
geometric stiffening (the moving-frame stiffness terms of Sandu et al.), so one run gives the
target's deviation both ways. Usage: make_model.py [END_TIME] > model.json"""
import json
import math
import sys

end = float(sys.argv[1]) if len(sys.argv) > 1 else 2.0
dt = 0.002
ts = [round(k * dt, 10) for k in range(int(round(end / dt)) + 1)]


def window(t):  # smooth start of the vibrations over 0.2 s
    return 1.0 if t >= 0.2 else 0.5 * (1 - math.cos(math.pi * t / 0.2))


def vib(amp, hz):
    return [amp * window(t) * math.sin(2 * math.pi * hz * t) for t in ts]


def yaw(t):  # the stage turns up to 6 rad/s over 1 s (smoothly), then on at that rate
    w, T = 6.0, 1.0
    if t < T:
        return w * (t * t * t / (T * T) - 0.5 * t ** 4 / T ** 3)
    return w * (T / 2) + w * (t - T)


def rigid(name, z):
    return {"name": name, "type": "rigid", "mass": 1.0, "com": [0, 0, z],
            "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]}


motions = {
    "x": vib(2e-3, 6.0), "y": vib(1.5e-3, 9.0), "z": vib(1e-3, 14.0),
    "roll": vib(math.radians(0.2), 4.0), "pitch": vib(math.radians(0.2), 5.0),
    "yaw": [yaw(t) for t in ts],
}
stages = [("sx", "x", "prismatic", [1, 0, 0]), ("sy", "y", "prismatic", [0, 1, 0]), ("sz", "z", "prismatic", [0, 0, 1]),
          ("rx", "roll", "revolute", [1, 0, 0]), ("ry", "pitch", "revolute", [0, 1, 0]), ("base", "yaw", "revolute", [0, 0, 1])]
bodies, joints = [], []
previous = "ground"
for body, joint, kind, axis in stages:
    bodies.append(rigid(body, 0.0))
    joints.append({"name": joint, "type": kind, "body1": previous, "body2": body, "at": [0, 0, 0], "axis": axis})
    previous = body
for name, stiffening in (("chamber", True), ("chamber_plain", False)):
    bodies.append({"name": name, "type": "flexible", "sid": "frame.sid.h5", "stiffening": stiffening})
    joints.append({"name": name + "_mount", "type": "fixed", "body1": "base", "body2": name, "node2": "foot"})

model = {
    "comment": "The precision chamber of 'Dynamic analysis of the reaction chamber for the ELIADE array' (Sandu et al.): "
               "an elastic frame carrying a target on a base in six-DOF motion. Written by make_model.py.",
    "gravity": [0, 0, -9.81],
    "bodies": bodies,
    "joints": joints,
    "motions": [{"joint": j, "table": {"t": ts, "value": [round(v, 15) for v in motions[j]]}} for _, j, _, _ in stages],
    # Settled under gravity first (the frame's static sag), so the run shows the base's effect.
    "solver": {"end": end, "step": 5e-4, "output_every": 4, "initial_equilibrium": True},
    "outputs": [
        {"name": "deviation", "type": "node_deformation", "body": "chamber", "node": "target"},
        {"name": "deviation_plain", "type": "node_deformation", "body": "chamber_plain", "node": "target"},
        {"name": "target", "type": "node_position", "body": "chamber", "node": "target"},
        {"name": "yaw_rate", "type": "joint_rate", "joint": "yaw"},
        {"name": "mount_load", "type": "joint_reaction", "joint": "chamber_mount"},
    ],
}
json.dump(model, sys.stdout, separators=(", ", ": "))
sys.stdout.write("\n")
