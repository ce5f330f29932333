#!/usr/bin/python3
"""Accuracy against cost: a matrix of models of three contact benchmarks, each run measured
for its error, CPU time, solutions and memory (docs/accuracy-and-stability.md, "Cost study").

    tools/study.py                 # the default matrix, about 17 minutes on 2 cores
    tools/study.py --quick         # a smoke test of the whole chain, under a minute
    tools/study.py --convergence   # the refinement sequences that justify the references
    tools/study.py --figures       # redraw the charts and tables from OUT/study.csv
    tools/study.py --full          # every model with both solvers (about twice the time)
    tools/study.py --keep          # keep the runs' HDF5 files (several GB; deleted once read by default)

Benchmarks (decks from tools/make_examples.py, the generators of the paper's examples):

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
Reads only what docs/results-format.md documents.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import make_examples as mx  # noqa: E402
from paper_figures import find_or_build  # noqa: E402  (build/kontakt2d, built if needed)

ELEMENTS = {"T3": 3, "Q4": 4, "Q8": 8, "Q9": 9}
SCHEMES = ["incremental", "newton", "automatic"]
P_SPHERE = 200.0                 # N, the load of both sphere benchmarks
CN_ROUGH = 0.8                   # um/(kgf/cm2)^0.5, m = 0.5 (example 5.2's rougher surface)
# mesh levels of the spheres: contact nodes a_H/5, a_H/10, a_H/20 apart (a quadratic
# element spans two node spacings, so its hdiv is half the linear element's)
SPHERE_LEVELS = {"L1": 5.0, "L2": 10.0, "L3": 20.0}
# mesh levels of the punch: the paper's mesh (13 contact nodes; T3/Q4 2.5 mm apart at the
# edge, Q8/Q9 4.17 mm) with every cell split k x k; "g": graded towards the punch corner
PUNCH_LEVELS = {"L1": (1, None), "L2": (2, None), "L3": (4, None),
                "L1g": (1, 0.25), "L2g": (2, 0.25), "L3g": (4, 0.25)}
PUNCH_GRADE_RADIUS = 25.0        # mm around the punch corner (50, 0)
# mesh levels of the cylinder: contact nodes 2, 1, 0.5 mm apart across the 25 mm annulus
CYLINDER_LEVELS = {"L1": 2.0, "L2": 1.0, "L3": 0.5}
P_CYLINDER = 1.0e5               # N (p_m = 16.98 N/mm2)
CN_CYLINDER = 0.44
BENCHES = ["hertz_smooth", "hertz_rough", "punch", "cylinder"]
INCREMENTS = {"hertz_smooth": [1, 5, 20], "hertz_rough": [1, 5, 20], "punch": [1, 5, 20, 80],
              "cylinder": [1, 5, 20, 80, 320]}
# the scheme under OPTIONS AUTOINC: the cuts act on a failed convergence test, which the
# rough law's explicit scheme does not have (it accepts every increment), so NEWTON; the
# ideal law iterates its multipliers to convergence under either scheme, and INCREMENTAL
# refactorizes only when a contact mode changes
AUTO_SCHEME = {"hertz_smooth": "INCREMENTAL", "hertz_rough": "NEWTON", "punch": "NEWTON", "cylinder": "NEWTON"}
# UMFPACK beside skyline for every element and level at one scheme and increment count
SOLVER_SLICE = {"hertz_smooth": ("newton", 5), "hertz_rough": ("newton", 5), "punch": ("newton", 20),
                "cylinder": ("newton", 5)}
# the settings of the example decks of inputs/ before this study (the baselines of the ratios)
BASELINE = {"hertz_smooth": ("Q4", "L2", 20, "newton", "skyline"),
            "hertz_rough": ("Q4", "L2", 20, "newton", "skyline"),
            "punch": ("Q4", "L1", 20, "incremental", "skyline"),
            "cylinder": ("Q4", "L2", 20, "incremental", "skyline")}
REFERENCES = {
    "hertz_rough": dict(element="Q8", hdiv=20.0, nincs=5, scheme="newton"),      # nodes a_H/40 apart
    "punch": dict(element="Q8", refine=4, factor=0.1, nincs=320, scheme="newton"),
    "cylinder": dict(element="Q8", h=0.25, nincs=640, scheme="newton"),              # nodes 0.125 mm apart
}
QUICK_REFERENCES = {
    "hertz_rough": dict(element="Q8", hdiv=5.0, nincs=1, scheme="newton"),
    "punch": dict(element="Q8", refine=2, factor=0.1, nincs=80, scheme="newton"),
    "cylinder": dict(element="Q8", h=2.0, nincs=20, scheme="newton"),
}
TITLES = {"hertz_smooth": "Hertz sphere, smooth (ideal law), P = 200 N",
          "hertz_rough": "Hertz sphere, rough c_n = 0.8, P = 200 N",
          "punch": "Punch, example 5.1 (rough, Coulomb 0.2)",
          "cylinder": "Rigid annulus, example 5.3, 100 kN, c_n = 0.44"}
ERROR_NAMES = {"hertz_smooth": ("peak pressure", "contact radius"),
               "hertz_rough": ("peak pressure", "contact radius"),
               "punch": ("edge pressure", "u_T at the edge"),
               "cylinder": ("pressure at R_A", "largest shear")}
FIELDS = ["benchmark", "element", "level", "graded", "increments", "scheme", "solver", "status", "error",
          "error_1", "error_2", "value_1", "value_2", "reference_1", "reference_2", "h_min", "cpu_s", "wall_s",
          "program_s", "maxrss_mb", "solutions", "steps", "cuts", "nodes", "equations", "pairs", "law_drift",
          "imbalance", "violations", "case"]
DPI = 80


# ============================================================================ decks
def update_card(bench, scheme):
    if scheme == "automatic":
        return AUTO_SCHEME[bench]
    return "NEWTON" if scheme == "newton" else "INCREMENTAL"


def write_deck(path, bench, element, level, nincs, scheme, refdef=None):
    """One deck of the matrix (or a reference / convergence run when refdef is given)."""
    nnode = ELEMENTS[element]
    update = update_card(bench, scheme)
    options = ["AUTOINC   ON"] if scheme == "automatic" else []
    if bench.startswith("hertz"):
        if refdef is not None:
            hdiv = refdef["hdiv"]
        else:
            hdiv = SPHERE_LEVELS[level] / (2.0 if nnode >= 8 else 1.0)
        mx.sphere(path, P=P_SPHERE, cn=None if bench == "hertz_smooth" else CN_ROUGH, nnode=nnode, hdiv=hdiv,
                  nincs=nincs, update=update, options=options)
    elif bench == "cylinder":
        h = refdef["h"] if refdef is not None else CYLINDER_LEVELS[level] * (2.0 if nnode >= 8 else 1.0)
        mx.cylinder(path, P=P_CYLINDER, cn=CN_CYLINDER, nnode=nnode, h=h, nincs=nincs, update=update,
                    options=options)
    else:
        refine, factor = (refdef["refine"], refdef.get("factor")) if refdef is not None else PUNCH_LEVELS[level]
        kw = dict(column=2, nnode=nnode, refine=refine, nincs=nincs, update=update, options=options)
        if factor:
            mx.punch_graded(path, factor=factor, radius=PUNCH_GRADE_RADIUS, **kw)
        else:
            mx.punch(path, **kw)


# ============================================================================ running
class Case:
    def __init__(self, bench, element, level, nincs, scheme, solver, name=None, refdef=None, role="matrix"):
        self.bench, self.element, self.level, self.nincs = bench, element, level, nincs
        self.scheme, self.solver, self.refdef, self.role = scheme, solver, refdef, role
        self.name = name or "%s_%s_%s_n%d_%s_%s" % (bench, element, level, nincs, scheme, solver)

    def cost_guess(self):
        """For the order of the runs only (big ones first keep the pool busy)."""
        lv = {"L1": 1, "L2": 4, "L3": 16, "L1g": 1, "L2g": 4, "L3g": 16}.get(self.level, 64)
        el = {"T3": 1.0, "Q4": 1.0, "Q8": 2.5, "Q9": 3.0}[self.element]
        return lv * el * (1.0 if self.bench.startswith("hertz") else 0.3 * max(self.nincs, 5) / 20.0)


GNU_TIME = "/usr/bin/time"


def run_kontakt(exe, deck, h5, log, solver, timeout):
    """Run kontakt2d on one deck; returns (exit code, wall s, user + system CPU s, max RSS MB).

    The CPU time is the rusage of the child (os.wait4: this process alone, whatever else
    runs).  The peak memory comes from GNU time (Debian package `time`) when it is there: a
    child forked from this Python process inherits its resident set in ru_maxrss, so the
    fallback, the child's own ru_maxrss, is only an upper bound."""
    cmd = [exe, deck, "-o", h5, "-s", solver]
    rss_file = log[:-4] + ".rss"
    if os.path.exists(GNU_TIME):
        cmd = [GNU_TIME, "-f", "%M", "-o", rss_file] + cmd
    with open(log, "w") as f:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT)
        timer = threading.Timer(timeout, lambda: os.kill(p.pid, signal.SIGKILL))
        timer.start()
        try:
            _, status, ru = os.wait4(p.pid, 0)      # the rusage of this child alone
        finally:
            timer.cancel()
        wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    rss = ru.ru_maxrss / 1024.0
    if cmd[0] == GNU_TIME:
        try:
            with open(rss_file) as f:
                rss = float(f.read().split()[-1]) / 1024.0
        except (OSError, ValueError, IndexError):
            pass
    return p.returncode, wall, ru.ru_utime + ru.ru_stime, rss


