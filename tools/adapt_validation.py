#!/usr/bin/python3
"""Validation of tools/adapt.py on closed forms: Hertz and the flat punch (docs/adaptivity.md).

    tools/adapt_validation.py [--runs DIR] [--reuse] [--target T] [--max-dofs 100000]
                              [--md FILE] [--png FILE] [--exe KONTAKT2D]
                              [--growth G ...] [--growth-max-dofs 20000] [--contact-layer]
                              [--no-reference] [--scatter]

runs `tools/adapt.py DECK --compare` (adaptive against uniform remeshing) on the two decks of
inputs/adapt/ and measures every mesh of both sequences against the closed forms:

* hertz_adapt: an elastic cylinder (R = 15) on an elastic half-plane, plane strain, ideal
  frictionless contact, P' = 200 N/mm, E = 21000, nu = 0.3 for both: E* = E / (2 (1 - nu^2)),
  a = sqrt(4 P' R / (pi E*)), p0 = sqrt(P' E* / (pi R)) = 2 P' / (pi a) (Johnson, Contact
  Mechanics, 1985, sec. 4.2, eq. 4.43 - 4.45).  Measure: the peak pressure (the pair at x = 0).
* punch_flat: a flat punch of half width b = 1, 1000 times stiffer than the half-plane,
  frictionless, P' = 100 N/mm: p(x) = P' / (pi sqrt(b^2 - x^2)) (Sadowsky 1928; Johnson 1985,
  sec. 2.8, eq. 2.64), singular at the edge.  Measure: the edge pressure as the mean pressure
  over the outer tenth of the face, 0.9 b <= x <= b: (P' / pi) (pi/2 - asin 0.9) / (0.1 b)
  = 143.57 N/mm2 -- the singular peak itself has no finite value to converge to.  From the
  pairs: the normal forces of the pairs beyond 0.9 b, plus the pressure of the pair at 0.9 b
  (a node of every mesh: a point of the .geo) times half its outer edge.

* punch_flat_q8: the same punch with 8-node quadrilaterals (punch_flat_q8.geo includes
  punch_flat.geo and asks for incomplete second order).
* hertz_uniform: hertz_adapt's model from a uniform start mesh (one size, 3 mm, everywhere:
  about the DOFs of hertz_adapt's graded start), so that uniform refinement and the adaptive
  route start from the same mesh nobody graded by hand.

For each mesh: DOFs, the program's energy estimate, ||u_h||^2 (twice the strain energy, by the
Gauss rules), the measure's error against the closed form, CPU seconds (adapt.py's CSV).  The
exact energy ||u||^2 of the truncated bodies has no closed form: it is extrapolated from the
three finest uniform meshes, ||u||^2 - ||u_h||^2 = C N^-q (three equations for ||u||^2, C, q),
and the true relative energy error sqrt((||u||^2 - ||u_h||^2) / ||u||^2) (Galerkin
orthogonality; for contact with a converged contact zone) gives the effectivity estimate /
true.  That needs no initial gaps, so it serves the punch only; for every case the true error
is also measured directly against an overkill reference (REFERENCES: the same bodies on Q8
meshes refined by tools/adapt.py to an estimate of 0.02 - 0.05 %, run once into --runs),
||sigma_ref - sigma_h|| by the mesh's Gauss rules (k2d.adapt.reference_error), and against the
reference run's mesh before its last (the spread of the two effectivities is the reference's
uncertainty).  Rates: log(e_last / e_first) / log(N_last / N_first) over each sequence.
The report (Markdown) opens with the summary table of docs/adaptivity.md: per case the DOFs
each method needs for --tol (1 %) on its measure, interpolated log-log between the meshes
around it (extrapolated along the last two meshes' rate, and marked so, where the budget ended
a sequence first), the first mesh within --tol, and the ratios uniform / adaptive.
It goes to --md (default stdout) and the chart to --png.
With --growth G the adaptive route of each case is also run with at most G times the elements
per step (adapt.py --max-growth G) up to --growth-max-dofs: a finer sampling of the DOF axis,
where the default growth of 4 lets the measure's error fall by 5 - 30 times within one step and
the interpolation across that step overstates the DOFs to --tol; its table adds the first mesh
from which every later one is within --tol (the peak pressure is not monotone in the DOFs).
With --scatter only the study of the peak pressure's pair-to-pair scatter is run: Hertz with one
contact spacing (a/20 on the half-plane, 1, 0.8 and 0.5 times it on the cylinder) meshed by three
of gmsh's 2-D algorithms and with a boundary layer of quadrilaterals along the contact, the pairs
the same for each: every pair's F/A within 0.8 a against the mean of p0 sqrt(1 - x^2/a^2) over its
tributary zone.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

import numpy as np

from k2d import adapt as ad
from k2d.build import ROOT, find_or_build
from k2d.results import Result

NU = 0.3


def hertz_exact():
    E, R, P = 21000.0, 15.0, 200.0
    estar = E / (2.0 * (1.0 - NU ** 2))
    a = math.sqrt(4.0 * P * R / (math.pi * estar))
    return {"a": a, "p0": math.sqrt(P * estar / (math.pi * R))}


def punch_exact(b=1.0, P=100.0, band=0.1):
    force = P / math.pi * (0.5 * math.pi - math.asin(1.0 - band))
    return {"band_mean": force / (band * b), "band": band, "b": b}


def hertz_measure(r):
    p = r.last.contact("pressure")
    x = r.contact.position[:, 0]
    return float(p[np.argmin(np.abs(x))])


def punch_measure(r, b=1.0, band=0.1):
    last = r.last
    p, f = last.contact("pressure"), last.contact("force_normal")
    x = r.contact.position[:, 0]
    order = np.argsort(x)
    x, p, f = x[order], p[order], f[order]
    x0 = (1.0 - band) * b
    k = int(np.argmin(np.abs(x - x0)))
    if abs(x[k] - x0) > 1e-9 * b:
        raise ValueError("%s: no pair at x = %g" % (r.path, x0))
    # the pair at 0.9 b: the share of its force from its outer side, (x[k+1] - x[k]) / (x[k+1] - x[k-1])
    # of it (half its outer edge over half its two edges, for linear and quadratic edges alike)
    outer = (x[k + 1] - x[k]) / (x[k + 1] - x[k - 1])
    return float((np.sum(f[k + 1:]) + f[k] * outer) / (band * b))


CASES = {
    # energy=False: the contact's initial gaps make ||u||^2 - ||u_h||^2 no error measure (no Galerkin
    # orthogonality: the work of the load exceeds ||u_h||^2 by sum F_n g0, and MATCHING SEGMENT on
    # non-nested meshes is not conforming); the energies measured do not converge monotonically
    "hertz_adapt": dict(measure=hertz_measure, exact=lambda: hertz_exact()["p0"], label="Hertz peak pressure p0",
                        title="Hertz cylinder on a half-plane (Q4, plane strain)", energy=False, target=0.01,
                        reference="hertz_ref_q8"),
    # the same model from a uniform start mesh (one size everywhere, about the graded start's DOFs):
    # uniform refinement of a mesh nobody graded by hand against the adaptive route from the
    # same mesh
    "hertz_uniform": dict(measure=hertz_measure, exact=lambda: hertz_exact()["p0"],
                          label="Hertz peak pressure p0",
                          title="Hertz cylinder on a half-plane, uniform start mesh "
                          "(Q4, plane strain)",
                          energy=False, target=0.01, reference="hertz_ref_q8"),
    "punch_flat": dict(measure=punch_measure, exact=lambda: punch_exact()["band_mean"],
                       label="punch edge pressure (mean over 0.9b..b)",
                       title="Flat punch on a half-plane (Q4, plane strain)", energy=True, target=0.01,
                       reference="punch_ref_q8"),
    "punch_flat_q8": dict(measure=punch_measure, exact=lambda: punch_exact()["band_mean"],
                          label="punch edge pressure (mean over 0.9b..b)",
                          title="Flat punch on a half-plane (Q8, plane strain)", energy=True, target=0.002,
                          reference="punch_ref_q8"),
}

# The overkill references of the true energy-norm error (ReferenceField): each model's bodies on
# Q8 meshes refined adaptively by tools/adapt.py to an energy estimate far below the errors
# compared (run once, into --runs).  punch_ref_q8 is punch_flat_q8's deck run to a smaller target.
REFERENCES = {
    "hertz_ref_q8": dict(deck="hertz_ref_q8", target=0.0005, max_dofs=400000),
    "punch_ref_q8": dict(deck="punch_flat_q8", target=0.0007, max_dofs=400000),
}


def reference_fields(name, runs, exe, reuse):
    """(ReferenceField of the last mesh of the reference run `name`, that of the mesh before it,
    the two meshes' rows): the reference and the one that measures its uncertainty."""
    ref = REFERENCES[name]
    out = os.path.join(runs, name)
    csv_path = os.path.join(out, ref["deck"] + "_adapt.csv")
    if not reuse or not os.path.isfile(csv_path):
        subprocess.call([sys.executable, os.path.join(ROOT, "tools", "adapt.py"),
                         os.path.join(ROOT, "inputs", "adapt", ref["deck"] + ".dat"), "--target", str(ref["target"]),
                         "--max-dofs", str(ref["max_dofs"]), "-o", out, "--exe", exe])
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    if len(rows) < 2:
        raise SystemExit("adapt_validation: the reference run %s made fewer than two meshes" % out)
    fields = []
    for row in rows[-2:][::-1]:
        h5 = os.path.join(out, "steps_adaptive", "%s_%02d.h5" % (ref["deck"], int(row["step"])))
        fields.append(ad.ReferenceField(Result(h5)))
    return fields[0], fields[1], rows[-1], rows[-2]


def extrapolate(N, U):
    """U_inf, C, q with U_inf - U = C N^-q through three points (N ascending, U rising)."""
    N, U = np.asarray(N, float), np.asarray(U, float)
    ratio = (U[1] - U[0]) / (U[2] - U[1])

    def g(q):
        return (N[0] ** -q - N[1] ** -q) / (N[1] ** -q - N[2] ** -q) - ratio
    lo, hi = 1e-3, 5.0
    if g(lo) * g(hi) > 0:
        raise ValueError("no rate fits the energies %s at %s" % (U, N))
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    q = 0.5 * (lo + hi)
    C = (U[1] - U[0]) / (N[0] ** -q - N[1] ** -q)
    return float(U[2] + C * N[2] ** -q), float(C), q


def slope(N, e):
    """The overall rate from the first mesh to the last: log(e_last / e_first) / log(N_last / N_first)
    (adaptive meshes late in a sequence may hardly grow while their error falls, which makes
    slopes between neighbours meaningless)."""
    return float(math.log(e[-1] / e[0]) / math.log(N[-1] / N[0]))


def study(name, runs, target, max_dofs, exe, reuse, extra=(), reference=True):
    deck = os.path.join(ROOT, "inputs", "adapt", name + ".dat")
    out = os.path.join(runs, name)
    if not reuse or not os.path.isfile(os.path.join(out, name + "_adapt.csv")):
        subprocess.call([sys.executable, os.path.join(ROOT, "tools", "adapt.py"), deck, "--target",
                         str(target or CASES[name]["target"]),
                         "--compare", "--max-dofs", str(max_dofs), "-o", out, "--exe", exe] + list(extra))
    with open(os.path.join(out, name + "_adapt.csv")) as f:
        rows = list(csv.DictReader(f))
    mats = ad.deck_materials(deck)
    case = CASES[name]
    exact = case["exact"]()
    for row in rows:
        row["h5"] = os.path.join(out, "steps_" + row["method"], "%s_%02d.h5" % (name, int(row["step"])))
        r = Result(row["h5"])
        row["dofs"] = int(row["dofs"])
        row["est"] = float(row["estimated_error"])
        row["cpu"] = float(row["cpu_solve"])
        row["cpu_cum"] = float(row["cpu_cumulative"])
        row["U2"] = ad.energy_norm2(r, mats)
        row["value"] = case["measure"](r)
        row["err"] = abs(row["value"] - exact) / exact
    uni = [r for r in rows if r["method"] == "uniform"]
    ada = [r for r in rows if r["method"] == "adaptive"]
    Uinf, q, Uinf2, q2 = (float("nan"),) * 4
    if case["energy"]:
        Uinf, C, q = extrapolate([r["dofs"] for r in uni[-3:]], [r["U2"] for r in uni[-3:]])
        if len(ada) >= 3:       # the same from the adaptive meshes: the spread is the reference's uncertainty
            try:
                Uinf2, C2, q2 = extrapolate([r["dofs"] for r in ada[-3:]], [r["U2"] for r in ada[-3:]])
            except ValueError as e:     # the last adaptive meshes too alike in size to fit a rate
                print("adapt_validation: %s: no second reference (%s)" % (name, e), file=sys.stderr)
    if case.get("reference") and reference:
        fine, prev, frow, prow = REF_CACHE.get(case["reference"]) or reference_fields(case["reference"], runs, exe,
                                                                                     reuse)
        REF_CACHE[case["reference"]] = (fine, prev, frow, prow)
        for row in rows:
            r = Result(row["h5"])
            row["true_ref"] = ad.reference_error(r, mats, fine)[0]
            row["true_prev"] = ad.reference_error(r, mats, prev)[0]
    for row in rows:
        for key in ("ref", "prev"):
            t = row.get("true_" + key, float("nan"))
            row["true_" + key] = t
            row["eff_" + key] = row["est"] / t if t > 0 else float("nan")
    for row in rows:
        for key, ref in (("", Uinf), ("2", Uinf2)):
            d = ref - row["U2"]
            row["true" + key] = math.sqrt(d / ref) if d > 0 else float("nan")
            row["eff" + key] = row["est"] / row["true" + key] if d > 0 else float("nan")
    refinfo = REF_CACHE.get(case.get("reference"))
    return dict(name=name, case=case, exact=exact, rows=rows, uni=uni, ada=ada, Uinf=Uinf, q=q, Uinf2=Uinf2, q2=q2,
                ref=refinfo[2:] if refinfo else None)


REF_CACHE = {}


def first_within(rows, tol):
    return next((r for r in rows if r["err"] <= tol), None)


def dofs_at(rows, tol):
    """The DOFs at which the measure's error reaches tol, interpolated log-log between the two
    meshes around it (None when no mesh reached it)."""
    for a, b in zip(rows, rows[1:]):
        if a["err"] > tol >= b["err"]:
            t = math.log(tol / a["err"]) / math.log(b["err"] / a["err"])
            return math.exp(math.log(a["dofs"]) + t * math.log(b["dofs"] / a["dofs"]))
    return rows[0]["dofs"] if rows and rows[0]["err"] <= tol else None


def dofs_extrapolated(rows, tol):
    """Where no mesh reached tol: the DOFs at which the power law through the last two meshes'
    errors (err = C N^-r, r > 0) reaches it, with the rate r; None unless the last three meshes'
    errors fall (a sequence not yet in its asymptotic range extrapolates to nothing)."""
    if len(rows) < 3:
        return None
    z, a, b = rows[-3], rows[-2], rows[-1]
    if not (b["err"] < a["err"] < z["err"]) or not (z["dofs"] < a["dofs"] < b["dofs"]):
        return None
    r = math.log(a["err"] / b["err"]) / math.log(b["dofs"] / a["dofs"])
    return b["dofs"] * (b["err"] / tol) ** (1.0 / r), r


def summary(studies, tol):
    """The table of docs/adaptivity.md: per case the DOFs each method needs for tol, interpolated
    log-log between the meshes around it (extrapolated along the last two meshes' rate where the
    budget ended the sequence first, marked), the first mesh within tol, and the ratios."""
    md = ["| case | uniform: DOFs to %g %% (interpolated) | adaptive | uniform / adaptive "
          "| first mesh within %g %%: uniform | adaptive | uniform / adaptive |"
          % (100 * tol, 100 * tol),
          "|---|---|---|---|---|---|---|"]
    for s in studies:
        cells = []
        vals = []
        for rs in (s["uni"], s["ada"]):
            n = dofs_at(rs, tol)
            if n:
                cells.append("%.0f" % n)
                vals.append(n)
                continue
            ext = dofs_extrapolated(rs, tol)
            if ext:
                cells.append("≈ %.0f (extrapolated, N^−%.2f beyond %d)"
                             % (ext[0], ext[1], rs[-1]["dofs"]))
                vals.append(ext[0])
            elif rs:
                # not reached, not extrapolable: more than the largest mesh run
                cells.append("> %d (%.2f %% there)" % (rs[-1]["dofs"], 100 * rs[-1]["err"]))
                vals.append(-rs[-1]["dofs"])
            else:
                cells.append("—")
                vals.append(None)
        if all(v and v > 0 for v in vals):
            ratio = "%.2f" % (vals[0] / vals[1])
        elif vals[0] and vals[1] and vals[0] < 0 < vals[1]:
            ratio = "> %.2f" % (-vals[0] / vals[1])     # a lower bound: uniform needs more
        else:
            ratio = "—"
        fu, fa = first_within(s["uni"], tol), first_within(s["ada"], tol)
        md.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            s["name"], cells[0], cells[1], ratio,
            "%d" % fu["dofs"] if fu else "none within the budget",
            "%d" % fa["dofs"] if fa else "none within the budget",
            "%.2f" % (fu["dofs"] / fa["dofs"]) if fu and fa else "—"))
    return "\n".join(md) + "\n"


