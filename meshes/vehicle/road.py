#!/usr/bin/env python3
"""The rough road of the vehicle example: an ISO 8608 class C profile, generated with a fixed
seed (plain Python, no numpy), two tracks (under the left and the right wheels), written as JSON
{"s": [...], "left": [...], "right": [...]} for the model's two `roads` (a road is uniform across,
so each side's tyres run on a road of their own). Usage: road.py [SEED] > road.json

ISO 8608 (Mechanical vibration - Road surface profiles - Reporting of measured data) gives the
displacement PSD of a road over the spatial frequency n [cycles/m] as
    Gd(n) = Gd(n0) * (n / n0)^(-w),   n0 = 0.1 cycles/m,  waviness w = 2,
with Gd(n0) = 64e-6 m^3 the geometric mean of class C (32e-6 to 128e-6 m^3). The profile is the
usual sum of harmonics with random phases (e.g. Agostinacchio, Ciampa, Olita, "The vibrations
induced by surface irregularities in road pavements - a Matlab approach", 2014):
    h(s) = sum_i sqrt(2 Gd(n_i) dn) cos(2 pi n_i s + phi_i),
n_i = i dn, dn = 0.01 cycles/m (the 100 m section's own frequency), i = 1 ... 283: 0.01 ... 2.83
cycles/m (wavelengths 0.35 to 100 m; ISO 8608's band is 0.011 ... 2.83), phi_i uniform in [0, 2 pi) from Python's
Mersenne Twister seeded with SEED (default 8608) for the left track and SEED + 1 for the right
one: two independent profiles of the same class (real tracks are correlated at wavelengths
long against the track width; independent ones overstate the roll and twist input there). Its variance is sum_i Gd(n_i) dn (printed on
stderr with the profile's own rms; about (10 mm)^2, six tenths of it in the 100 m wave).

Layout along x (the direction of travel): flat (height 0) up to S0 = 25 m, where the vehicle
settles statically and gets up to speed; the rough section from S0 to S0 + 100 m, faded in and
out over its first and last 3 m by a half-cosine (so the road starts and ends level); flat again
to S0 + 130 m. Points every 0.05 m (seven a shortest wavelength; the model interpolates them by
PCHIP)."""
import json
import math
import random
import sys

SEED = int(sys.argv[1]) if len(sys.argv) > 1 else 8608
GD_N0, N0, W = 64e-6, 0.1, 2.0          # class C mean [m^3], reference frequency [1/m], waviness
DN, NMAX = 0.01, 2.83                   # frequency step and highest frequency [cycles/m]
S0, LENGTH, FADE, DS = 25.0, 100.0, 3.0, 0.05



def harmonics(seed):
    rng = random.Random(seed)
    out, i = [], 1
    while i * DN <= NMAX + 1e-12:
        n = i * DN
        out.append((n, math.sqrt(2.0 * GD_N0 * (n / N0) ** (-W) * DN), 2.0 * math.pi * rng.random()))
        i += 1
    return out


def rough(track, s):
    x = s - S0
    if x <= 0 or x >= LENGTH:
        return 0.0
    fade = min(1.0, x / FADE, (LENGTH - x) / FADE)
    window = 0.5 - 0.5 * math.cos(math.pi * fade)
    return window * sum(a * math.cos(2 * math.pi * n * x + p) for n, a, p in track)


s = [round(-10.0 + k * DS, 6) for k in range(int(round((S0 + LENGTH + 30.0 + 10.0) / DS)) + 1)]
result = {"s": s}
for side, seed in (("left", SEED), ("right", SEED + 1)):
    track = harmonics(seed)
    h = [round(rough(track, v), 7) for v in s]
    inside = [v for v, x in zip(h, s) if S0 + FADE <= x <= S0 + LENGTH - FADE]
    rms = math.sqrt(sum(v * v for v in inside) / len(inside))
    expect = math.sqrt(sum(a * a / 2 for _, a, _ in track))
    sys.stderr.write(f"road, {side} track: ISO 8608 class C, seed {seed}, {len(track)} harmonics {DN}..{track[-1][0]:.2f} cycles/m; "
                     f"rms {rms * 1e3:.2f} mm over the rough section (PSD integral {expect * 1e3:.2f} mm), "
                     f"range {min(h) * 1e3:.1f} .. {max(h) * 1e3:.1f} mm, {len(s)} points\n")
    result[side] = h
json.dump(result, sys.stdout)
sys.stdout.write("\n")