def parse_log(log):
    """Model size and the program's own timing from its terminal output."""
    out = {"nodes": "", "equations": "", "pairs": "", "program_s": ""}
    with open(log) as f:
        for line in f:
            m = re.match(r"\s*Nodes\s*:\s*(\d+)", line)
            if m:
                out["nodes"] = int(m.group(1))
            m = re.match(r"\s*Equations\s*:\s*(\d+)", line)
            if m:
                out["equations"] = int(m.group(1))
            m = re.match(r"\s*Contact\s*:\s*(\d+) pairs", line)
            if m:
                out["pairs"] = int(m.group(1))
            tok = line.split()
            if len(tok) >= 9 and tok[0].isdigit():
                try:
                    out["program_s"] = float(tok[-1])
                except ValueError:
                    pass
    return out


def read_h5(h5):
    """What the error measures and the cost columns need, from the result file."""
    with h5py.File(h5, "r") as f:
        status = f.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else str(status)
        incs = sorted(f["increments"])
        r = {"status": status.strip(), "steps": len(incs),
             "solutions": int(sum(int(f["increments"][k].attrs["iterations"]) for k in incs)),
             "cuts": int(sum(int(f["increments"][k].attrs.get("cuts", 0)) for k in incs)),
             "law_drift": float(max([float(f["increments"][k].attrs.get("law_drift", 0.0)) for k in incs] or [0.0])),
             "imbalance": float(max([float(np.max(f["increments"][k].attrs["imbalance"])) for k in incs] or [0.0])),
             "violations": int(sum(int(f["increments"][k].attrs["invariant_violations"]) for k in incs))}
        if not incs:
            return r
        x = f["contact"]["position"][:, 0]
        o = np.argsort(x)
        last = f["increments"][incs[-1]]
        r["load_factor"] = float(last.attrs["load_factor"][0])
        r["x"] = x[o]
        for key in ("pressure", "shear", "closure", "slip", "normal_state"):
            r[key] = last["contact"][key][...][o]
    return r


