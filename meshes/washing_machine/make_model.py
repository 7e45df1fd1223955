#!/usr/bin/env python3
"""Writes model.json: the washing machine of 'Flexible multibody simulation of a washing
machine' type models (elastic tub on springs and friction dampers in a cabinet on four feet).
Usage: make_model.py [END_TIME [FORMULATION [STEP]]] > model.json
  (defaults: 10 s, "absolute", 0.25 ms; "relative" carries the drum's and the rotor's shafts in
  rigid bearing housings on the tub, so that their spin is a joint angle, README.md)

Global axes: x along the drum's axis (front +x), z up; the floor is z = 0. The tub's mesh
(tub.geo: rear wall at x = 0, open front at x = 0.35) is placed with its axis at height 0.45.
The drum is driven by its speed (a speed motion on its bearing in the tub); the motor's rotor
follows through the belt, a coupler of ratio 11.25 between the rotor's shaft and the bearing
(both turning in the moving tub)."""
import json
import sys

end = float(sys.argv[1]) if len(sys.argv) > 1 else 10.0
formulation = sys.argv[2] if len(sys.argv) > 2 else "absolute"
assert formulation in ("relative", "absolute"), "FORMULATION is relative or absolute"
step = float(sys.argv[3]) if len(sys.argv) > 3 else 2.5e-4
housed = formulation == "relative"
RATIO = 11.25
TUB = (-0.175, 0.0, 0.45)  # position of the tub's mesh frame
RPM = 3.141592653589793 / 30
HOUSING = 0.2  # [kg] each bearing housing (below)


def tub(p):  # a point given in the tub's mesh frame, globally
    return [round(p[i] + TUB[i], 6) for i in range(3)]


# Drum speed [rpm] over time [s]: washing at 50 rpm, distribution at 90 rpm, then through the
# suspension's resonances (2-6 Hz, 120-360 rpm) up to the 1400 rpm spin, held.
profile = [(0.0, 0.0), (1.0, 50.0), (3.0, 50.0), (4.0, 90.0), (5.0, 90.0), (9.0, 1400.0), (10.0, 1400.0)]
speed_t = [t for t, _ in profile]
drum_speed = [round(v * RPM, 9) for _, v in profile]

bodies = [
    {"name": "cabinet", "type": "flexible", "sid": "cabinet.sid.h5",
     "comment": "elastic: 1.5 mm steel panels 0.6 x 0.6 x 0.85 m (cabinet.json), meshed in global coordinates"},
    {"name": "tub", "type": "flexible", "sid": "tub.sid.h5", "position": list(TUB)},
    {"name": "drum", "type": "rigid", "mass": 7.5, "com": [0, 0.0167, 0.45],
     "inertia": [[0.45, 0, 0], [0, 0.28, 0], [0, 0, 0.28]],
     "comment": "7 kg drum (radius 0.25 m) with a 0.5 kg unbalance at its radius, initially at +y"},
    {"name": "rotor", "type": "rigid", "mass": 1.2, "com": tub([0.175, 0, -0.37]),
     "inertia": [[0.002, 0, 0], [0, 0.003, 0], [0, 0, 0.003]]},
    # The bearings' housings: rigid parts bolted to the tub (the drum's to the rigid hub disk of
    # the rear wall, the rotor's end shield to the motor's mounting point), which do not turn.
    # Each shaft turns in its housing; its spin is then a joint angle of the relative formulation
    # (a revolute between two rigid frames), where a revolute on the shell's node could place the
    # spinning body only at its point, its frame turning in natural coordinates (FORMULATION.md 18).
] + [
    {"name": "bearing_housing", "type": "rigid", "mass": HOUSING, "com": tub([0, 0, 0]),
     "inertia": [[2e-4, 0, 0], [0, 1.1e-4, 0], [0, 0, 1.1e-4]]},
    {"name": "end_shield", "type": "rigid", "mass": HOUSING, "com": tub([0.175, 0, -0.37]),
     "inertia": [[2e-4, 0, 0], [0, 1.1e-4, 0], [0, 0, 1.1e-4]]},
] * housed
joints = [
    {"name": "bearing", "type": "revolute", "body1": "tub", "node1": "hub", "body2": "drum", "axis": [1, 0, 0]},
    {"name": "motor_shaft", "type": "revolute", "body1": "tub", "node1": "motor", "offset1": [0, 0, -0.07],
     "body2": "rotor", "axis": [1, 0, 0]},
] if not housed else [
    {"name": "housing_mount", "type": "fixed", "body1": "tub", "node1": "hub", "body2": "bearing_housing"},
    {"name": "shield_mount", "type": "fixed", "body1": "tub", "node1": "motor", "offset1": [0, 0, -0.07],
     "body2": "end_shield"},
    {"name": "bearing", "type": "revolute", "body1": "bearing_housing", "body2": "drum", "at": tub([0, 0, 0]),
     "axis": [1, 0, 0]},
    {"name": "motor_shaft", "type": "revolute", "body1": "end_shield", "body2": "rotor", "at": tub([0.175, 0, -0.37]),
     "axis": [1, 0, 0]},
]
joints += [
    {"name": "belt", "type": "coupler", "joint1": "motor_shaft", "joint2": "bearing", "ratio": RATIO},
]
# Three springs from the cabinet's top cross members to the tub, preloaded to carry the tub about where it is
# drawn (left/right a quarter of its weight each at 20 degrees, front a half); the static
# equilibrium settles the rest.
# The top ends hang from the cross members (cabinet interfaces rail_rear at (-0.0875, 0, 0.85),
# rail_front at (0.0875, 0, 0.85)), offset along them.
springs = [("spring_left", "rail_rear", [0, 0.2, 0], 116.0),
           ("spring_right", "rail_rear", [0, -0.2, 0], 116.0),
           ("spring_front", "rail_front", [0, 0, 0], 219.0)]