def report(studies, tol):
    md = [summary(studies, tol)]
    for s in studies:
        second = ("from the three last adaptive meshes %.7g, N^−%.2f: the second effectivity" % (s["Uinf2"], s["q2"])
                  if math.isfinite(s["Uinf2"]) else "none from the last adaptive meshes: too alike in size")
        ref = ("reference energy ‖u‖² = %.7g (extrapolated from the three finest uniform meshes, "
               "‖u‖² − ‖u_h‖² ∝ N^−%.2f; %s)" % (s["Uinf"], s["q"], second)) if s["case"]["energy"] else \
            "no extrapolated energy reference (the initial gaps: no Galerkin orthogonality)"
        if s["ref"]:
            fr, pr = s["ref"]
            ref += ("; true error against the overkill reference %s: its last mesh, %d DOFs (Q8), estimate "
                    "%.2g %% (the mesh before it, %d DOFs, estimate %.2g %%: the second effectivity)"
                    % (s["case"]["reference"], int(fr["dofs"]), 100 * float(fr["estimated_error"]),
                       int(pr["dofs"]), 100 * float(pr["estimated_error"])))
        md += ["#### %s" % s["case"]["title"], "",
               "Closed form: %s = %.5g N/mm²; %s." % (s["case"]["label"], s["exact"], ref), "",
               "| method | mesh | DOFs | estimate η | true energy error (reference) "
               "| effectivity (reference / the mesh before it) "
               "| effectivity, ‖u‖² extrapolated (uniform / adaptive) "
               "| measure | its error | CPU solve [s] | CPU cumulative [s] |",
               "|---|---|---|---|---|---|---|---|---|---|---|"]

        def f(v, fmt):
            return fmt % v if math.isfinite(v) else "—"
        for r in s["rows"]:
            md.append("| %s | %s | %d | %.4f | %s | %s / %s | %s / %s | %.5g | %.2f %% | %.2f | %.2f |" % (
                r["method"], r["step"], r["dofs"], r["est"], f(r["true_ref"], "%.4f"), f(r["eff_ref"], "%.2f"),
                f(r["eff_prev"], "%.2f"), f(r["eff"], "%.2f"), f(r["eff2"], "%.2f"), r["value"],
                100 * r["err"], r["cpu"], r["cpu_cum"]))
        md.append("")
        fa, fu = first_within(s["ada"], tol), first_within(s["uni"], tol)
        rates = []
        for method, rs in (("uniform", s["uni"]), ("adaptive", s["ada"])):
            fin = [r for r in rs if math.isfinite(r["true_ref"]) and r["true_ref"] > 0]
            txt = "%s: estimate ∝ N^%.2f" % (method, slope([r["dofs"] for r in rs], [r["est"] for r in rs])) \
                if len(rs) >= 2 else "%s: too few meshes" % method
            if len(fin) >= 2:
                txt += ", true energy error ∝ N^%.2f" % slope([r["dofs"] for r in fin], [r["true_ref"] for r in fin])
            if len(rs) >= 2:
                errs = [max(r["err"], 1e-12) for r in rs]
                txt += ", measure's error ∝ N^%.2f" % slope([r["dofs"] for r in rs], errs)
            rates.append(txt)
        md.append("Rates from the first mesh to the last: " + "; ".join(rates) + ".")
        md.append("")
        md.append("First mesh within %g %% of the closed form: adaptive %s, uniform %s%s." % (
            100 * tol, "%d DOFs (%.2f s cumulative CPU)" % (fa["dofs"], fa["cpu_cum"]) if fa else "none",
            "%d DOFs (%.2f s)" % (fu["dofs"], fu["cpu_cum"]) if fu else "none within the budget",
            " (uniform / adaptive = %.2f)" % (fu["dofs"] / fa["dofs"]) if fa and fu else ""))
        na, nu = dofs_at(s["ada"], tol), dofs_at(s["uni"], tol)
        md.append("")
        md.append("DOFs at %g %%, interpolated log-log between the meshes around it: adaptive %s, uniform %s%s." % (
            100 * tol, "%.0f" % na if na else "—", "%.0f" % nu if nu else "—",
            " (uniform / adaptive = %.2f)" % (nu / na) if na and nu else ""))
        md.append("")
    return "\n".join(md)