def radius_rough(x, u, st):
    """Rough law: where the closure of the outermost closed pair, interpolated linearly to the
    next pair, falls to zero (as docs/validation.md, example 5.2)."""
    k = np.where(st > 0)[0]
    if not len(k) or k.max() + 1 >= len(x):
        return float("nan")
    k = k.max()
    u0, u1 = u[k], u[k + 1]
    return float(x[k] + (x[k + 1] - x[k]) * u0 / (u0 - u1)) if u0 > u1 else float(x[k])


def radius_ideal(x, u, st):
    """Ideal law: the closure of a closed pair is zero (to the tolerance), so interpolating it
    says nothing.  Outside a smooth frictionless contact the gap grows like (r - a)^(3/2)
    (the pressure falls like (a - r)^(1/2)); the gaps g1, g2 of the first two open pairs
    r1 < r2 then give a = (r1 - q r2)/(1 - q), q = (g1/g2)^(2/3), kept between the last but
    one closed pair and the first open one (the last closed pair's force stands for its
    whole tributary zone, so the edge may lie before it)."""
    k = np.where(st > 0)[0]
    if not len(k) or k.max() + 2 >= len(x):
        return float("nan")
    k = k.max()
    g1, g2 = -u[k + 1], -u[k + 2]
    lo, hi = float(x[max(k - 1, 0)]), float(x[k + 1])
    if not (0.0 < g1 < g2):
        return 0.5 * float(x[k] + x[k + 1])
    q = (g1 / g2) ** (2.0 / 3.0)
    a = (x[k + 1] - q * x[k + 2]) / (1.0 - q)
    return float(min(max(a, lo), hi))


