#!/usr/bin/python3
"""Parameter sweep: run variants of one deck as separate processes on every core, then tabulate.

    tools/sweep.py DECK PARAM VALUE [VALUE ...] [--out DIR] [--jobs N] [--solver NAME]
                   [--exe PATH] [--interface K]

PARAM names a field of a CONTACT card (docs/deck-format.md):

    c_n, m, c_n2, m2     NORMAL fields 1-4          R, S     TANGENT fields 1-2
    mu                   FRICTION field 2 (COULOMB MU, or FREDRIKSSON MU_M)
    kappa                HARDENING field 2
or CARD:FIELD for any keyword card of the CONTACT block, e.g. START:1 (the start pressure) or
AUGMENTED:1.  The field is rewritten in its ten columns (k2d.deck's F10 writer); the card must
be in the deck.  With several interfaces every one is changed, or only the K-th with
--interface K.

Each variant is written to OUT (default sweep_<deck>/) as <deck>_<PARAM>_<k>.dat, with a
relative GMSH path made absolute, and run there with k2d.build.run_deck (result file, listing
and terminal log beside it), --jobs at a time (default: every core; each run is one process on
one core, OPENBLAS_NUM_THREADS=1 unless set).  The summary (terminal and OUT/summary.csv) gives
per variant: exit code and status, increments completed, the largest contact pressure p = F/A
and the largest closure (the approach of the rough surfaces) of the last kept increment, the
solutions of the kept increments (all of them unless OPTIONS RESULTS thins the file), and the
CPU time of the run (user + system, from the operating system).
"""
import argparse
import concurrent.futures
import csv
import os
import re
import resource
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

import numpy as np  # noqa: E402

from k2d.build import find_or_build, run_deck  # noqa: E402
from k2d.deck import BLOCKS, f10, keyword  # noqa: E402
from k2d.results import Result  # noqa: E402

ALIASES = {"c_n": ("NORMAL", 1), "m": ("NORMAL", 2), "c_n2": ("NORMAL", 3), "m2": ("NORMAL", 4),
           "R": ("TANGENT", 1), "S": ("TANGENT", 2), "mu": ("FRICTION", 2), "kappa": ("HARDENING", 2)}
INTERFACE_CARDS = ("LAW", "UNITS", "NORMAL", "TANGENT", "FRICTION", "HARDENING", "SLIP", "SURFACE",
                   "MATCHING", "RIGID", "PAIRS", "TOLERANCE")


def parse_param(param):
    """(keyword, field) of PARAM: an alias or CARD:FIELD."""
    if param in ALIASES:
        return ALIASES[param]
    m = re.fullmatch(r"([A-Za-z]+):([1-9])", param)
    if not m:
        raise SystemExit(f"sweep: unknown parameter {param!r}: one of {', '.join(ALIASES)} or CARD:FIELD")
    return m.group(1).upper(), int(m.group(2))


def set_field(line, field, value):
    """The card with field `field` (columns 11 + 10 (field - 1) ...) set to `value`."""
    body, sep, comment = line.partition("#")
    body = body.rstrip("\n")
    a = 10 + 10 * (field - 1)
    body = body.ljust(a + 10)
    new = body[:a] + f10(value) + body[a + 10:]
    return new.rstrip() + ("   " + sep + comment if sep else "\n")


def variant(lines, deck_dir, kw, field, value, interface):
    """The deck's lines with the field changed (and a relative GMSH path made absolute);
    raises SystemExit when the card is not in the CONTACT block."""
    out, block, n_iface, changed = [], None, 1, 0
    content = False           # the current interface has cards (an INTERFACE card opens the next)
    for line in lines:
        k = keyword(line)
        if not line.startswith((" ", "#")) and k in BLOCKS:
            block = k
        if k == "GMSH":
            path = line[10:].split("#")[0].strip()
            if path and not os.path.isabs(path):
                line = line[:10] + os.path.normpath(os.path.join(deck_dir, path)) + "\n"
        if block == "CONTACT":
            if k == "INTERFACE":
                if content:
                    n_iface += 1
                content = False
            elif k in INTERFACE_CARDS:
                content = True
            if k == kw and (interface is None or n_iface == interface):
                line = set_field(line, field, value)
                changed += 1
        out.append(line)
    if not changed:
        where = f" of interface {interface}" if interface else ""
        raise SystemExit(f"sweep: no {kw} card in the CONTACT block{where} of the deck")
    return out


