#!/usr/bin/python3
"""Accuracy against cost: a matrix of models of three contact benchmarks, each run measured
for its error, CPU time, solutions and memory (docs/accuracy-and-stability.md, "Cost study").

    tools/study.py                 # the default matrix, about 17 minutes on 2 cores
    tools/study.py --quick         # a smoke test of the whole chain, under a minute
    tools/study.py --convergence   # the refinement sequences that justify the references
    tools/study.py --figures       # redraw the charts and tables from OUT/study.csv
    tools/study.py --full          # every model with both solvers (about twice the time)
    tools/study.py --keep          # keep the runs' HDF5 files (several GB; deleted once read by default)

Benchmarks (decks from k2d.examples, the generators of the paper's examples):

* hertz_smooth  sphere of example 5.2 at P = 200 N with the ideal law (LAW IDEAL), frictionless;
                reference: Hertz's closed form, peak pressure p0 and contact radius a;
* hertz_rough   the same sphere with the paper's rough surface c_n = 0.8, m = 0.5;
                reference: a converged fine run (Q8, contact nodes a_H/40 apart, Newton);
* punch         example 5.1, Table 1 column 2 (rough, Coulomb 0.2); reference: a converged
                fine Newton run (Q8 graded towards the punch corner, 320 increments);
                errors of the pressure at the punch edge (its maximum) and of u_T there;
* cylinder      example 5.3 at 100 kN, c_n = 0.44; reference: a converged fine Newton run
                (Q8, nodes 0.125 mm apart, 640 increments); errors
                of the pressure at the outer edge of the annulus (its maximum) and of the
                largest shear stress.

The matrix: element (T3, Q4, Q8, Q9) x mesh level x increments x scheme (incremental = the
paper's SCHEME INCREMENTAL, newton = SCHEME NEWTON, automatic = OPTIONS AUTOINC with the
scheme named in AUTO_SCHEME) x solver (skyline for every model, UMFPACK for the slice
SOLVER_SLICE, or for every model with --full).  A run's error is the larger of its two
relative errors; its cost the CPU time (user + system) of the kontakt2d process, from the
operating system's accounting of that child (os.wait4), beside the wall time, the program's
own timing (last line of its progress table), the solutions of the linear system (sum of the
increments' `iterations`), the accepted steps and cuts, and the peak memory (max RSS).

Writes OUT/study.csv, OUT/study.png (error against CPU time, Pareto fronts per scheme and per
element), OUT/study_summary.md (cheapest models meeting 1 % and 5 %, the Pareto-optimal
models, the solvers compared) and, with --convergence, OUT/study_convergence.csv.  Unless
--quick or --no-docs, these are copied to docs/figures/.  Timings are comparable only within
one run of this script (the machine may be shared): the summary gives them as ratios.
The study itself is the package module k2d.study (reading through k2d.results); this is its
command line.
"""
import argparse
import os
import shutil
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from k2d import study  # noqa: E402
from k2d.build import find_or_build  # noqa: E402
from k2d.tables import read_csv  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe",
                    help="the kontakt2d program (default: $K2D_EXECUTABLE, else build/kontakt2d, built if needed)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "study"))
    ap.add_argument("-j", "--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--quick", action="store_true", help="a small matrix with cheap references (smoke test)")
    ap.add_argument("--full", action="store_true", help="both solvers for every model")
    ap.add_argument("--only", nargs="+", choices=study.BENCHES)
    ap.add_argument("--convergence", action="store_true", help="run the refinement sequences of the references")
    ap.add_argument("--figures", action="store_true", help="redraw from OUT/study.csv, run nothing")
    ap.add_argument("--no-docs", action="store_true", help="do not copy the results to docs/figures/")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds before a run is stopped")
    ap.add_argument("--keep", action="store_true", help="keep every run's HDF5 file and listing in OUT/h5")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    docs = None if (args.quick or args.no_docs) else os.path.join(ROOT, "docs", "figures")

    if args.convergence:
        exe = find_or_build(args.exe)
        rows = study.run_pool(exe, args.out, study.convergence_cases(args.only), args.jobs, args.timeout,
                              keep=args.keep)
        path = os.path.join(args.out, "study_convergence.csv")
        study.convergence_table([rows[k] for k in sorted(rows)], path)
        if docs:
            shutil.copy(path, docs)
        return

    csv_path = os.path.join(args.out, "study.csv")
    if args.figures:
        rows = read_csv(csv_path)
    else:
        exe = find_or_build(args.exe)
        t0 = time.time()
        cases = study.reference_cases(args.quick, args.only) + study.matrix(args.quick, args.full, args.only)
        done = study.run_pool(exe, args.out, cases, args.jobs, args.timeout, 1 if args.quick else study.REPEATS,
                              keep=args.keep)
        rows = []
        for c in cases:
            row = done[c.name]
            row["role"] = c.role
            rows.append(row)
        refs = {r["benchmark"]: r for r in rows if r["role"] == "reference"}
        study.attach_errors(rows, refs)
        rows = [dict(r, level=r["level"] if r["role"] == "matrix" else "reference") for r in rows]
        study.write_csv(csv_path, rows)
        print("%d runs in %.0f s of wall time" % (len(cases), time.time() - t0))
    for r in rows:
        r.setdefault("role", "reference" if r["level"] == "reference" else "matrix")
        if r["level"] == "reference":
            r["role"] = "reference"
    refs = {r["benchmark"]: r for r in rows if r["role"] == "reference"}
    benches = [b for b in study.BENCHES if any(r["benchmark"] == b for r in rows)]
    png = os.path.join(args.out, "study.png")
    study.chart(rows, png, benches)
    md = os.path.join(args.out, "study_summary.md")
    print(study.summary(rows, md, benches, refs))
    print("table: %s\nchart: %s\nsummary: %s" % (csv_path, png, md))
    if docs:
        for p in (csv_path, png, md):
            shutil.copy(p, docs)


if __name__ == "__main__":
    main()