def measures(bench, r):
    """The two measured values of a benchmark: (peak pressure, contact radius) of a sphere,
    (pressure at the punch edge = its maximum, u_T at the edge in um) of the punch, (pressure
    at the outer edge R_A = its maximum, largest shear stress |p_T|) of the annulus."""
    if "x" not in r or r.get("load_factor", 0.0) < 1.0 - 1e-9:
        return float("nan"), float("nan")
    if bench == "punch":
        return float(np.max(r["pressure"])), 1e3 * float(r["slip"][-1])
    if bench == "cylinder":
        return float(r["pressure"][-1]), float(np.max(np.abs(r["shear"])))
    rad = radius_ideal if bench == "hertz_smooth" else radius_rough
    return float(np.max(r["pressure"])), rad(r["x"], r["closure"], r["normal_state"])


# a run that leaves a body out of equilibrium by more than this (relative to the load; the
# program warns above 1e-8, which round-off reaches on the largest condensed models) is not
# counted as a result
IMBALANCE_LIMIT = 1e-6
# runs cheaper than this (CPU s) are repeated, up to REPEATS times in all, and the least CPU
# and wall time kept: a short run's time is mostly noise of the machine
REPEAT_BELOW = 0.5
REPEATS = 3
# the result files of the runs are deleted once read, unless --keep
KEEP_RESULTS = False


def run_case(exe, out, c, timeout, repeats=REPEATS):
    deck = os.path.join(out, "decks", c.name + ".dat")
    h5 = os.path.join(out, "h5", c.name + ".h5")
    log = os.path.join(out, "logs", c.name + ".log")
    write_deck(deck, c.bench, c.element, c.level, c.nincs, c.scheme, c.refdef)
    for stale in (h5, h5[:-3] + ".xdmf"):
        if os.path.exists(stale):
            os.remove(stale)
    rc, wall, cpu, rss = run_kontakt(exe, deck, h5, log, c.solver, timeout)
    for _ in range(repeats - 1):
        if rc != 0 or cpu >= REPEAT_BELOW:
            break
        rc, wall2, cpu2, rss = run_kontakt(exe, deck, h5, log, c.solver, timeout)
        wall, cpu = min(wall, wall2), min(cpu, cpu2)
    row = {"benchmark": c.bench, "element": c.element, "level": c.level,
           "graded": int(c.level.endswith("g")) if c.role == "matrix" else "",
           "increments": c.nincs, "scheme": c.scheme, "solver": c.solver, "case": c.name,
           "cpu_s": cpu, "wall_s": wall, "maxrss_mb": rss}
    row.update(parse_log(log))
    r = {}
    if os.path.exists(h5):
        try:
            r = read_h5(h5)
        except (OSError, KeyError):
            r = {}
    if not KEEP_RESULTS:
        # hundreds of runs, the longest writing a gigabyte each: keep the deck and the log only
        for f in (h5, h5[:-3] + ".xdmf", h5[:-3] + ".lis"):
            if os.path.exists(f):
                os.remove(f)
    row["status"] = "ok" if rc == 0 and r.get("status") == "completed" else "failed (exit %d)" % rc
    if row["status"] == "ok" and r.get("imbalance", 0.0) > IMBALANCE_LIMIT:
        row["status"] = "unbalanced"
    for key in ("solutions", "steps", "cuts", "law_drift", "imbalance", "violations"):
        row[key] = r.get(key, "")
    row["value_1"], row["value_2"] = measures(c.bench, r) if row["status"] in ("ok", "unbalanced") else \
        (float("nan"),) * 2
    row["h_min"] = float(np.min(np.diff(r["x"]))) if "x" in r and len(r["x"]) > 1 else float("nan")
    return row