def stays_within(rows, tol):
    """The first mesh from which every later mesh of the sequence is within tol (None if none):
    the peak pressure of adaptive meshes is not monotone in the DOFs (the contact surface's node
    arrangement changes from mesh to mesh), so a single mesh within tol may be a lucky one."""
    for k, r in enumerate(rows):
        if all(x["err"] <= tol for x in rows[k:]):
            return r
    return None


def growth_study(name, runs, growth, max_dofs, exe, reuse, uniform_rows, tol, extra=()):
    """The adaptive route of `name` with at most `growth` times the elements per step (a finer
    sampling of its DOF axis than the default 4, which makes the measure's error fall by 5 - 30
    in one step), up to max_dofs: per mesh the DOFs, the estimate and the measure's error; the
    DOFs to tol interpolated, the first mesh within tol, the first from which all are within,
    and the ratios against the uniform sequence of the main study."""
    deck = os.path.join(ROOT, "inputs", "adapt", name + ".dat")
    out = os.path.join(runs, "%s_growth%g" % (name, growth))
    csv_path = os.path.join(out, name + "_adapt.csv")
    case = CASES[name]
    if not reuse or not os.path.isfile(csv_path):
        subprocess.call([sys.executable, os.path.join(ROOT, "tools", "adapt.py"), deck, "--target",
                         str(case["target"]), "--max-growth", str(growth), "--max-dofs", str(max_dofs),
                         "--max-steps", "12", "-o", out, "--exe", exe] + list(extra))
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    exact = case["exact"]()
    for row in rows:
        r = Result(os.path.join(out, "steps_adaptive", "%s_%02d.h5" % (name, int(row["step"]))))
        row["dofs"] = int(row["dofs"])
        row["est"] = float(row["estimated_error"])
        row["err"] = abs(case["measure"](r) - exact) / exact
    return dict(name=name, growth=growth, rows=rows, n_ada=dofs_at(rows, tol), first=first_within(rows, tol),
                stays=stays_within(rows, tol), n_uni=dofs_at(uniform_rows, tol),
                first_uni=first_within(uniform_rows, tol), stays_uni=stays_within(uniform_rows, tol))


