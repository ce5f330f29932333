"""The cost study: accuracy against cost over a matrix of models of three contact benchmarks
(docs/accuracy-and-stability.md, "Cost study"); tools/study.py is the command line and
describes the benchmarks, the matrix and the outputs.

    from k2d import study
    cases = study.reference_cases(quick) + study.matrix(quick, full, only)   # Case objects
    rows = study.run_pool(exe, out, cases, jobs, timeout)                     # {name: row of study.csv}
    study.attach_errors(rows, refs); study.write_csv(path, rows)
    study.chart(rows, png, benches); study.summary(rows, md, benches, refs)

Reads the results through k2d.results only.
"""
import math
import os
import time

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import examples as ex  # noqa: E402
from .analysis import contact_radius, radius_ideal  # noqa: E402
from .batch import parse_log, run_measured, run_parallel  # noqa: E402
from .results import Result  # noqa: E402
from .tables import write_dict_csv  # noqa: E402

__all__ = ["ELEMENTS", "SCHEMES", "P_SPHERE", "CN_ROUGH", "SPHERE_LEVELS", "PUNCH_LEVELS", "PUNCH_GRADE_RADIUS",
           "CYLINDER_LEVELS", "P_CYLINDER", "CN_CYLINDER", "BENCHES", "INCREMENTS", "AUTO_SCHEME", "SOLVER_SLICE",
           "BASELINE", "REFERENCES", "QUICK_REFERENCES", "TITLES", "ERROR_NAMES", "FIELDS", "DPI", "update_card",
           "write_deck", "Case", "read_h5", "measures", "IMBALANCE_LIMIT", "REPEAT_BELOW", "REPEATS", "run_case",
           "run_pool", "matrix", "reference_cases", "convergence_cases", "fnum", "attach_errors", "write_csv",
           "pareto", "ok_points", "label", "SCHEME_STYLE", "ELEMENT_STYLE", "clip", "chart", "pct", "summary",
           "convergence_table"]

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
        ex.sphere(path, P=P_SPHERE, cn=None if bench == "hertz_smooth" else CN_ROUGH, nnode=nnode, hdiv=hdiv,
                  nincs=nincs, update=update, options=options)
    elif bench == "cylinder":
        h = refdef["h"] if refdef is not None else CYLINDER_LEVELS[level] * (2.0 if nnode >= 8 else 1.0)
        ex.cylinder(path, P=P_CYLINDER, cn=CN_CYLINDER, nnode=nnode, h=h, nincs=nincs, update=update,
                    options=options)
    else:
        refine, factor = (refdef["refine"], refdef.get("factor")) if refdef is not None else PUNCH_LEVELS[level]
        kw = dict(column=2, nnode=nnode, refine=refine, nincs=nincs, update=update, options=options)
        if factor:
            ex.punch_graded(path, factor=factor, radius=PUNCH_GRADE_RADIUS, **kw)
        else:
            ex.punch(path, **kw)


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


def read_h5(h5):
    """What the error measures and the cost columns need, from the result file."""
    res = Result(h5)
    steps = res.steps
    r = {"status": res.status.strip(), "steps": len(steps),
         "solutions": int(sum(int(s.attrs["iterations"]) for s in steps)),
         "cuts": int(sum(int(s.attrs.get("cuts", 0)) for s in steps)),
         "law_drift": float(max([float(s.attrs.get("law_drift", 0.0)) for s in steps] or [0.0])),
         "imbalance": float(max([float(np.max(s.attrs["imbalance"])) for s in steps] or [0.0])),
         "violations": int(sum(int(s.attrs["invariant_violations"]) for s in steps))}
    if not steps:
        return r
    if res.contact is None:
        raise KeyError("%s holds no contact definition" % h5)
    x = res.contact.position[:, 0]
    o = np.argsort(x)
    last = res.last
    contact = last.contact_all()
    r["load_factor"] = float(last.load_factor[0])
    r["x"] = x[o]
    for key in ("pressure", "shear", "closure", "slip", "normal_state"):
        r[key] = contact[key][o]
    return r


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
    rad = radius_ideal if bench == "hertz_smooth" else contact_radius
    return float(np.max(r["pressure"])), rad(r["x"], r["closure"], r["normal_state"])