def run_pool(exe, out, cases, jobs, timeout, repeats=REPEATS):
    for sub in ("decks", "h5", "logs"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    rows = {}
    t0 = time.time()
    order = sorted(cases, key=lambda c: -c.cost_guess())
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(run_case, exe, out, c, timeout, repeats): c for c in order}
        for i, fut in enumerate(concurrent.futures.as_completed(futures), 1):
            c = futures[fut]
            row = fut.result()
            rows[c.name] = row
            print("[%4d/%d %6.0f s] %-52s %-6s cpu %7.2f s  %s" % (
                i, len(cases), time.time() - t0, c.name, row["status"][:6], row["cpu_s"],
                "p %.4g, %.4g" % (row["value_1"], row["value_2"])), flush=True)
    return rows


# ============================================================================ the matrix
def matrix(quick=False, full=False, only=None):
    cases = []
    for bench in BENCHES:
        if only and bench not in only:
            continue
        elements = ["Q4", "Q8"] if quick else list(ELEMENTS)
        levels = list(PUNCH_LEVELS) if bench == "punch" else ["L1", "L2", "L3"]
        if quick:
            levels = ["L1", "L1g"] if bench == "punch" else ["L1", "L2"]
        incs = INCREMENTS[bench][:2] if quick else INCREMENTS[bench]
        for el in elements:
            for lv in levels:
                for n in incs:
                    for sc in SCHEMES:
                        solvers = ["skyline"]
                        if full or (sc, n) == SOLVER_SLICE[bench]:
                            solvers.append("umfpack")
                        for so in solvers:
                            cases.append(Case(bench, el, lv, n, sc, so))
    return cases


def reference_cases(quick=False, only=None):
    refs = QUICK_REFERENCES if quick else REFERENCES
    out = []
    for bench, d in refs.items():
        if only and bench not in only:
            continue
        out.append(Case(bench, d["element"], "ref", d["nincs"], d["scheme"], "skyline",
                        name="%s_reference" % bench, refdef=d, role="reference"))
    return out


def convergence_cases(only=None):
    """The refinement sequences that show the references converged (--convergence)."""
    out = []

    def add(bench, tag, element, nincs, **d):
        d.update(element=element, nincs=nincs, scheme="newton")
        out.append(Case(bench, element, tag, nincs, "newton", "skyline", name="conv_%s_%s" % (bench, tag),
                        refdef=d, role="convergence"))
    if not only or "hertz_rough" in only or "hertz_smooth" in only:
        for el, hd in (("Q8", 5.0), ("Q8", 10.0), ("Q8", 20.0), ("Q4", 10.0), ("Q4", 20.0), ("Q4", 40.0)):
            add("hertz_rough", "%s_hdiv%g_n5" % (el, hd), el, 5, hdiv=hd)
        for n in (1, 20):
            add("hertz_rough", "Q8_hdiv10_n%d" % n, "Q8", n, hdiv=10.0)
        for el, hd in (("Q8", 10.0), ("Q8", 20.0), ("Q4", 40.0)):
            add("hertz_smooth", "%s_hdiv%g_n1" % (el, hd), el, 1, hdiv=hd)
    if not only or "punch" in only:
        for k in (2, 4, 8):
            add("punch", "Q8_r%d_g0.1_n40" % k, "Q8", 40, refine=k, factor=0.1)
        for k in (4, 8, 16):
            add("punch", "Q8_r%d_uniform_n40" % k, "Q8", 40, refine=k, factor=None)
        for n in (80, 160, 320, 640):
            add("punch", "Q8_r4_g0.1_n%d" % n, "Q8", n, refine=4, factor=0.1)
    if not only or "cylinder" in only:
        for h in (1.0, 0.5, 0.25, 0.125):
            add("cylinder", "Q4_h%g_n20" % h, "Q4", 20, h=h)
        for h in (2.0, 1.0, 0.5, 0.25, 0.125):
            add("cylinder", "Q8_h%g_n20" % h, "Q8", 20, h=h)
        for n in (80, 160, 320, 640):
            add("cylinder", "Q8_h1_n%d" % n, "Q8", n, h=1.0)
        for n in (320, 640):
            add("cylinder", "Q8_h0.25_n%d" % n, "Q8", n, h=0.25)
    return out