def growth_report(gs, tol):
    md = ["| case | growth per step | adaptive meshes: DOFs (measure's error) | adaptive DOFs to %g %% "
          "(interpolated) / first within / all within from | uniform (main study) | uniform / adaptive "
          "(interpolated / first within / all within from) |" % (100 * tol),
          "|---|---|---|---|---|---|"]
    for g in gs:
        meshes = ", ".join("%d (%.2f %%)" % (r["dofs"], 100 * r["err"]) for r in g["rows"])

        def d(v):
            return "%.0f" % v if v else "—"

        def rr(u, a):
            return "%.2f" % (u / a) if u and a else "—"
        fa, sa = g["first"]["dofs"] if g["first"] else None, g["stays"]["dofs"] if g["stays"] else None
        fu, su = (g["first_uni"]["dofs"] if g["first_uni"] else None,
                  g["stays_uni"]["dofs"] if g["stays_uni"] else None)
        md.append("| %s | %g | %s | %s / %s / %s | %s / %s / %s | %s / %s / %s |" % (
            g["name"], g["growth"], meshes, d(g["n_ada"]), d(fa), d(sa), d(g["n_uni"]), d(fu), d(su),
            rr(g["n_uni"], g["n_ada"]), rr(fu, fa), rr(su, sa)))
    return "\n".join(md) + "\n"