forces = [{"name": n, "type": "spring_damper", "body1": "cabinet", "node1": rail, "offset1": off, "body2": "tub", "node2": n,
           "k": 5000.0, "c": 20.0, "preload": pre} for n, rail, off, pre in springs]
# Two friction dampers from the tub's bottom to the cabinet floor's cross member (interface
# floor_rail at the origin), each with its rubber bearing in series.
for n, y in (("damper_left", 0.22), ("damper_right", -0.22)):
    forces.append({"name": n, "type": "friction_damper", "body1": "cabinet", "node1": "floor_rail", "offset1": [0, y, 0],
                   "body2": "tub", "node2": n, "force": 80.0, "series_stiffness": 3.0e4})
# The door gasket: stiffening radially (a table per radial axis), linear axially and in rotation.
gasket = {"x": [-0.03, -0.01, 0.0, 0.01, 0.03], "value": [-240.0, -30.0, 0.0, 30.0, 240.0]}
# Between the door ring of the cabinet's front panel (interface door at x = 0.3) and the tub's rim
# (x = 0.175): the point is the rim's, carried by the door ring at its offset.
forces.append({"name": "gasket", "type": "bushing", "body1": "cabinet", "node1": "door", "offset1": [-0.125, 0, 0],
               "body2": "tub", "node2": "rim",
               "stiffness": [3000.0, 0, 0, 20.0, 20.0, 20.0], "damping": [30.0, 30.0, 30.0, 0.2, 0.2, 0.2],
               "tables": {"y": gasket, "z": gasket}})
# Four rubber feet on the floor, under the cabinet's bottom corners (its interfaces of the same names).
feet = []
for n in ("foot_front_left", "foot_front_right", "foot_rear_left", "foot_rear_right"):
    forces.append({"name": n, "type": "bushing", "body1": "ground", "body2": "cabinet", "node2": n,
                   "stiffness": [1.0e5, 1.0e5, 4.0e5, 0, 0, 0], "damping": [300.0, 300.0, 800.0, 0, 0, 0]})
    feet.append(n)

model = {
    "comment": "Washing machine: elastic tub (shell, motor and counterweight attached) on three springs and two "
               "friction dampers in an elastic cabinet (shell) on four feet; drum with an unbalance spun up to 1400 rpm. "
               "Written by make_model.py.",
    "gravity": [0, 0, -9.81],
    "bodies": bodies,
    "joints": joints,
    "forces": forces,
    "motions": [{"joint": "bearing", "speed": {"t": speed_t, "value": drum_speed}}],
    # h = 0.25 ms: the rotor spins at up to 1650 rad/s, 0.41 rad a step; at 0.5 ms (0.82 rad a
    # step) Newton diverges near the top speed, with the trapezoidal rule and with generalized-alpha
    # alike (README.md). Newton's tolerance is tied to the step's own error: the tub's orbit at the
    # spin (6 mm at 23 Hz) has a local truncation error of h^3/12 |d^3x/dt^3| ~ 2.5e-8 m a step,
    # 4e-8 of the model length (0.61 m, the cabinet's feet from its centre of mass); the default
    # 1e-10 sat 400 times below it and cost 3.7 Newton iterations a step, 1e-8 costs 2.6 and moves
    # the outputs by a hundredth of what halving the step moves them (README.md).
    "solver": {"end": end, "step": step, "output_every": max(1, round(5e-3 / step)), "initial_equilibrium": True,
               "newton_tolerance": 1e-8, "formulation": formulation},
    "outputs": [{"name": "drum_speed", "type": "joint_rate", "joint": "bearing"},
                {"name": "rotor_speed", "type": "joint_rate", "joint": "motor_shaft"},
                {"name": "drum_omega", "type": "body_angular_velocity", "body": "drum"},
                {"name": "rotor_omega", "type": "body_angular_velocity", "body": "rotor"},
                {"name": "hub", "type": "node_position", "body": "tub", "node": "hub"},
                {"name": "rim", "type": "node_position", "body": "tub", "node": "rim"},
                # the tub's elastic coordinates, from which `ffr-info --stress` recovers its stress
                {"name": "q_tub", "type": "modal_coordinates", "body": "tub"},
                {"name": "energy", "type": "energy"}]
               + [{"name": n, "type": "element_force", "force": n} for n in feet],
}
json.dump(model, sys.stdout, indent=1)
sys.stdout.write("\n")
