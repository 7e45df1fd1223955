#!/usr/bin/env python3
"""Tables and the memory model of tools/bench/mpi/RESULTS.md from run.sh's results.tsv.

Model of the peak resident memory of one rank of the slepc path (the largest over the ranks),
n DOF on p ranks:   R(n, p) = a + b n + c n^alpha / p
  a: the program and its libraries; b n: what every rank holds whole (the mesh, the FE model,
  the DOF transform, the gathered modes); c n^alpha / p: what is divided (the rank's elements'
  K and M, its rows of the summed matrices, its part of MUMPS's factor and of the Krylov basis).
alpha is scanned, (a, b, c) fitted by relative least squares. The check: the model fitted
without the largest size predicts the largest size's runs.
Usage: fit.py results.tsv [more.tsv ...] [--mumps=pord/in-core]   (the runs of every file, sorted
by DOF; the model on the slepc runs of the given MUMPS settings only, else on all of them)
"""
import math
import sys


def solve3(A, y):
    # Normal equations of a small least-squares problem, Gaussian elimination with pivoting.
    n = len(A[0])
    N = [[sum(r[i] * r[j] for r in A) for j in range(n)] + [sum(r[i] * v for r, v in zip(A, y))] for i in range(n)]
    for k in range(n):
        piv = max(range(k, n), key=lambda i: abs(N[i][k]))
        N[k], N[piv] = N[piv], N[k]
        for i in range(k + 1, n):
            f = N[i][k] / N[k][k]
            for j in range(k, n + 1):
                N[i][j] -= f * N[k][j]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (N[i][n] - sum(N[i][j] * x[j] for j in range(i + 1, n))) / N[i][i]
    return x


def fit(runs):
    best = None
    for k in range(100, 171):
        alpha = k / 100
        A = [[1 / r, n / r, n ** alpha / p / r] for n, p, r in runs]
        y = [1.0] * len(runs)
        a, b, c = solve3(A, y)
        if min(a, b, c) < 0:
            continue
        err = max(abs(a + b * n + c * n ** alpha / p - r) / r for n, p, r in runs)
        if best is None or err < best[0]:
            best = (err, alpha, a, b, c)
    return best


def model(m, n, p):
    _, alpha, a, b, c = m
    return a + b * n + c * n ** alpha / p


def krylov_basis(nev):
    """Vectors in SLEPc Krylov-Schur's basis when ncv is not set (nev < 500)."""
    return max(2 * nev, nev + 15)


def incore_estimate(r):
    """An out-of-core run's in-core peak of its largest rank (MiB): its peak plus what MUMPS
    estimated in core (INFOG(16)) less what it allocated (INFOG(18)), plus, for a run with fewer
    modes than the model's 20, the Krylov basis it did not hold (SLEPc's default size, this
    rank's n / p rows). Returns (estimate, the basis part)."""
    n, p = int(r["dof"]), int(r["ranks"])
    peak = max(float(x) for x in r["maxrss_mib_per_rank"].split(","))
    extra = (float(r["mumps_incore_estimate_mb_max"]) - float(r["mumps_mb_max"])) * 1e6 / 2 ** 20
    basis = (krylov_basis(20) - krylov_basis(int(r["modes"]))) * (n / p) * 8 / 2 ** 20
    return peak + extra + basis, basis