# ---------------------------------------------------------------------- the peak pressure's scatter
# Hertz with one contact spacing along both surfaces (h_B = a/20 on the half-plane, h_A = ratio h_B
# on the cylinder), meshed by gmsh's 2-D algorithms 6 (Frontal-Delaunay, the .geo's), 5 (Delaunay)
# and 1 (MeshAdapt), and by algorithm 6 with a boundary layer of quadrilaterals along both contact
# curves (gmsh's BoundaryLayer field: first layer the curve's spacing, ratio 1.15, 8 spacings
# thick; "L"): the 1-D meshes of the curves, and with them the pairs, their weights, areas and
# gaps, are the same for every variant; only the bodies' elements under the contact differ.
SCATTER_RATIOS = (1.0, 0.8, 0.5)
SCATTER_ALGORITHMS = (6, 5, 1, "L")
SCATTER_ZONE = 0.8          # the pairs within 0.8 a: the ellipse's slope is moderate there


def tributary_ellipse(x, a, p0, npts=16):
    """Hertz's pressure p0 sqrt(1 - s^2/a^2) averaged over the tributary zone of every pair at the
    sorted positions x (the hat function of its node on the segments to its neighbours; the first
    and last pair one-sided): what F/A of a pair is when the discrete pressure is exact.  Gauss-
    Legendre with npts points per segment (the segments within 0.8 a: a smooth integrand)."""
    x = np.asarray(x, float)
    g, w = np.polynomial.legendre.leggauss(npts)
    out = np.empty_like(x)
    for i in range(len(x)):
        num = den = 0.0
        for j in (i - 1, i + 1):
            if j < 0 or j >= len(x):
                continue
            lo, hi = sorted((x[i], x[j]))
            s = 0.5 * (lo + hi) + 0.5 * (hi - lo) * g
            hat = 1.0 - np.abs(s - x[i]) / (hi - lo)
            p = p0 * np.sqrt(np.clip(1.0 - (s / a) ** 2, 0.0, None))
            num += 0.5 * (hi - lo) * np.sum(w * hat * p)
            den += 0.5 * (hi - lo) * np.sum(w * hat)
        out[i] = num / den
    return out


