#!/usr/bin/env python3
"""Tables and the memory model of tools/bench/mpi/RESULTS.md from run.sh's results.tsv.

Model of the peak resident memory of one rank of the slepc path (the largest over the ranks),
n DOF on p ranks:   R(n, p) = a + b n + c n^alpha / p
  a: the program and its libraries; b n: what every rank holds whole (the mesh, the FE model,
  the DOF transform, the gathered modes); c n^alpha / p: what is divided (the rank's elements'
  K and M, its rows of the summed matrices, its part of MUMPS's factor and of the Krylov basis).
alpha is scanned, (a, b, c) fitted by relative least squares. The check: the model fitted
without the largest size predicts the largest size's runs.
Usage: fit.py results.tsv [more.tsv ...]   (the runs of every file, sorted by DOF)
"""
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


def main():
    rows = [l.rstrip("\n").split("\t") for f in sys.argv[1:] for l in list(open(f))[1:]]
    rows.sort(key=lambda r: (int(r[1]), r[2] != "serial", r[3]))
    print("| size | DOF | path | ranks | wall [s] | peak RSS per rank [MiB] | SID vs serial |")
    print("|---|---|---|---|---|---|---|")
    for size, dof, path, ranks, wall, rss, diff in rows:
        name = "serial (default)" if path == "serial" else "slepc"
        print(f"| {size} | {dof} | {name} | {ranks} | {wall} | {rss.replace(',', ' / ')} | {diff} |")
    runs = [(int(r[1]), int(r[3]), max(float(x) for x in r[5].split(","))) for r in rows
            if r[2] != "serial" and r[3] != "-"]
    if len({n for n, _, _ in runs}) < 3:
        print("\n(fewer than three sizes of slepc runs: no model)")
        return
    m = fit(runs)
    err, alpha, a, b, c = m
    print(f"\nModel (all slepc runs): R(n, p) = {a:.0f} MiB + {b * 1e3:.3f} MiB per 1000 DOF x n/1000"
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
    print("\nPredicted peak memory per rank at 10M DOF (the fit on all runs):")
    for p in (1, 2, 8, 16, 32, 64, 128):
        print(f"- {p} ranks: {model(m, 10e6, p) / 1024:.1f} GiB per rank ({p * model(m, 10e6, p) / 1024:.0f} GiB in all)")


if __name__ == "__main__":
    main()
