#!/usr/bin/env python3
"""Sanity checks of the washing-machine run (the example's test):
- every sample finite, the run reached its end;
- at rest (the first sample, after the static equilibrium): the four feet's vertical forces add
  up to the machine's weight within 1 %, the horizontal ones to nothing; the weight is computed
  here from the masses the model and the part files state (the tub's shell from its meshed
  geometry: a 24-sided mantle and rear wall, 2 mm steel; the cabinet's panels from their
  drawn areas, 1.5 mm steel), not from the SIDs;
- energy: the friction dampers' dissipated energy never decreases; the kinetic energy is at
  least the drum's and the rotor's spin energy 1/2 I_xx w_x^2 (their absolute angular velocities,
  principal moments about their axes: a part of the whole), and once they spin (above 0.1 J) at
  most 1.3 times it plus 0.5 J (the tub's vibration and the unbalance's translation add a little);
- the belt: the rotor turns (relative to the tub) at 11.25 times the drum's rate, to 1e-6;
- the tub stays within its cabinet (the hub moves less than 50 mm from where it settled).
Usage: check.py RESULTS.csv END_TIME [FORMULATION]   (make_model.py's; "relative" adds the housings)"""
import csv
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
end = float(sys.argv[2])
housed = len(sys.argv) > 3 and sys.argv[3] == "relative"
assert rows, "no samples"
for r in rows:
    for k, v in r.items():
        assert math.isfinite(float(v)), f"{k} is not finite at t = {r['time']}"
t_last = float(rows[-1]["time"])
assert abs(t_last - end) < 1e-9, f"the run stopped at {t_last}, not {end}"

g = 9.81
R, L, t, rho, n = 0.3, 0.35, 0.002, 7850.0, 24
shell = (n * 2 * R * math.sin(math.pi / n) * L + 0.5 * n * R * R * math.sin(2 * math.pi / n)) * t * rho
tub = shell + 6.0 + 15.0                      # shell, motor, counterweight (tub.json)
# The cabinet (cabinet.json, cabinet.geo): 1.5 mm steel panels, four 0.6 x 0.85 m sides less the
# door's opening (radius 0.2 m) and the 0.6 x 0.6 m top and floor.
cabinet = (4 * 0.6 * 0.85 - math.pi * 0.2 ** 2 + 2 * 0.6 * 0.6) * 0.0015 * rho
mass = tub + cabinet + 7.5 + 1.2              # cabinet, drum with unbalance, rotor (make_model.py)
if housed:
    mass += 2 * 0.2                           # the two bearing housings of the relative model (make_model.py)
weight = mass * g
feet = ["foot_front_left", "foot_front_right", "foot_rear_left", "foot_rear_right"]
r0 = rows[0]
fz = [float(r0[f"{f}[2]"]) for f in feet]
fx = sum(float(r0[f"{f}[0]"]) for f in feet)
fy = sum(float(r0[f"{f}[1]"]) for f in feet)
print(f"at rest: feet carry {sum(fz):.2f} N of the weight {weight:.2f} N ({mass:.2f} kg); "
      f"per foot {', '.join(f'{v:.1f}' for v in fz)} N; horizontal sum {fx:.3g}, {fy:.3g} N")
assert abs(sum(fz) - weight) < 0.01 * weight, "the feet do not carry the machine's weight within 1 %"
assert abs(fx) < 1e-3 * weight and abs(fy) < 1e-3 * weight, "horizontal foot forces at rest do not cancel"
assert all(0.1 * weight < v < 0.4 * weight for v in fz), "a foot carries less than a tenth or more than 0.4 of the weight"

diss = [float(r["energy[3]"]) for r in rows]
assert diss[0] >= -1e-9 and all(b >= a - 1e-9 for a, b in zip(diss, diss[1:])), "dissipated energy decreases"
checked = 0
for r in rows:
    spin = 0.5 * (0.45 * float(r["drum_omega[0]"]) ** 2 + 0.002 * float(r["rotor_omega[0]"]) ** 2)
    ke = float(r["energy[0]"])
    assert ke >= spin * (1 - 1e-6) - 1e-9, f"kinetic energy {ke:.6g} J below the spin energy {spin:.6g} J at t = {r['time']}"
    if spin > 0.1:
        assert ke < 1.3 * spin + 0.5, f"kinetic energy {ke:.3f} J vs spinning parts {spin:.3f} J at t = {r['time']}"
        checked += 1
belt = max(abs(float(r["rotor_speed[0]"]) - 11.25 * float(r["drum_speed[0]"])) for r in rows)
top = max(abs(float(r["drum_speed[0]"])) for r in rows)
assert belt <= 1e-6 * max(1.0, 11.25 * top), f"the rotor's rate differs from 11.25 times the drum's by {belt:.3g} rad/s"
hub0 = [float(r0[f"hub[{i}]"]) for i in range(3)]
orbit = max(math.dist(hub0, [float(r[f"hub[{i}]"]) for i in range(3)]) for r in rows)
print(f"kinetic energy checked at {checked} samples; dissipated {diss[-1]:.3f} J; largest hub excursion {orbit * 1e3:.2f} mm")
assert orbit < 0.05, "the tub left its cabinet (hub moved more than 50 mm)"
print("washing machine: checks passed")
