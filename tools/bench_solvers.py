#!/usr/bin/python3
"""Solver benchmark: skyline (RCM and the generator's order) against UMFPACK and MUMPS.

    tools/bench_solvers.py [--build DIR] [--out DIR] [--quick]
                           [--skyline-max-neq N] [--timeout S]
    tools/bench_solvers.py --refinement [--sizes NX ...] [--nsolve N]

Builds the `bench_solvers` target (bench/bench_solvers.F90; Release build in
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

--refinement measures what UMFPACK's iterative refinement buys: on the
uniform and the graded block of each size, UMFPACK with 2 steps (UMFPACK's
default) and with none, each timed over --nsolve solves of one right-hand
side, against the skyline solver; prints the solve times, the residuals
max|b - K x| / max|b| and the largest difference from the skyline solution,
and writes OUT/refinement.csv.  The runs are interleaved, one process each.
Runs with OPENBLAS_NUM_THREADS=1 (one core per run) unless it is set.
"""
import argparse
import csv
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from k2d.build import build_target  # noqa: E402

FIELDS = ["solver", "renumber", "nx", "grade", "neq", "nnz_factor", "analyse_s", "assembly_s",
          "factorize_s", "solve_s", "peak_rss_mb", "solver_mb", "max_u", "option", "residual"]
# (solver, renumber, grade, label)
CONFIGS = [("skyline", "RCM", 1.0, "skyline + RCM"),
           ("skyline", "NONE", 1.0, "skyline, row-by-row order"),
           ("umfpack", "NONE", 1.0, "UMFPACK"),
           ("mumps", "NONE", 1.0, "MUMPS"),
           ("skyline", "RCM", 20.0, "skyline + RCM, graded"),
           ("umfpack", "NONE", 20.0, "UMFPACK, graded"),
           ("mumps", "NONE", 20.0, "MUMPS, graded")]
SIZES = [22, 32, 45, 64, 90, 128, 180, 256, 360, 510, 707]
QUICK = [22, 45, 90]


def build(build_dir):
    """The bench_solvers program of a Release build in build_dir (configured and built if needed)."""
    return os.path.join(build_target("bench_solvers", build_dir, jobs=2), "bench_solvers")


def run_one(exe, args, timeout):
    """One bench_solvers run; its CSV line as a dict, or None (reported)."""
    try:
        r = subprocess.run([exe] + [str(a) for a in args], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        print(f"timeout {' '.join(map(str, args))}", flush=True)
        return None
    if r.returncode != 0:
        print(f"failed {' '.join(map(str, args))}: {r.stdout} {r.stderr}", flush=True)
        return None
    return dict(zip(FIELDS, r.stdout.strip().split(",")))


def refinement(exe, sizes, nsolve, out, timeout):
    """UMFPACK with 2 and 0 steps of iterative refinement against skyline."""
    import tempfile
    rows = []
    tmp = tempfile.mkdtemp(prefix="k2d_refinement_")
    sol = {k: os.path.join(tmp, k + ".bin") for k in ("sky", "ir2", "ir0")}
    print(f"{'grade':>5s} {'neq':>8s} {'solve, 2 steps [s]':>19s} {'solve, none [s]':>16s} {'ratio':>6s} "
          f"{'residual, 2 steps':>18s} {'residual, none':>15s} {'|u - u_sky|/|u|, 2':>19s} "
          f"{'|u - u_sky|/|u|, 0':>19s}")
    for grade in (1.0, 20.0):
        for nx in sizes:
            # the same numbering (NONE) for all three, so that the solutions compare entry by entry
            sky = run_one(exe, ["skyline", "NONE", nx, grade, -1, 1, sol["sky"]], timeout)
            ir2 = run_one(exe, ["umfpack", "NONE", nx, grade, 2, nsolve, sol["ir2"]], timeout)
            ir0 = run_one(exe, ["umfpack", "NONE", nx, grade, 0, nsolve, sol["ir0"]], timeout)
            if not (sky and ir2 and ir0):
                continue
            u = np.fromfile(sol["sky"], dtype=np.float64)
            scale = np.abs(u).max()
            d2 = np.abs(np.fromfile(sol["ir2"], dtype=np.float64) - u).max() / scale
            d0 = np.abs(np.fromfile(sol["ir0"], dtype=np.float64) - u).max() / scale
            t2, t0 = float(ir2["solve_s"]), float(ir0["solve_s"])
            print(f"{grade:5.0f} {int(sky['neq']):8d} {t2:19.3e} {t0:16.3e} {t2 / t0:6.2f} "
                  f"{float(ir2['residual']):18.2e} {float(ir0['residual']):15.2e} {d2:19.2e} {d0:19.2e}",
                  flush=True)
            rows += [sky, ir2, ir0]
    for f in sol.values():
        if os.path.exists(f):
            os.remove(f)
    os.rmdir(tmp)
    path = os.path.join(out, "refinement.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")
    return 0


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
    p.add_argument("--refinement", action="store_true",
                   help="UMFPACK with and without iterative refinement (see above)")
    p.add_argument("--sizes", type=int, nargs="+", default=[22, 45, 90, 128],
                   help="NX of the blocks of --refinement")
    p.add_argument("--nsolve", type=int, default=50, help="solves timed together in --refinement")
    args = p.parse_args()

    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    exe = build(args.build)
    os.makedirs(args.out, exist_ok=True)
    if args.refinement:
        return refinement(exe, args.sizes, args.nsolve, args.out, args.timeout)
    rows = []
    for nx in (QUICK if args.quick else SIZES):
        neq = 2 * (nx + 1) * nx      # bottom row clamped
        for solver, ren, grade, _ in CONFIGS:
            if solver == "skyline" and neq > args.skyline_max_neq:
                print(f"skip  {solver:8s} {ren:4s} grade {grade:4.0f} nx {nx:4d}: {neq} equations "
                      f"> --skyline-max-neq {args.skyline_max_neq}", flush=True)
                continue
            row = run_one(exe, [solver, ren, nx, grade], args.timeout)
            if row is None:
                continue
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
    styles = {"skyline + RCM": "o-", "skyline, row-by-row order": "s--", "UMFPACK": "^-", "MUMPS": "v-",
              "skyline + RCM, graded": "o:", "UMFPACK, graded": "^:", "MUMPS, graded": "v:"}
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