def read(files):
    # Columns by name: results.tsv files written before the MUMPS columns existed still read.
    rows = []
    for f in files:
        lines = [l.rstrip("\n").split("\t") for l in open(f)]
        head = lines[0]
        for l in lines[1:]:
            r = dict(zip(head, l))
            for k in ("mumps", "factor_entries", "mumps_mb_max", "load_mean_max", "mumps_incore_estimate_mb_max"):
                r.setdefault(k, "-")
            r.setdefault("modes", "20")
            rows.append(r)
    return rows


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    # --mumps SETTINGS: the model on the slepc runs of these MUMPS settings only (e.g. pord/in-core).
    only = next((a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--mumps=")), None)
    rows = read(args)
    rows.sort(key=lambda r: (int(r["dof"]), r["path"] != "serial", r["ranks"], r["mumps"]))
    print("| size | DOF | path | ranks | MUMPS | wall [s] | peak RSS per rank [MiB] | factor entries | MUMPS MB (largest rank) | MUMPS in-core estimate MB | load (mean/max) | SID vs serial |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        name = "serial (default)" if r["path"] == "serial" else "slepc"
        print(f"| {r['size']} | {r['dof']} | {name} | {r['ranks']} | {r['mumps']} | {r['wall_s']} | "
              f"{r['maxrss_mib_per_rank'].replace(',', ' / ')} | {r['factor_entries']} | {r['mumps_mb_max']} | "
              f"{r['mumps_incore_estimate_mb_max']} | "
              f"{r['load_mean_max']} | {r['diff']} |")
    runs = [(int(r["dof"]), int(r["ranks"]), max(float(x) for x in r["maxrss_mib_per_rank"].split(",")))
            for r in rows if r["path"] != "serial" and r["ranks"] != "-" and r["diff"] in ("equivalent", "-")
            and (only is None or r["mumps"] == only)]
    label = "slepc runs" + (f", MUMPS {only}" if only else "")
    if len({n for n, _, _ in runs}) < 3:
        print(f"\n(fewer than three sizes of {label}: no model)")
        return
    m = fit(runs)
    err, alpha, a, b, c = m
    print(f"\nModel (all {label}): R(n, p) = {a:.0f} MiB + {b * 1e3:.3f} MiB per 1000 DOF x n/1000"
          f" + {c:.3g} MiB x n^{alpha:.2f} / p;  largest relative misfit {100 * err:.1f} %")
    # The check: fitted without a size (and every larger one), the model predicts that size's
    # runs; for the largest size and the one below it.
    for largest in sorted({n for n, _, _ in runs})[-2:]:
        rest = [x for x in runs if x[0] < largest]
        if len({n for n, _, _ in rest}) < 3:
            print(f"\n(fewer than three sizes below {largest} DOF: no check there)")
            continue
        m2 = fit(rest)
        print(f"\nCheck: fitted to the runs below {largest} DOF (alpha {m2[1]:.2f}), the model predicts those at {largest}:")
        for n, p, r in runs:
            if n == largest:
                pr = model(m2, n, p)
                print(f"- {p} rank(s): predicted {pr:.0f} MiB, measured {r:.0f} MiB ({100 * (pr - r) / r:+.1f} %)")
    # Out-of-core runs against the in-core model: MUMPS reports, besides what it allocated out of
    # core (INFOG(18)), what an in-core factorization would allocate on the largest rank
    # (INFOG(16)); the run's peak plus the difference estimates the in-core peak of that rank.
    ooc = [r for r in rows if r["path"] != "serial" and r["mumps"].endswith("/out-of-core")
           and r["mumps_mb_max"] != "-" and r["mumps_incore_estimate_mb_max"] != "-"]
    if ooc:
        print(f"\nOut-of-core runs against the model (all {label}): the in-core peak estimated as the"
              " run's peak + (MUMPS in-core estimate - MUMPS allocated):")
    for r in ooc:
        n, p, k = int(r["dof"]), int(r["ranks"]), int(r["modes"])
        peak = max(float(x) for x in r["maxrss_mib_per_rank"].split(","))
        est, basis = incore_estimate(r)
        pr = model(m, n, p)
        fewer = f" (with {basis:.0f} MiB added for the basis of 20 modes instead of {k})" if k != 20 else ""
        print(f"- {n} DOF, {p} rank(s): peak {peak:.0f} MiB out of core, in core about {est:.0f} MiB{fewer};"
              f" model {pr:.0f} MiB ({100 * (pr - est) / est:+.1f} %)")
    # The factor's growth between the two largest sizes of one-rank runs (MUMPS's entries), and
    # with it a second extrapolation: the divided part of the largest run's (estimated) in-core
    # peak, grown at that rate, plus the model's a + b n.
    one = {int(r["dof"]): float(r["factor_entries"]) for r in rows
           if r["path"] != "serial" and r["ranks"] == "1" and r["factor_entries"] != "-"}
    grown = None
    if len(one) >= 2 and ooc:
        (n1, e1), (n2, e2) = sorted(one.items())[-2:]
        growth = math.log(e2 / e1) / math.log(n2 / n1)
        r = max(ooc, key=lambda r: int(r["dof"]))
        n, p = int(r["dof"]), int(r["ranks"])
        est, _ = incore_estimate(r)
        _, _, a, b, _ = m
        divided = (est - a - b * n) * p
        grown = lambda q: a + b * 10e6 + divided * (10e6 / n) ** growth / q
        print(f"\nFactor entries (one rank) grew as n^{growth:.2f} from {n1} to {n2} DOF; the divided part of the"
              f" {n}-DOF run's in-core estimate ({divided:.0f} MiB on one rank) grown so to 10M DOF gives the second column.")
    print(f"\nPredicted peak memory per rank at 10M DOF (the fit on all {label}" + ("; by the factor's growth" if grown else "") + "):")
    for p in (1, 2, 8, 16, 32, 64, 128):
        extra = f"; {grown(p) / 1024:.1f} GiB per rank by the factor's growth" if grown else ""
        print(f"- {p} ranks: {model(m, 10e6, p) / 1024:.1f} GiB per rank ({p * model(m, 10e6, p) / 1024:.0f} GiB in all){extra}")


if __name__ == "__main__":
    main()