def scatter_geo(text, h_a, h_b, algorithm):
    """hertz_adapt.geo with the sizes h_a (the cylinder's contact arc) and h_b (the half-plane's
    contact line) at both ends of the contact curves, and gmsh's 2-D algorithm (an int), or "L":
    the .geo's algorithm and a boundary layer of quadrilaterals along both contact curves."""
    layer = algorithm == "L"
    if layer:
        algorithm = 6
    subs = [("Point(1) = {0, 0, 0, h_c};", "Point(1) = {0, 0, 0, %r};" % h_a),
            ("Point(2) = {c, yc, 0, h_e};", "Point(2) = {c, yc, 0, %r};" % h_a),
            ("Point(11) = {0, 0, 0, h_c};", "Point(11) = {0, 0, 0, %r};" % h_b),
            ("Point(12) = {c, 0, 0, h_e};", "Point(12) = {c, 0, 0, %r};" % h_b),
            ("Mesh.Algorithm = 6;", "Mesh.Algorithm = %d;" % algorithm)]
    for old, new in subs:
        if old not in text:
            raise SystemExit("adapt_validation: hertz_adapt.geo has no line %r" % old)
        text = text.replace(old, new)
    if layer:
        for k, (curve, h) in enumerate((("1", h_a), ("11", h_b)), start=1):
            text += ("\nField[%d] = BoundaryLayer; Field[%d].CurvesList = {%s}; Field[%d].Size = %r;\n"
                     "Field[%d].Ratio = 1.15; Field[%d].Quads = 1; Field[%d].Thickness = %r;\n"
                     "BoundaryLayer Field = %d;\n" % (k, k, curve, k, h, k, k, k, 8 * h, k))
    return text