# ============================================================================ analysis
def fnum(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return float("nan")


def attach_errors(rows, refs):
    """Relative errors against the references; `error` is the larger of the two."""
    for row in rows:
        b = row["benchmark"]
        if b == "hertz_smooth":
            a_h, p0_h, _ = mx.hertz_sphere(P_SPHERE)
            r1, r2 = p0_h, a_h
        else:
            ref = refs.get(b)
            r1, r2 = (fnum(ref["value_1"]), fnum(ref["value_2"])) if ref else (float("nan"),) * 2
        row["reference_1"], row["reference_2"] = r1, r2
        e1 = abs(fnum(row["value_1"]) / r1 - 1.0)
        e2 = abs(fnum(row["value_2"]) / r2 - 1.0)
        row["error_1"], row["error_2"] = e1, e2
        row["error"] = max(e1, e2) if not (math.isnan(e1) or math.isnan(e2)) else float("nan")


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def pareto(points):
    """The points (cost, error, row) not beaten in both cost and error, by increasing cost
    (an error counts as lower when it is lower by more than 0.1 % of itself)."""
    front = []
    best = float("inf")
    for c, e, r in sorted(points, key=lambda p: (p[0], p[1])):
        if e < best * (1.0 - 1e-3):
            front.append((c, e, r))
            best = e
    return front


def ok_points(rows, bench):
    pts = []
    for r in rows:
        if r["benchmark"] != bench or r["status"] != "ok" or r.get("role", "matrix") != "matrix":
            continue
        e, c = fnum(r["error"]), fnum(r["cpu_s"])
        if not math.isnan(e):
            pts.append((c, e, r))
    return pts


def label(r):
    return "%s %s N=%s %s%s" % (r["element"], r["level"], r["increments"], r["scheme"],
                                "" if r["solver"] == "skyline" else " (UMFPACK)")


SCHEME_STYLE = {"incremental": ("tab:red", "o"), "newton": ("tab:blue", "s"), "automatic": ("tab:green", "^")}
ELEMENT_STYLE = {"T3": ("tab:orange", "v"), "Q4": ("tab:blue", "o"), "Q8": ("tab:purple", "s"),
                 "Q9": ("tab:brown", "D")}


def clip(e):
    return min(max(e, 1e-5), 1.0)


def chart(rows, path, benches):
    fig, axes = plt.subplots(len(benches), 2, figsize=(11, 3.6 * len(benches)), squeeze=False)
    for i, bench in enumerate(benches):
        pts = ok_points(rows, bench)
        for j, (key, styles) in enumerate((("scheme", SCHEME_STYLE), ("element", ELEMENT_STYLE))):
            ax = axes[i][j]
            for g, (col, mk) in styles.items():
                sel = [p for p in pts if p[2][key] == g]
                if not sel:
                    continue
                ax.scatter([p[0] for p in sel], [clip(p[1]) for p in sel], s=9, color=col, alpha=0.25,
                           marker=mk, linewidths=0)
                fr = pareto(sel)
                ax.step([p[0] for p in fr], [clip(p[1]) for p in fr], where="post", color=col, lw=1.3)
                ax.plot([p[0] for p in fr], [clip(p[1]) for p in fr], mk, color=col, ms=4, label=g)
            for tol in (0.01, 0.05):
                ax.axhline(tol, color="k", lw=0.6, ls=":")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("CPU time of the run [s]")
            ax.set_ylabel("error (larger of the two; >= 1 drawn at 1)")
            ax.set_title("%s: fronts per %s" % (TITLES[bench], key), fontsize=9)
            ax.grid(True, which="both", alpha=0.25)
            ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def pct(v):
    v = fnum(v)
    return "—" if math.isnan(v) else ("%.2g %%" % (100 * v) if v < 0.1 else "%.0f %%" % (100 * v))


def summary(rows, path, benches, refs):
    L = ["# Cost study: summary", "",
         "Written by tools/study.py. CPU times are ratios to the baseline of each benchmark (the",
         "setting of its example deck in inputs/ before the study), measured in the same run.", ""]
    for bench in benches:
        pts = ok_points(rows, bench)
        if not pts:
            continue
        bl = [p for p in pts if (p[2]["element"], p[2]["level"], int(p[2]["increments"]), p[2]["scheme"],
                                 p[2]["solver"]) == BASELINE[bench]]
        base, base_name = (bl[0][0], label(bl[0][2])) if bl else (min(p[0] for p in pts), "the fastest run")
        n1, n2 = ERROR_NAMES[bench]
        L += ["## " + TITLES[bench], ""]
        ref = refs.get(bench)
        if ref:
            L.append("Reference: %s (%s = %.6g, %s = %.6g)." % (ref["case"], n1, fnum(ref["value_1"]), n2,
                                                               fnum(ref["value_2"])))
        else:
            a_h, p0_h, _ = mx.hertz_sphere(P_SPHERE)
            L.append("Reference: Hertz, p0 = %.6g N/mm2, a = %.6g mm." % (p0_h, a_h))
        L.append("Baseline of the CPU ratios: %s (%.3g s CPU in this run)." % (base_name, base))
        failed = [r for r in rows if r["benchmark"] == bench and r["status"] != "ok"]
        L += ["Runs: %d; not counted (failed, or a body out of equilibrium by more than %g of the load): "
              "%d%s." % (len([r for r in rows if r["benchmark"] == bench]), IMBALANCE_LIMIT, len(failed),
                         (" (" + ", ".join("%s: %s" % (label(r), r["status"]) for r in failed[:10]) +
                          (", ..." if len(failed) > 10 else "") + ")") if failed else ""), ""]
        L += ["| target | cheapest model | %s | %s | error | CPU / baseline | solutions | "
              "as cheap within 20 %% (timing noise) |" % (n1, n2), "|---|---|---|---|---|---|---|---|"]
        for tol in (0.01, 0.05):
            good = sorted([p for p in pts if p[1] <= tol], key=lambda p: (p[0], p[1]))
            if good:
                c, e, r = good[0]
                near = ["%s (%s)" % (label(q[2]), pct(q[1])) for q in good[1:] if q[0] <= 1.2 * c][:4]
                L.append("| %s | %s | %s | %s | %s | %.2f | %s | %s |" % (pct(tol), label(r), pct(r["error_1"]),
                         pct(r["error_2"]), pct(e), c / base, r["solutions"], ", ".join(near) or "—"))
            else:
                L.append("| %s | none of the matrix | | | | | | |" % pct(tol))
        L += ["", "Pareto-optimal models (no other model is both cheaper and more accurate):", "",
              "| model | %s | %s | error | CPU / baseline | solutions | steps (cuts) | max RSS MB |" % (n1, n2),
              "|---|---|---|---|---|---|---|---|"]
        for c, e, r in pareto(pts):
            L.append("| %s | %s | %s | %s | %.3g | %s | %s (%s) | %.0f |" % (
                label(r), pct(r["error_1"]), pct(r["error_2"]), pct(e), c / base, r["solutions"], r["steps"],
                r["cuts"], fnum(r["maxrss_mb"])))
        L += ["", "Best error per scheme and the CPU ratio it took:", "", "| scheme | best error | model | CPU / baseline |",
              "|---|---|---|---|"]
        for sc in SCHEMES:
            sel = [p for p in pts if p[2]["scheme"] == sc]
            if sel:
                c, e, r = min(sel, key=lambda p: (p[1], p[0]))
                L.append("| %s | %s | %s | %.3g |" % (sc, pct(e), label(r), c / base))
        # solvers: UMFPACK against skyline on the same model
        pairs = {}
        for r in rows:
            if r["benchmark"] == bench and r["status"] == "ok":
                key = (r["element"], r["level"], r["increments"], r["scheme"])
                pairs.setdefault(key, {})[r["solver"]] = fnum(r["cpu_s"])
        ratios = {}
        for key, d in pairs.items():
            if "skyline" in d and "umfpack" in d:
                ratios.setdefault(key[1], []).append(d["umfpack"] / d["skyline"])
        if ratios:
            L += ["", "UMFPACK against skyline (CPU ratio on the same model; median and range over the elements):",
                  "", "| level | median | range | models |", "|---|---|---|---|"]
            for lv in sorted(ratios):
                v = ratios[lv]
                L.append("| %s | %.2f | %.2f – %.2f | %d |" % (lv, float(np.median(v)), min(v), max(v), len(v)))
        L.append("")
    with open(path, "w") as f:
        f.write("\n".join(L))
    return "\n".join(L)


def convergence_table(rows, path):
    """The refinement sequences, each value beside the finest of its kind."""
    out = []
    for r in rows:
        out.append({"case": r["case"], "benchmark": r["benchmark"], "element": r["element"],
                    "variant": r["level"], "increments": r["increments"], "status": r["status"],
                    "h_min": r["h_min"], "value_1": r["value_1"], "value_2": r["value_2"],
                    "cpu_s": r["cpu_s"], "solutions": r["solutions"]})
    a_h, p0_h, _ = mx.hertz_sphere(P_SPHERE)
    for r in out:
        if r["benchmark"] == "hertz_smooth":
            r["rel_1"], r["rel_2"] = fnum(r["value_1"]) / p0_h - 1.0, fnum(r["value_2"]) / a_h - 1.0
    with open(path, "w", newline="") as f:
        keys = ["case", "benchmark", "element", "variant", "increments", "status", "h_min", "value_1", "value_2",
                "rel_1", "rel_2", "cpu_s", "solutions"]
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in out:
            w.writerow({k: ("%.7g" % v if isinstance(v, float) else v) for k, v in r.items()})
    for r in out:
        print("%-48s %-8s v1 %.6g  v2 %.6g  cpu %.1f s" % (r["case"], r["status"][:6], fnum(r["value_1"]),
                                                          fnum(r["value_2"]), fnum(r["cpu_s"])))


# ============================================================================ main
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", help="the kontakt2d program (default: build/kontakt2d, built if needed)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "study"))
    ap.add_argument("-j", "--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--quick", action="store_true", help="a small matrix with cheap references (smoke test)")
    ap.add_argument("--full", action="store_true", help="both solvers for every model")
    ap.add_argument("--only", nargs="+", choices=BENCHES)
    ap.add_argument("--convergence", action="store_true", help="run the refinement sequences of the references")
    ap.add_argument("--figures", action="store_true", help="redraw from OUT/study.csv, run nothing")
    ap.add_argument("--no-docs", action="store_true", help="do not copy the results to docs/figures/")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds before a run is stopped")
    ap.add_argument("--keep", action="store_true", help="keep every run's HDF5 file and listing in OUT/h5")
    args = ap.parse_args(argv)
    global KEEP_RESULTS
    KEEP_RESULTS = args.keep
    os.makedirs(args.out, exist_ok=True)
    docs = None if (args.quick or args.no_docs) else os.path.join(ROOT, "docs", "figures")

    if args.convergence:
        exe = find_or_build(args.exe)
        rows = run_pool(exe, args.out, convergence_cases(args.only), args.jobs, args.timeout)
        path = os.path.join(args.out, "study_convergence.csv")
        convergence_table([rows[k] for k in sorted(rows)], path)
        if docs:
            shutil.copy(path, docs)
        return

    csv_path = os.path.join(args.out, "study.csv")
    if args.figures:
        rows = read_csv(csv_path)
    else:
        exe = find_or_build(args.exe)
        t0 = time.time()
        cases = reference_cases(args.quick, args.only) + matrix(args.quick, args.full, args.only)
        done = run_pool(exe, args.out, cases, args.jobs, args.timeout, 1 if args.quick else REPEATS)
        rows = []
        for c in cases:
            row = done[c.name]
            row["role"] = c.role
            rows.append(row)
        refs = {r["benchmark"]: r for r in rows if r["role"] == "reference"}
        attach_errors(rows, refs)
        rows = [dict(r, level=r["level"] if r["role"] == "matrix" else "reference") for r in rows]
        write_csv(csv_path, rows)
        print("%d runs in %.0f s of wall time" % (len(cases), time.time() - t0))
    for r in rows:
        r.setdefault("role", "reference" if r["level"] == "reference" else "matrix")
        if r["level"] == "reference":
            r["role"] = "reference"
    refs = {r["benchmark"]: r for r in rows if r["role"] == "reference"}
    benches = [b for b in BENCHES if any(r["benchmark"] == b for r in rows)]
    png = os.path.join(args.out, "study.png")
    chart(rows, png, benches)
    md = os.path.join(args.out, "study_summary.md")
    print(summary(rows, md, benches, refs))
    print("table: %s\nchart: %s\nsummary: %s" % (csv_path, png, md))
    if docs:
        for p in (csv_path, png, md):
            shutil.copy(p, docs)


if __name__ == "__main__":
    main()
