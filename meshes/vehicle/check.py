#!/usr/bin/env python3
"""Sanity checks of the vehicle run (the example's test):
- every sample finite, the run reached its end;
- at rest (until the drive starts, after the static equilibrium): the cab moves less than 1e-6 m
  (no drift), the tyres' normal forces add up to the vehicle's weight within 0.1 % and their
  horizontal forces to nothing; the weight is computed here from the rigid bodies' masses in the
  model and the frame's mass from its drawn geometry and sections (frame.geo, frame.json), not
  from the SID;
- driving: the wheels' centres travel the distance the wheels roll (their absolute spin times the
  loaded rolling radius, make_model.py's r - delta) within the tyres' drive slip (3 % + 1 cm),
  and at constant speed its mean speed over the rough road is the set speed within 1 %;
- energy at constant speed: the kinetic energy is that of the whole vehicle's translation at its
  mean speed plus the wheels' spin (1/2 m v^2 + 4 * 1/2 I w^2) within -2 % and +5 % (the ride's
  own motion adds a little);
- bounds: the frame's twist stays below 2 degrees and the cab's vertical acceleration's rms over the
  rough road between 0.05 and 5 m/s^2 (a ride, not a crash; printed);
- the tyres keep their mean normal load at constant speed (within 5 % of the static one; over at
  least 5 s of it).
Usage: check.py RESULTS.csv MODEL.json END_TIME"""
import csv
import json
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
model = json.load(open(sys.argv[2]))
end = float(sys.argv[3])
assert rows, "no samples"
for r in rows:
    for k, v in r.items():
        assert math.isfinite(float(v)), f"{k} is not finite at t = {r['time']}"
t = [float(r["time"]) for r in rows]
assert abs(t[-1] - end) < 1e-9, f"the run stopped at {t[-1]}, not {end}"
col = lambda k: [float(r[k]) for r in rows]
drive = model["_drive"]
V, T_REST, T_CRUISE = drive["speed"], drive["rest_until"], drive["cruise_from"]
r_front, r_rear = drive["rolling_radius"]

g = 9.81
rho = 7850.0
frame = 2 * 3.5 * 1.3e-3 * rho + 5 * 0.9 * 8.29e-4 * rho   # rails 2 x 3.5 m, cross members 5 x 0.9 m
mass = frame + sum(b["mass"] for b in model["bodies"] if b["type"] == "rigid")
tyres = ["tyre_fl", "tyre_fr", "tyre_rl", "tyre_rr"]
rest = [i for i, v in enumerate(t) if v <= T_REST + 1e-12]
cab0 = [float(rows[0][f"cab[{j}]"]) for j in range(3)]
drift = max(math.dist(cab0, [float(rows[i][f"cab[{j}]"]) for j in range(3)]) for i in rest)
fz = [float(rows[0][f"{n}[2]"]) for n in tyres]
fx = sum(float(rows[0][f"{n}[0]"]) for n in tyres)
fy = sum(float(rows[0][f"{n}[1]"]) for n in tyres)
print(f"at rest ({len(rest)} samples to t = {t[rest[-1]]:.3f} s): cab drift {drift:.2e} m; tyres carry {sum(fz):.1f} N "
      f"of the weight {mass * g:.1f} N ({mass:.1f} kg), per tyre {', '.join(f'{v:.0f}' for v in fz)} N; horizontal {fx:.2g}, {fy:.2g} N")
assert drift < 1e-6, "the vehicle drifts at rest"
assert abs(sum(fz) - mass * g) < 1e-3 * mass * g, "the tyres do not carry the vehicle's weight within 0.1 %"
assert abs(fx) < 1e-3 * mass * g and abs(fy) < 1e-3 * mass * g, "horizontal tyre forces at rest do not cancel"

vx = col("cab_velocity[0]")
roll = [0.5 * (r_front * (float(r["omega_fl[1]"]) + float(r["omega_fr[1]"])) / 2 + r_rear * (float(r["omega_rl[1]"]) + float(r["omega_rr[1]"])) / 2)
        for r in rows]