def summarize(h5):
    """Status, increments, max pressure, max closure (last kept increment), solutions."""
    r = Result(h5)
    row = {"status": r.status, "increments": r.completed}
    if not r.steps:
        return row
    last = r.last
    if r.contact is not None:
        row["max_pressure"] = float(np.max(last.contact("pressure")))
        row["max_closure"] = float(np.max(last.contact("closure")))
    row["solutions"] = int(np.nansum(r.history("iterations")))
    return row


def run_one(job):
    """Run one variant in this worker process; the CPU time of its child process from the
    difference of RUSAGE_CHILDREN (one child at a time per worker)."""
    exe, deck, h5, solver = job
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    extra = ["-s", solver] if solver else []
    rc = run_deck(exe, deck, h5, listing=os.path.splitext(h5)[0] + ".lis", quiet=False, extra=extra,
                  log=os.path.splitext(h5)[0] + ".log", cwd=os.path.dirname(h5))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return rc, cpu, time.time() - t0


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("deck")
    p.add_argument("param", help="c_n, m, c_n2, m2, R, S, mu, kappa, or CARD:FIELD")
    p.add_argument("values", type=float, nargs="+")
    p.add_argument("--out", help="folder of the variants and results (default sweep_<deck>)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="runs at a time (default: every core)")
    p.add_argument("--solver", help="override the deck's solver (skyline, umfpack, mumps, dense)")
    p.add_argument("--exe", help="the kontakt2d program (default: K2D_EXECUTABLE or build/kontakt2d)")
    p.add_argument("--interface", type=int, help="change only the K-th interface's card")
    args = p.parse_args()

    kw, field = parse_param(args.param)
    deck = os.path.abspath(args.deck)
    name = os.path.splitext(os.path.basename(deck))[0]
    out = os.path.abspath(args.out or f"sweep_{name}")
    os.makedirs(out, exist_ok=True)
    with open(deck) as f:
        lines = f.readlines()
    tag = re.sub(r"[^A-Za-z0-9]+", "_", args.param)
    jobs = []
    exe = find_or_build(args.exe)
    for k, v in enumerate(args.values, start=1):
        text = variant(lines, os.path.dirname(deck), kw, field, v, args.interface)
        path = os.path.join(out, f"{name}_{tag}_{k}.dat")
        with open(path, "w") as f:
            f.writelines(text)
        jobs.append((exe, path, os.path.splitext(path)[0] + ".h5", args.solver))

    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    print(f"sweep: {len(jobs)} runs of {os.path.basename(deck)} over {args.param} ({kw} field {field}), "
          f"{min(args.jobs, len(jobs))} at a time, in {out}", flush=True)
    t0 = time.time()
    with concurrent.futures.ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        results = list(pool.map(run_one, jobs))
    wall = time.time() - t0

    rows = []
    for (exe_, path, h5, _), v, (rc, cpu, elapsed) in zip(jobs, args.values, results):
        row = {"value": v, "rc": rc, "cpu_s": cpu, "wall_s": elapsed, "deck": os.path.basename(path)}
        if os.path.exists(h5):
            try:
                row.update(summarize(h5))
            except (OSError, KeyError) as e:
                row["status"] = f"unreadable: {e}"
        rows.append(row)

    head = f"{args.param:>12s} {'rc':>3s} {'status':>10s} {'incs':>5s} {'max p':>11s} {'max closure':>12s} " \
           f"{'solutions':>9s} {'CPU [s]':>8s}"
    print(head)
    for r in rows:
        def num(key, fmt):
            return format(r[key], fmt) if key in r else "-"
        print(f"{r['value']:12.5g} {r['rc']:3d} {str(r.get('status', '-')):>10s} {num('increments', '5d'):>5s} "
              f"{num('max_pressure', '11.4e'):>11s} {num('max_closure', '12.4e'):>12s} "
              f"{num('solutions', '9d'):>9s} {r['cpu_s']:8.2f}")
    fields = ["value", "rc", "status", "increments", "max_pressure", "max_closure", "solutions", "cpu_s",
              "wall_s", "deck"]
    with open(os.path.join(out, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print(f"{len(rows)} runs, {sum(r['cpu_s'] for r in rows):.1f} s CPU in {wall:.1f} s; "
          f"summary in {os.path.join(out, 'summary.csv')}")
    return 0 if all(r["rc"] == 0 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