def scatter_run(runs, exe, ratio, algorithm):
    """One scatter mesh: gmsh, kontakt2d, and per pair within SCATTER_ZONE a the error of F/A
    against the tributary mean of the ellipse.  Returns a dict with the contact definition."""
    ex = hertz_exact()
    a, p0 = ex["a"], ex["p0"]
    h_b = a / 20.0
    out = os.path.join(runs, "scatter", "r%.2f_alg%s" % (ratio, algorithm))
    os.makedirs(out, exist_ok=True)
    src = os.path.join(ROOT, "inputs", "adapt", "hertz_adapt")
    with open(src + ".geo") as f:
        geo = scatter_geo(f.read(), ratio * h_b, h_b, algorithm)
    with open(os.path.join(out, "hertz.geo"), "w") as f:
        f.write(geo)
    with open(src + ".dat") as f:
        deck = f.read().replace("hertz_adapt.msh", "hertz.msh")
    with open(os.path.join(out, "hertz.dat"), "w") as f:
        f.write(deck)
    base = os.path.join(out, "hertz")
    subprocess.run(["gmsh", "-2", "-format", "msh41", base + ".geo", "-o", base + ".msh"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    subprocess.run([exe, base + ".dat", "-o", base + ".h5", "-l", base + ".lis", "-q"], check=True)
    r = Result(base + ".h5")
    x = r.contact.position[:, 0]
    order = np.argsort(x)
    x, p = x[order], r.last.contact("pressure")[order]
    zone = x < SCATTER_ZONE * a
    err = p[zone] / tributary_ellipse(x, a, p0)[zone] - 1.0
    if np.count_nonzero(zone) < 5:
        raise SystemExit("adapt_validation: %s has %d pairs within %g a" % (base, np.count_nonzero(zone),
                                                                          SCATTER_ZONE))
    contact = {k: np.asarray(getattr(r.contact, k)) for k in ("node_a", "master_nodes", "master_weights",
                                                              "area", "gap")}
    return dict(ratio=ratio, algorithm=algorithm, spacing=float(np.median(np.diff(x[zone]))),
                axis=100.0 * (p[0] / p0 - 1.0), err=100.0 * err, contact=contact)


def scatter_report(runs, exe):
    """The table of docs/adaptivity.md, "The peak pressure's scatter": per spacing ratio and gmsh
    algorithm the axis pair's error against p0, the rms and largest pair error e against the
    tributary mean of the ellipse, the rms of e's second difference (the pair-to-pair part, which
    a smooth error profile has not), and whether the pairing is identical across the algorithms."""
    md = ["| h_A / h_B | gmsh algorithm | pairs within 0.8 a | spacing h_A [mm] | axis pair against p0 | "
          "rms of the pairs against the ellipse | largest | pair to pair: rms of e_i - (e_i-1 + e_i+1)/2 | "
          "pairing the same as algorithm %d's |" % SCATTER_ALGORITHMS[0], "|---|---|---|---|---|---|---|---|---|"]
    for ratio in SCATTER_RATIOS:
        first = None
        for alg in SCATTER_ALGORITHMS:
            s = scatter_run(runs, exe, ratio, alg)
            first = first or s
            same = all(first["contact"][k].shape == s["contact"][k].shape
                       and np.array_equal(first["contact"][k], s["contact"][k]) for k in s["contact"])
            e = s["err"]
            jump = e[1:-1] - 0.5 * (e[:-2] + e[2:])
            md.append("| %.2f | %s | %d | %.4f | %+.2f %% | %.2f %% | %.2f %% | %.2f %% | %s |" % (
                ratio, "6 + boundary layer" if alg == "L" else alg, len(e), s["spacing"], s["axis"],
                math.sqrt(np.mean(e ** 2)), np.max(np.abs(e)), math.sqrt(np.mean(jump ** 2)),
                "yes" if same else "no"))
    return "\n".join(md) + "\n"


def plot(studies, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(studies), figsize=(5.5 * len(studies), 4.2))
    for ax, s in zip(np.atleast_1d(axes), studies):
        for method, rs, c in (("uniform", s["uni"], "C0"), ("adaptive", s["ada"], "C1")):
            N = [r["dofs"] for r in rs]
            ax.loglog(N, [r["est"] for r in rs], "o-", color=c, label="%s: estimate η" % method)
            fin = [r for r in rs if math.isfinite(r["true_ref"])]
            ax.loglog([r["dofs"] for r in fin], [r["true_ref"] for r in fin], "s--", color=c, mfc="none",
                      label="%s: true energy error" % method)
            ax.loglog(N, [max(r["err"], 1e-5) for r in rs], "^:", color=c, label="%s: %s" % (method, "measure's error"))
        ax.axhline(0.01, color="k", lw=0.8, ls="--")
        ax.set_title(s["case"]["title"], fontsize=10)
        ax.set_xlabel("DOFs")
        ax.set_ylabel("relative error")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", default=os.path.join(ROOT, "results", "adapt_validation"))
    ap.add_argument("--reuse", action="store_true", help="read the runs already in --runs")
    ap.add_argument("--target", type=float, default=None,
                    help="estimate to refine to (default per deck: 0.01 for Q4, 0.002 for Q8; docs/adaptivity.md)")
    ap.add_argument("--max-dofs", type=int, default=100000)
    ap.add_argument("--tol", type=float, default=0.01, help="accuracy asked of the measures (default 1 %%)")
    ap.add_argument("--md", default=None)
    ap.add_argument("--png", default=os.path.join(ROOT, "docs", "figures", "adapt_validation.png"))
    ap.add_argument("--exe", default=None)
    ap.add_argument("--cases", nargs="*", default=list(CASES), choices=list(CASES))
    ap.add_argument("--growth", type=float, nargs="*", default=[],
                    help="also run the adaptive route with at most this growth of the elements per step "
                    "(e.g. 1.5), up to --growth-max-dofs, for the DOFs to --tol")
    ap.add_argument("--growth-max-dofs", type=int, default=20000)
    ap.add_argument("--contact-layer", action="store_true",
                    help="the adaptive routes with tools/adapt.py --contact-layer (the references and "
                    "the uniform routes as they are)")
    ap.add_argument("--no-reference", action="store_true",
                    help="no true errors against the overkill references (their fits to every Gauss "
                    "point of every mesh take most of the time): the ratios and the measures only")
    ap.add_argument("--scatter", action="store_true",
                    help="only the study of the peak pressure's scatter: Hertz at one contact spacing, "
                    "three spacing ratios of the surfaces, three gmsh algorithms (docs/adaptivity.md)")
    args = ap.parse_args(argv)
    exe = find_or_build(args.exe)
    if args.scatter:
        if shutil.which("gmsh") is None:
            raise SystemExit("adapt_validation: --scatter needs gmsh (Debian package gmsh)")
        text = scatter_report(args.runs, exe)
        if args.md:
            with open(args.md, "w") as f:
                f.write(text)
        else:
            print(text)
        return 0
    extra = ["--contact-layer"] if args.contact_layer else []
    studies = [study(n, args.runs, args.target, args.max_dofs, exe, args.reuse, extra, not args.no_reference)
               for n in args.cases]
    text = report(studies, args.tol)
    if args.growth:
        gs = [growth_study(s["name"], args.runs, g, args.growth_max_dofs, exe, args.reuse, s["uni"], args.tol,
                           extra)
              for g in args.growth for s in studies]
        text += "\n#### The adaptive route sampled more finely (--max-growth)\n\n" + growth_report(gs, args.tol)
    if args.md:
        with open(args.md, "w") as f:
            f.write(text + "\n")
    else:
        print(text)
    plot(studies, args.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
