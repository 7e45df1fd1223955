#!/usr/bin/env python3
"""Writes model.json: an Iltis-like 4x4 (elastic ladder frame, rigid cab and engine on rubber
mounts, two rigid axles on coil springs and dampers, four driven wheels on tyres) that stands on a
flat road, settles statically, speeds up to 10 m/s and drives over 100 m of an ISO 8608 class C
road (road.py). Usage: make_model.py ROAD_JSON [END_TIME] > model.json

Global axes: x forward (the direction of travel), y to the left, z up; the road's level part is
z = 0; the rear axle stands at x = 0, the front axle at x = 2.0. The frame's mesh (frame.geo) is
drawn in these coordinates.

Data (assumed, of the order of the VW Iltis, type 183: wheelbase about 2.0 m, curb mass about
1.5 t, 6.50-16 tyres; not taken from a data sheet): masses below; wheelbase 2.0 m, track 1.3 m,
tyre radius 0.36 m. The Iltis has independent wheels on transverse leaf springs; here two rigid
axles on coil springs, the simplest suspension that carries the frame's twist into the road.

Drive: the four wheels turn at a prescribed speed relative to their axles (a speed motion on each
wheel's revolute joint: a 4x4 with locked differentials driven at constant speed), zero for the
first T_REST s (the vehicle at rest, from its static equilibrium), then up along a smooth ramp
to V / r_e at T_CRUISE, held (PCHIP through rest, rest, V, V: zero acceleration at both ends of
the ramp, at most 1.5 V / (T_CRUISE - T_REST) = 3.75 m/s^2 in its middle; the vehicle squats and
pitches as it speeds up, about 20 m, on the road's flat start). r_e = r - delta is the rolling radius of the loaded tyre (the tyre
model rolls about its contact point under the centre, r - delta below it), so the vehicle runs at
V up to the slip that the rolling losses need."""
import json
import sys

road = json.load(open(sys.argv[1]))
end = float(sys.argv[2]) if len(sys.argv) > 2 else 15.0
G = 9.81
V, T_REST, T_CRUISE = 10.0, 0.5, 4.5       # speed [m/s]; at rest until T_REST, at V from T_CRUISE
R, KT, CT = 0.36, 2.5e5, 300.0             # tyre radius [m], vertical stiffness [N/m] and damping [N s/m]
XF, XR, TRACK, W = 2.0, 0.0, 1.3, 0.45     # axle positions, track, half distance of the rails [m]
Z_FRAME = 0.6                              # the rails' height (frame.geo)
M_FRAME = 2 * 3.5 * 1.3e-3 * 7850 + 5 * 0.9 * 8.29e-4 * 7850  # frame.json: rails and cross members
M_CAB, CAB = 800.0, (0.6, 0.0, 1.1)        # cab/body with seats, occupants and load
M_ENGINE, ENGINE = 250.0, (2.1, 0.0, 0.85) # engine, gearbox and transfer case
M_AXLE = {"front": 130.0, "rear": 120.0}   # axle with differential and brakes
M_WHEEL, I_SPIN, I_TILT = 35.0, 1.2, 0.7   # wheel: mass [kg], moments about its axle and across [kg m^2]
K_SPRING = {"front": 22000.0, "rear": 25000.0}  # coil springs [N/m] (body ride near 1.4 Hz)
C_SPRING = 1800.0                               # dampers [N s/m]

# Static loads from rigid-body statics (moments about the rear axle): the sprung mass (frame,
# cab, engine) on the springs; each tyre carries its corner's spring load and half its axle and
# its wheel. They preload the springs and place the wheels so that the static settling has
# little left to move (it finds the exact equilibrium).
sprung = M_FRAME + M_CAB + M_ENGINE
x_sprung = (M_FRAME * 0.95 + M_CAB * CAB[0] + M_ENGINE * ENGINE[0]) / sprung
spring_load = {"front": 0.5 * sprung * G * (x_sprung - XR) / (XF - XR), "rear": 0.5 * sprung * G * (XF - x_sprung) / (XF - XR)}
tyre_load = {a: spring_load[a] + (0.5 * M_AXLE[a] + M_WHEEL) * G for a in ("front", "rear")}
delta = {a: tyre_load[a] / KT for a in tyre_load}
z_axle = {a: R - delta[a] for a in delta}
omega = {a: V / (R - delta[a]) for a in delta}
X = {"front": XF, "rear": XR}


def r6(v):
    return [round(c, 6) for c in v]


bodies = [{"name": "frame", "type": "flexible", "sid": "frame.sid.h5",
           "comment": "elastic ladder frame (frame.json): free-free modes up to 80 Hz, meshed in global coordinates"},
          {"name": "cab", "type": "rigid", "mass": M_CAB, "com": list(CAB),
           "inertia": [[240.0, 0, 0], [0, 810.0, 0], [0, 0, 860.0]],
           "comment": "a box 3.3 x 1.5 x 1.2 m of uniform density"},
          {"name": "engine", "type": "rigid", "mass": M_ENGINE, "com": list(ENGINE),
           "inertia": [[15.0, 0, 0], [0, 25.0, 0], [0, 0, 25.0]]}]