# The distance the wheels roll (their absolute spin, about y, times the rolling radius, integrated
# by the trapezoidal rule) against the distance their centres travel: the absolute spin, not the
# prescribed one relative to the axle, since the axles pitch with the frame as the vehicle squats
# (up to 0.05 rad while it speeds up: 1.7 cm of rolling), and the wheels' centres, not the cab,
# which lags them by the same squat at its height.
rolled, worst = 0.0, 0.0
for i in range(1, len(t)):
    rolled += 0.5 * (roll[i] + roll[i - 1]) * (t[i] - t[i - 1])
    if t[i] <= T_REST:
        continue
    moved = sum(float(rows[i][f"hub_{n}[0]"]) - float(rows[0][f"hub_{n}[0]"]) for n in ("fl", "fr", "rl", "rr")) / 4
    tol = 0.03 * rolled + 0.01
    worst = max(worst, abs(moved - rolled) / tol)
    assert abs(moved - rolled) <= tol, f"at t = {t[i]:.3f} s the wheels' centres have moved {moved:.4f} m, the wheels have rolled {rolled:.4f} m"
print(f"driving: the wheels' centres travel as far as the wheels roll (worst {worst:.2f} of 3 % + 1 cm); "
      f"at the end {vx[-1]:.3f} m/s, {float(rows[-1]['cab[0]']) - cab0[0]:.2f} m travelled")

cruise = [i for i, v in enumerate(t) if v >= T_CRUISE + 1.0]
if len(cruise) > 10:
    i0, i1 = cruise[0], cruise[-1]
    mean_v = (float(rows[i1]["cab[0]"]) - float(rows[i0]["cab[0]"])) / (t[i1] - t[i0])
    print(f"constant speed from t = {t[i0]:.2f} s: mean speed {mean_v:.4f} m/s (set {V} m/s)")
    assert abs(mean_v - V) < 0.01 * V, "the vehicle does not advance at the set speed"
    wheels = [b for b in model["bodies"] if b["name"].startswith("wheel_")]
    spin_i = wheels[0]["inertia"][1][1]
    ke = col("energy[0]")
    lo = hi = None
    for i in cruise:
        w = [float(rows[i][f"omega_{n}[1]"]) for n in ("fl", "fr", "rl", "rr")]
        ref = 0.5 * mass * mean_v ** 2 + sum(0.5 * spin_i * x * x for x in w)
        q = ke[i] / ref
        lo, hi = (q, q) if lo is None else (min(lo, q), max(hi, q))
    print(f"kinetic energy at constant speed: {lo:.4f} .. {hi:.4f} of the translation and spin")
    assert 0.98 < lo and hi < 1.05, "the kinetic energy leaves the band of the vehicle's translation and its wheels' spin"
    for n in tyres if t[i1] - t[i0] >= 5.0 else []:  # a mean over at least 50 m of rough road
        f0 = float(rows[0][f"{n}[2]"])
        mean_f = sum(float(rows[i][f"{n}[2]"]) for i in cruise) / len(cruise)
        lift = sum(1 for i in cruise if float(rows[i][f"{n}[2]"]) <= 0) / len(cruise)
        print(f"  {n}: mean normal force {mean_f:.0f} N (static {f0:.0f} N), range {min(float(rows[i][f'{n}[2]']) for i in cruise):.0f} .. "
              f"{max(float(rows[i][f'{n}[2]']) for i in cruise):.0f} N, off the road {100 * lift:.1f} % of the time")
        assert abs(mean_f - f0) < 0.05 * f0, f"{n}'s mean normal force moved more than 5 % from the static one"

W = 0.45
twist = [((float(r["twist_fl[2]"]) - float(r["twist_fr[2]"])) - (float(r["twist_rl[2]"]) - float(r["twist_rr[2]"]))) / (2 * W) for r in rows]
print(f"frame twist: {1e3 * min(twist):.3f} .. {1e3 * max(twist):.3f} mrad")
assert max(abs(v) for v in twist) < math.radians(2), "the frame twists by more than 2 degrees"
if len(cruise) > 10:
    vz = col("cab_velocity[2]")
    acc = [(vz[i + 1] - vz[i - 1]) / (t[i + 1] - t[i - 1]) for i in cruise[1:-1]]
    rms = math.sqrt(sum(a * a for a in acc) / len(acc))
    print(f"cab vertical acceleration at constant speed: rms {rms:.3f} m/s^2, peak {max(abs(a) for a in acc):.2f} m/s^2")
    assert 0.05 < rms < 5, "the cab's vertical acceleration is out of a ride's range"
print("vehicle: checks passed")