# a run that leaves a body out of equilibrium by more than this (relative to the load; the
# program warns above 1e-8, which round-off reaches on the largest condensed models) is not
# counted as a result
IMBALANCE_LIMIT = 1e-6
# runs cheaper than this (CPU s) are repeated, up to REPEATS times in all, and the least CPU
# and wall time kept: a short run's time is mostly noise of the machine
REPEAT_BELOW = 0.5
REPEATS = 3


def run_case(exe, out, c, timeout, repeats=REPEATS, keep=False):
    """Write the deck of case c, run it (repeated when it is cheap) and measure it: one row of
    study.csv.  The result file is deleted once read unless `keep` (hundreds of runs, the
    longest writing a gigabyte each)."""
    deck = os.path.join(out, "decks", c.name + ".dat")
    h5 = os.path.join(out, "h5", c.name + ".h5")
    log = os.path.join(out, "logs", c.name + ".log")
    write_deck(deck, c.bench, c.element, c.level, c.nincs, c.scheme, c.refdef)
    for stale in (h5, h5[:-3] + ".xdmf"):
        if os.path.exists(stale):
            os.remove(stale)
    rc, wall, cpu, rss = run_measured(exe, deck, h5, log, ["-s", c.solver], timeout)
    for _ in range(repeats - 1):
        if rc not in (0, 4) or cpu >= REPEAT_BELOW:
            break
        rc, wall2, cpu2, rss = run_measured(exe, deck, h5, log, ["-s", c.solver], timeout)
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
    if not keep:
        # hundreds of runs, the longest writing a gigabyte each: keep the deck and the log only
        for f in (h5, h5[:-3] + ".xdmf", h5[:-3] + ".lis"):
            if os.path.exists(f):
                os.remove(f)
    # exit code 4: completed with doubts (the paper's explicit scheme drifting off the law);
    # the study measures the error of such a run like any other
    done = (rc == 0 and r.get("status") == "completed") or (rc == 4 and str(r.get("status", "")).startswith("doubtful"))
    row["status"] = "ok" if done else "failed (exit %d)" % rc
    if row["status"] == "ok" and r.get("imbalance", 0.0) > IMBALANCE_LIMIT:
        row["status"] = "unbalanced"
    for key in ("solutions", "steps", "cuts", "law_drift", "imbalance", "violations"):
        row[key] = r.get(key, "")
    row["value_1"], row["value_2"] = measures(c.bench, r) if row["status"] in ("ok", "unbalanced") else \
        (float("nan"),) * 2
    row["h_min"] = float(np.min(np.diff(r["x"]))) if "x" in r and len(r["x"]) > 1 else float("nan")
    return row


def run_pool(exe, out, cases, jobs, timeout, repeats=REPEATS, keep=False):
    """Run the cases in `jobs` parallel runs, the biggest first; returns {case name: row}."""
    for sub in ("decks", "h5", "logs"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    rows = {}
    t0 = time.time()
    order = sorted(cases, key=lambda c: -c.cost_guess())
    for i, (c, row) in enumerate(run_parallel(lambda c: run_case(exe, out, c, timeout, repeats, keep), order,
                                              jobs), 1):
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
            a_h, p0_h, _ = ex.hertz_sphere(P_SPHERE)
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
    write_dict_csv(path, FIELDS, rows)


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
            a_h, p0_h, _ = ex.hertz_sphere(P_SPHERE)
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
        L += ["", "Best error per scheme and the CPU ratio it took:", "",
              "| scheme | best error | model | CPU / baseline |",
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
    a_h, p0_h, _ = ex.hertz_sphere(P_SPHERE)
    for r in out:
        if r["benchmark"] == "hertz_smooth":
            r["rel_1"], r["rel_2"] = fnum(r["value_1"]) / p0_h - 1.0, fnum(r["value_2"]) / a_h - 1.0
    keys = ["case", "benchmark", "element", "variant", "increments", "status", "h_min", "value_1", "value_2",
            "rel_1", "rel_2", "cpu_s", "solutions"]
    write_dict_csv(path, keys, out, fmt="%.7g")
    for r in out:
        print("%-48s %-8s v1 %.6g  v2 %.6g  cpu %.1f s" % (r["case"], r["status"][:6], fnum(r["value_1"]),
                                                          fnum(r["value_2"]), fnum(r["cpu_s"])))
