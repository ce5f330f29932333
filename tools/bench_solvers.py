#!/usr/bin/python3
"""Solver benchmark: skyline (RCM and the generator's order) against UMFPACK.

    tools/bench_solvers.py [--build DIR] [--out DIR] [--quick]
                           [--skyline-max-neq N] [--timeout S]

Builds the `bench_solvers` target (bench/bench_solvers.f90; Release build in
DIR, default build/), then runs it once per mesh and solver -- a square
plane-strain block of Q4 elements, uniform and graded (ratio 20 between the
last and the first cell), from about 1e3 to 1e6 equations -- so that each
run's peak memory (VmHWM) is its own.  Writes OUT/solvers.csv and
OUT/solvers.png (time against equations, log-log; default OUT = docs/bench)
and prints the fitted scaling exponents and the crossover size.

The skyline solver is skipped above --skyline-max-neq equations (default
300000: beyond that its profile needs several GB and its factorization
grows like n^2); every run is stopped after --timeout seconds.
Not a test: a run takes about 10 to 20 minutes on 2 cores.
"""
import argparse
import csv
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from k2d.build import build_target  # noqa: E402

FIELDS = ["solver", "renumber", "nx", "grade", "neq", "nnz_factor", "analyse_s", "assembly_s",
          "factorize_s", "solve_s", "peak_rss_mb", "solver_mb", "max_u"]
# (solver, renumber, grade, label)
CONFIGS = [("skyline", "RCM", 1.0, "skyline + RCM"),
           ("skyline", "NONE", 1.0, "skyline, row-by-row order"),
           ("umfpack", "NONE", 1.0, "UMFPACK"),
           ("skyline", "RCM", 20.0, "skyline + RCM, graded"),
           ("umfpack", "NONE", 20.0, "UMFPACK, graded")]
SIZES = [22, 32, 45, 64, 90, 128, 180, 256, 360, 510, 707]
QUICK = [22, 45, 90]


def build(build_dir):
    """The bench_solvers program of a Release build in build_dir (configured and built if needed)."""
    return os.path.join(build_target("bench_solvers", build_dir, jobs=2), "bench_solvers")


def fit(n, t):
    """Least-squares slope and intercept of log t against log n."""
    if len(n) < 2:
        return float("nan"), float("nan")
    b, a = np.polyfit(np.log(n), np.log(t), 1)
    return b, a


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--out", default=os.path.join(ROOT, "docs", "bench"))
    p.add_argument("--quick", action="store_true", help="three small meshes only (a smoke test)")
    p.add_argument("--skyline-max-neq", type=int, default=300000)
    p.add_argument("--timeout", type=float, default=900.0)
    args = p.parse_args()

    exe = build(args.build)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for nx in (QUICK if args.quick else SIZES):
        neq = 2 * (nx + 1) * nx      # bottom row clamped
        for solver, ren, grade, _ in CONFIGS:
            if solver == "skyline" and neq > args.skyline_max_neq:
                print(f"skip  {solver:8s} {ren:4s} grade {grade:4.0f} nx {nx:4d}: {neq} equations "
                      f"> --skyline-max-neq {args.skyline_max_neq}", flush=True)
                continue
            try:
                r = subprocess.run([exe, solver, ren, str(nx), str(grade)], capture_output=True,
                                   text=True, timeout=args.timeout)
            except subprocess.TimeoutExpired:
                print(f"timeout {solver} {ren} nx {nx}", flush=True)
                continue
            if r.returncode != 0:
                print(f"failed {solver} {ren} nx {nx}: {r.stdout} {r.stderr}", flush=True)
                continue
            row = dict(zip(FIELDS, r.stdout.strip().split(",")))
            rows.append(row)
            print(f"{solver:8s} {ren:4s} grade {grade:4.0f} neq {int(row['neq']):8d}  "
                  f"assembly {float(row['assembly_s']):8.3f} s  factorize {float(row['factorize_s']):8.3f} s  "
                  f"solve {float(row['solve_s']):7.3f} s  peak {float(row['peak_rss_mb']):8.1f} MB", flush=True)

    csv_path = os.path.join(args.out, "solvers.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)

    def series(solver, ren, grade, key):
        sel = [r for r in rows if r["solver"] == solver and r["renumber"] == ren
               and abs(float(r["grade"]) - grade) < 1e-9]
        n = np.array([int(r["neq"]) for r in sel], dtype=float)
        if key == "total":
            t = np.array([float(r["assembly_s"]) + float(r["factorize_s"]) + float(r["solve_s"]) for r in sel])
        else:
            t = np.array([float(r[key]) for r in sel])
        return n, t

    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    styles = {"skyline + RCM": "o-", "skyline, row-by-row order": "s--", "UMFPACK": "^-",
              "skyline + RCM, graded": "o:", "UMFPACK, graded": "^:"}
    print("\nfitted exponents t ~ n^b (n >= 1e4 equations):")
    for solver, ren, grade, label in CONFIGS:
        n, tf = series(solver, ren, grade, "factorize_s")
        _, tt = series(solver, ren, grade, "total")
        _, mem = series(solver, ren, grade, "peak_rss_mb")
        if len(n) == 0:
            continue
        axes[0].loglog(n, tf, styles[label], label=label)
        axes[1].loglog(n, mem, styles[label], label=label)
        big = n >= 1.0e4
        bf, _ = fit(n[big], tf[big])
        bt, _ = fit(n[big], tt[big])
        bm, _ = fit(n[big], mem[big])
        print(f"  {label:28s} factorize {bf:5.2f}   assembly+factorize+solve {bt:5.2f}   peak memory {bm:5.2f}")
    # crossover: the smallest size from which UMFPACK's total beats skyline + RCM's
    ns, ts = series("skyline", "RCM", 1.0, "total")
    nu, tu = series("umfpack", "NONE", 1.0, "total")
    common = sorted(set(ns) & set(nu))
    ratios = [(n, ts[list(ns).index(n)] / tu[list(nu).index(n)]) for n in common]
    print("\nskyline + RCM / UMFPACK, assembly + factorize + solve:")
    for n, r in ratios:
        print(f"  neq {int(n):8d}: {r:6.2f}")
    cross = next((n for i, (n, r) in enumerate(ratios) if all(rr > 1.0 for _, rr in ratios[i:])), None)
    print("crossover: UMFPACK faster from", f"{int(cross)} equations on" if cross else "no size measured")

    axes[0].set_xlabel("equations")
    axes[0].set_ylabel("numeric factorization [s]")
    axes[0].set_title("factorization time")
    axes[1].set_xlabel("equations")
    axes[1].set_ylabel("peak resident memory [MB]")
    axes[1].set_title("peak memory of the run (VmHWM)")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Kontakt2D solvers: plane-strain Q4 block, one core")
    fig.tight_layout()
    png = os.path.join(args.out, "solvers.png")
    fig.savefig(png, dpi=110)
    print(f"\nwrote {csv_path} and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