joints, forces, motions = [], [], []
outputs = [{"name": "cab", "type": "node_position", "body": "cab"},
           {"name": "cab_velocity", "type": "node_velocity", "body": "cab"},
           {"name": "seat_velocity", "type": "node_velocity", "body": "cab", "at": [1.0, 0.35, 1.0]},
           {"name": "energy", "type": "energy"}]
for a in ("front", "rear"):
    x, z, s = X[a], z_axle[a], a[0]
    bodies.append({"name": f"{a}_axle", "type": "rigid", "mass": M_AXLE[a], "com": r6([x, 0, z]),
                   "inertia": [[M_AXLE[a] * TRACK ** 2 / 12, 0, 0], [0, 2.0, 0], [0, 0, M_AXLE[a] * TRACK ** 2 / 12]]})
    # The axle's guide (a bushing at the middle of the frame's cross member above it, the
    # axle's side carried rigidly): stiff along x and y and against the axle's pitch and steer,
    # free in heave and roll, which the springs carry.
    forces.append({"name": f"guide_{s}", "type": "bushing", "body1": "frame", "node1": f"guide_{s}", "body2": f"{a}_axle",
                   "stiffness": [2e6, 2e6, 0, 0, 2e5, 2e5], "damping": [2e3, 2e3, 0, 0, 2e2, 2e2]})
    for side, y in (("l", W), ("r", -W)):
        forces.append({"name": f"spring_{s}{side}", "type": "spring_damper", "body1": "frame", "node1": f"spring_{s}{side}",
                       "body2": f"{a}_axle", "at2": r6([x, y, z]), "k": K_SPRING[a], "c": C_SPRING,
                       "preload": round(-spring_load[a], 3),
                       "comment": "compression spring: a negative tension carries the static load at the drawn length"})
        outputs.append({"name": f"twist_{s}{side}", "type": "node_deformation", "body": "frame", "node": f"spring_{s}{side}"})
    for side, y in (("l", 0.5 * TRACK), ("r", -0.5 * TRACK)):
        w = f"wheel_{s}{side}"
        c = r6([x, y, z])
        bodies.append({"name": w, "type": "rigid", "mass": M_WHEEL, "com": c,
                       "inertia": [[I_TILT, 0, 0], [0, I_SPIN, 0], [0, 0, I_TILT]]})
        joints.append({"name": w, "type": "revolute", "body1": f"{a}_axle", "body2": w, "at": c, "axis": [0, 1, 0]})
        forces.append({"name": f"tyre_{s}{side}", "type": "tire", "body": w, "axis": [0, 1, 0], "radius": R,
                       "vertical_stiffness": KT, "vertical_damping": CT, "longitudinal_stiffness": 8e4,
                       "cornering_stiffness": 5e4, "friction": 0.9,
                       "road": "road_left" if side == "l" else "road_right"})
        motions.append({"joint": w, "speed": {"t": [0.0, T_REST, T_CRUISE, T_CRUISE + 1.0],
                                               "value": [0.0, 0.0, round(omega[a], 9), round(omega[a], 9)]}})
        outputs += [{"name": f"tyre_{s}{side}", "type": "element_force", "force": f"tyre_{s}{side}"},
                    {"name": f"spin_{s}{side}", "type": "joint_rate", "joint": w},
                    {"name": f"omega_{s}{side}", "type": "body_angular_velocity", "body": w},
                    {"name": f"hub_{s}{side}", "type": "node_position", "body": w}]
# The cab on four rubber mounts, the engine on three (two in front, one under the gearbox).
for n, p in (("cab_rl", [-0.6, W]), ("cab_rr", [-0.6, -W]), ("cab_fl", [1.0, W]), ("cab_fr", [1.0, -W])):
    forces.append({"name": n, "type": "bushing", "body1": "frame", "node1": n, "body2": "cab",
                   "stiffness": [1.5e5, 1.5e5, 3e5, 2e3, 2e3, 2e3], "damping": [1.5e3, 1.5e3, 3e3, 20.0, 20.0, 20.0]})
for n in ("engine_fl", "engine_fr", "engine_r"):
    forces.append({"name": n, "type": "bushing", "body1": "frame", "node1": n, "body2": "engine",
                   "stiffness": [2e5, 2e5, 3e5, 2e3, 2e3, 2e3], "damping": [1e3, 1e3, 1.5e3, 10.0, 10.0, 10.0]})

model = {
    "comment": "Iltis-like 4x4 on an ISO 8608 class C road at 10 m/s. Written by make_model.py.",
    "_drive": {"speed": V, "rest_until": T_REST, "cruise_from": T_CRUISE, "rolling_radius": r6([R - delta["front"], R - delta["rear"]])},
    "gravity": [0, 0, -G],
    "roads": [{"name": f"road_{side}", "direction": [1, 0, 0], "s": road["s"], "height": road[side]} for side in ("left", "right")],
    "bodies": bodies,
    "joints": joints,
    "forces": forces,
    "motions": motions,
    "solver": {"end": end, "step": 4e-3, "output_every": 1, "initial_equilibrium": True,
               "integrator": "generalized_alpha", "spectral_radius": 0.8, "newton_tolerance": 1e-8},
    "outputs": outputs,
}
json.dump(model, sys.stdout, indent=1)
sys.stdout.write("\n")
