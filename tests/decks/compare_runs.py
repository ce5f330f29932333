#!/usr/bin/python3
"""Two runs of one deck, one answer: compare two Kontakt2D result files increment by increment.

    compare_runs.py A.h5 B.h5 [--rtol 1e-10] [--every N]

Both files must hold the same increments with the same decisions: the same status, the same
increment numbers, and the same counts of every increment (solutions, repeats, cuts, convergence,
invariant violations).  Every nodal and Gauss-point field and every contact quantity of every
increment must agree to rtol relative to the largest magnitude of its kind in A's increment --
lengths to the displacements, stresses to the stresses and contact pressures, forces to the
reactions and spring forces, anything else to itself -- so that a quantity that is zero up to
round-off (the slip of a frictionless patch test) is not measured against its own round-off.
State codes must be equal.
With --every N, B is A's run writing one increment in N (OPTIONS RESULTS N): B must hold exactly
A's increments n with n mod N = 0 and A's last one, and those are compared, each kind relative to
its largest magnitude over A's whole run (B's skipped increments may be summed in another order, so
its round-off is that of the run's increments, not of an increment whose field is near zero, such
as the end of an unloading).
Used for the MPI test (the serial run against `mpirun -np 2`).  Reads results through k2d.results
only (tools/ on PYTHONPATH).  Exit code 0 when they agree.
"""
import argparse
import sys

import numpy as np

from k2d.results import Result

COUNTS = ("increment", "deck_increment", "iterations", "repeats", "cuts", "converged", "invariant_violations")
FIELDS = ("displacement", "reaction", "stress_nodal", "stress_gauss")
# the kinds of quantity, each measured against the largest magnitude of its kind
KINDS = {"length": ("displacement", "contact/closure", "contact/slip", "contact/slip_gross",
                    "contact/slip_irreversible", "contact/effective_slip"),
         "stress": ("stress_nodal", "stress_gauss", "contact/pressure", "contact/shear"),
         "force": ("reaction", "contact/force_normal", "contact/force_tangential")}


def peak(x):
    x = np.asarray(x, dtype=float)
    return float(np.abs(x).max()) if x.size else 0.0


def worst_difference(a, b, scale):
    """max |a - b| / scale (absolute when the scale is zero); inf when the shapes differ."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    if a.shape != b.shape:
        return np.inf
    if a.size == 0:
        return 0.0
    d = np.abs(a - b).max()
    return d / scale if scale > 0 else d


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--rtol", type=float, default=1.0e-10)
    p.add_argument("--every", type=int, default=1, help="B writes one increment in N (OPTIONS RESULTS N)")
    args = p.parse_args()
    ra, rb = Result(args.a), Result(args.b)
    problems = []
    if ra.status != rb.status or (ra.completed != rb.completed and args.every == 1):
        problems.append(f"status {ra.status!r} ({ra.completed} increments) against {rb.status!r} "
                        f"({rb.completed} increments)")
    na = [s.number for s in ra.steps]
    nb = [s.number for s in rb.steps]
    if args.every > 1:
        # B keeps every N-th increment of A's and the last
        na = [n for n in na if n % args.every == 0 or n == na[-1]] if na else na
        if len(na) < 2:
            problems.append(f"{args.a} has too few increments to test RESULTS {args.every}")
    if na != nb:
        problems.append(f"increments {na} against {nb}")
    if not ra.steps:
        problems.append(f"no increments in {args.a}")
    worst, where, compared = 0.0, "", 0
    run_scales = {}
    if args.every > 1:
        for sa in ra.steps:
            ca = sa.contact_all()
            named = [(f, sa.field(f)) for f in FIELDS] + [("contact/" + k, ca[k]) for k in ca]
            for name, x in named:
                run_scales[name] = max(run_scales.get(name, 0.0), peak(x))
    for sa in ra.steps:
        if sa.number not in nb or sa.number not in na:
            continue
        sb = rb.step(sa.number)
        for k in COUNTS:
            if k in sa.attrs and sa.attrs.get(k) != sb.attrs.get(k):
                problems.append(f"increment {sa.number}: {k} {sa.attrs.get(k)} against {sb.attrs.get(k)}")
        arrays = [(f, sa.field(f), sb.field(f)) for f in FIELDS]
        ca, cb = sa.contact_all(), sb.contact_all()
        if sorted(ca) != sorted(cb):
            problems.append(f"increment {sa.number}: contact datasets {sorted(ca)} against {sorted(cb)}")
        arrays += [("contact/" + k, ca[k], cb[k]) for k in ca if k in cb]
        scales = {kind: max([run_scales.get(name, peak(x)) for name, x, _ in arrays if name in members] + [0.0])
                  for kind, members in KINDS.items()}
        for name, x, y in arrays:
            x, y = np.asarray(x), np.asarray(y)
            if x.dtype.kind in "iu":
                ok = x.shape == y.shape and np.array_equal(x, y)
                d = 0.0 if ok else np.inf
            else:
                kind = next((k for k, members in KINDS.items() if name in members), None)
                d = worst_difference(x, y, scales[kind] if kind else run_scales.get(name, peak(x)))
            compared += 1
            if not d <= args.rtol:
                problems.append(f"increment {sa.number}: {name} differs by {d:.3e} (relative) > {args.rtol:.1e}")
            if d > worst:
                worst, where = d, f"increment {sa.number} {name}"
    for msg in problems[:20]:
        print(msg)
    if problems:
        return 1
    print(f"agree: {len(na)} increment(s), {compared} arrays, worst relative difference {worst:.3e} "
          f"({where or 'none'}) <= {args.rtol:.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
