"""Compare two runs of a joint: a deck against a variant of itself (one card changed: the
interface law, or the contact scheme), or two decks.  tools/compare.py is the command line.

    from k2d.compare import vary_deck, compare_runs
    text = vary_deck(open("punch.dat").read(), "LAW", "IDEAL")     # the deck with LAW IDEAL
    report = compare_runs([("rough", "a.dat"), ("ideal", "b.dat")], "out/", exe)

Each run is a separate kontakt2d process (CPU time: the rusage of that process).  The report
(Markdown, out/report.md, with PNG figures beside it and the figures as JSON in
out/report.json) holds per run: status, increments, solutions, CPU time, and at like states
(the last increments when both reached the same load factors along the same load path, else the
last state both reached -- a failed run -- or a note that none exists) the peak pressure,
contact width and area, approach, total normal and tangential force, the tangential
displacements (mean and largest u_T, largest irreversible slip), closed and slipping pairs,
worst law drift; the differences of the second run from the first in per cent where both
values are above round-off (ROUND_OFF of the run's scale), else absolute; figures of the
pressure and shear along the interface overlaid (at the compared state, and at the peak load
when the history unloads), approach and peak pressure against the load factor, slipping
pairs, mean u_T and total F_T, law drift and solutions per increment.  A failed run is named
in the report and report.json ("failed").  The figures are those
of k2d.history; the results are read through k2d.results only.
"""
import json
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .batch import run_measured  # noqa: E402
from .deck import BLOCKS, keyword  # noqa: E402
from .history import History, unit_labels  # noqa: E402
from .results import Result  # noqa: E402
from .terminal import read_terminal  # noqa: E402

__all__ = ["VARY", "CompareError", "parse_vary", "vary_deck", "run_totals", "failed", "path_lengths", "like_states",
           "run_figures", "ROUND_OFF", "pct", "difference", "ROWS", "shown_path", "compare_runs"]

VARY = {
    "LAW": {"ROUGH": "ROUGH", "IDEAL": "IDEAL"},
    "SCHEME": {"INCREMENTAL": "INCREMENTAL", "EXPLICIT": "INCREMENTAL", "NEWTON": "NEWTON",
               "RETURN": "NEWTON", "MODIFIED": "MODIFIED"},
}


class CompareError(Exception):
    """A bad request: the message names what was expected and what was found."""


def parse_vary(text):
    """KEY=VALUE of --vary, checked: (KEY, VALUE) with the value in its canonical spelling."""
    if "=" not in text:
        raise CompareError("--vary: expected KEY=VALUE (LAW=ROUGH|IDEAL or SCHEME=INCREMENTAL|NEWTON|MODIFIED), "
                           "found %r" % text)
    key, value = (t.strip().upper() for t in text.split("=", 1))
    if key not in VARY:
        raise CompareError("--vary: unknown card %r; expected LAW or SCHEME" % key)
    if value not in VARY[key]:
        raise CompareError("--vary %s: unknown value %r; expected %s" % (key, value, " or ".join(sorted(VARY[key]))))
    return key, VARY[key][value]


def vary_deck(text, key, value, name="deck"):
    """The deck `text` with the card KEY set to VALUE in its CONTACT block: LAW on every
    interface (cards before the first INTERFACE card open interface 1), SCHEME (or its synonym
    UPDATE) once for the block.  CompareError when the deck has no CONTACT block."""
    lines = text.splitlines(keepends=True)
    try:
        start = next(i for i, ln in enumerate(lines) if keyword(ln) == "CONTACT" and not ln.startswith("#"))
    except StopIteration:
        raise CompareError("%s: no CONTACT block, nothing to vary with %s" % (name, key)) from None
    end = next((i for i in range(start + 1, len(lines)) if keyword(lines[i]) in BLOCKS), len(lines))
    drop = ("LAW",) if key == "LAW" else ("SCHEME", "UPDATE")
    body = [ln for ln in lines[start + 1:end] if keyword(ln) not in drop]
    card = "%-10s%s\n" % (key, value)
    out = []
    if key == "SCHEME":
        out = [card] + body
    else:
        first = next((ln for ln in body if ln.strip() and not ln.lstrip().startswith("#")), "")
        if keyword(first) != "INTERFACE":
            out.append(card)
        for ln in body:
            out.append(ln)
            if keyword(ln) == "INTERFACE":
                out.append(card)
    return "".join(lines[:start + 1] + out + lines[end:])


def run_totals(log):
    """(solutions, increments) of the whole run from the program's terminal output (its summary
    line "N solutions in M increments"), or None when the log has no such line."""
    t = read_terminal(log)
    return t["totals"] if t else None


def failed(fig):
    """True for a run that failed (exit code other than 0 or 4, or a status "failed ...")."""
    return fig.get("exit_code") not in (0, 4) or str(fig.get("status", "")).startswith("failed")


def path_lengths(res):
    """(nsteps) the load path length of every kept increment: the sum over the increments from
    zero of the change of the load factors (1-norm over the cases).  Two states with equal load
    factors and equal path lengths are like states: the same point of the same load history
    (a cycle passes a load factor several times, at different path lengths)."""
    lf = res.load_factors()
    if not len(lf):
        return np.zeros(0)
    return np.cumsum(np.abs(np.diff(np.vstack([np.zeros((1, lf.shape[1])), lf]), axis=0)).sum(axis=1))


def like_states(res_a, res_b, rtol=1e-9):
    """(step index in a, step index in b, note) of the states to compare: the last increments
    when they are like states (equal load factors and load path lengths to rtol of the largest
    factor, path), else the latest state of a that b also reached (the note says so), else the
    last increments with a note that no like state exists (then no differences are given)."""
    la, lb = res_a.load_factors(), res_b.load_factors()
    sa, sb = path_lengths(res_a), path_lengths(res_b)
    if la.shape[1] != lb.shape[1]:
        return len(la) - 1, len(lb) - 1, ("no like states: the runs have %d and %d load cases; the figures are "
                                          "at their last increments and no differences are given"
                                          % (la.shape[1], lb.shape[1]))
    scale = max(1.0, np.max(np.abs(la)), np.max(np.abs(lb)), sa[-1], sb[-1])
    tol = rtol * scale

    def match(i):
        d = np.max(np.abs(lb - la[i]), axis=1) + np.abs(sb - sa[i])
        j = int(np.argmin(d))
        return j if d[j] <= tol else None

    if match(len(la) - 1) == len(lb) - 1:
        return len(la) - 1, len(lb) - 1, None
    for i in range(len(la) - 1, -1, -1):
        j = match(i)
        if j is not None:
            return i, j, "like states: the last state both runs reached"
    return len(la) - 1, len(lb) - 1, ("no like states: no increment of the second run has the load factors "
                                      "and load path of one of the first; the figures are at the last "
                                      "increments and no differences are given")


def run_figures(h5, cpu, wall, rc, approach_nodes=None, log=None, step=None):
    """The figures of one run (a dict), from its result file (and the totals of its log), at the
    step index `step` (default: the last kept increment)."""
    res = Result(h5)
    f = {"exit_code": rc, "status": res.status, "kept": len(res.steps), "cpu_s": cpu, "wall_s": wall,
         "solutions": int(np.nansum(res.history("iterations"))) if res.steps else 0, "increments": res.completed}
    totals = run_totals(log) if log else None
    if totals:
        f["solutions"], f["increments"] = totals
    if res.contact is None or not res.steps:
        return f
    h = History(res, approach_nodes=approach_nodes)
    k = len(h.steps) - 1 if step is None else step
    last = h.figures(k)
    drift = res.history("law_drift")
    f.update({key: last[key] for key in ("load_factor", "peak_pressure", "width", "area", "approach", "normal_force",
                                         "tangential_force", "slipping", "closed", "mean_slip", "max_slip",
                                         "max_irreversible")})
    f["increment"] = h.steps[k].number
    f["load_factors"] = " ".join("%.6g" % v for v in h.steps[k].load_factor)
    f["peak_at"] = list(last["peak_at"])
    f["worst_drift"] = float(np.nanmax(drift)) if np.isfinite(drift).any() else float("nan")
    # the run's scales, below which a figure is round-off (ROUND_OFF of them)
    figs = [h.figures(i) for i in range(len(h.steps))]
    fmax = max(max(abs(v["normal_force"]) for v in figs), max(abs(v["tangential_force"]) for v in figs))
    lmax = max(max(abs(v["approach"]) for v in figs), max(abs(v["max_slip"]) for v in figs),
               max(v["max_closure"] for v in figs), max(v["width"] for v in figs))
    f["scale"] = {"force": fmax, "length": lmax, "stress": max(v["peak_pressure"] for v in figs),
                  "area": max(v["area"] for v in figs)}
    return f


ROUND_OFF = 1e-9      # a figure below this fraction of its run's scale is round-off (no per cent of it)


def pct(a, b, floor=0.0):
    """Difference of b from a in per cent; '' when either is missing, or either is at most
    `floor` in magnitude (round-off: a per cent of it means nothing)."""
    try:
        a, b = float(a), float(b)
    except (TypeError, ValueError):
        return ""
    if math.isnan(a) or math.isnan(b) or abs(a) <= floor or abs(b) <= floor or a == 0.0:
        return ""
    return "%+.3g %%" % (100.0 * (b / a - 1.0))


def difference(a, b, floor, fmt):
    """The difference column: "equal" for equal values, per cent where both values are above
    round-off (`floor`), the absolute difference where one is not and they differ by more than
    it, "equal to round-off" where they differ by less, "-" for non-numbers."""
    try:
        a, b = float(a), float(b)
    except (TypeError, ValueError):
        return "-"
    if math.isnan(a) or math.isnan(b):
        return "-"
    if a == b:
        return "equal"
    p = pct(a, b, floor)
    if p:
        return p
    if abs(b - a) <= floor:
        return "equal to round-off"
    return "%+.3g (absolute)" % (b - a)


ROWS = [("status", "status", None), ("exit code", "exit_code", None), ("increments", "increments", "%d"),
        ("increments kept in the result file", "kept", "%d"), ("solutions (all increments)", "solutions", "%d"),
        ("CPU time [s]", "cpu_s", "%.3g"),
        ("compared increment", "increment", None), ("load factors of the compared state", "load_factors", None),
        ("load factor", "load_factor", "%.6g"), ("peak pressure [{stress}]", "peak_pressure", "%.6g"),
        ("contact width [{length}]", "width", "%.6g"), ("contact area [{length}²]", "area", "%.6g"),
        ("approach [{length}]", "approach", "%.6g"), ("total normal force [{force}]", "normal_force", "%.6g"),
        ("total tangential force [{force}]", "tangential_force", "%.6g"),
        ("mean tangential displacement u_T of the closed pairs [{length}]", "mean_slip", "%.6g"),
        ("largest tangential displacement u_T [{length}]", "max_slip", "%.6g"),
        ("largest irreversible slip u_T^p [{length}]", "max_irreversible", "%.6g"),
        ("closed pairs", "closed", "%d"),
        ("slipping pairs", "slipping", "%d"), ("worst law drift", "worst_drift", "%.3g")]
# the scale of each row's round-off (figures of the compared state; others have no difference)
ROW_SCALE = {"load_factor": None, "peak_pressure": "stress", "width": "length", "area": "area",
             "approach": "length", "normal_force": "force", "tangential_force": "force", "mean_slip": "length",
             "max_slip": "length", "max_irreversible": "length", "closed": None, "slipping": None}
RUN_ROWS = ("increments", "kept", "solutions", "cpu_s", "worst_drift")


def _cell(v, fmt):
    if v is None or v == "":
        return "-"
    if fmt and isinstance(v, (int, float)) and not (isinstance(v, float) and math.isnan(v)):
        return fmt % v
    return str(v)


def _curves(h5):
    res = Result(h5)
    if res.contact is None or not res.steps:
        return None
    h = History(res)
    figs = [h.figures(k) for k in range(len(h.steps))]
    return {"h": h, "lam": h.lam, "approach": h.approach,
            "peak": np.array([v["peak_pressure"] for v in figs]),
            "slipping": np.array([v["slipping"] for v in figs]),
            "width": np.array([v["width"] for v in figs]),
            "drift": res.history("law_drift"), "solutions": res.history("iterations"),
            "mean_slip": np.array([v["mean_slip"] for v in figs]),
            "tangential_force": np.array([v["tangential_force"] for v in figs]),
            "number": np.array([s.number for s in res.steps])}


def _plot_distributions(curves, labels, out, units, which, steps=(None, None)):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for (c, lab), colour, style, step in zip(zip(curves, labels), ("C0", "C3"), ("o-", "s--"), steps):
        h = c["h"]
        if which == "last":
            k = len(h.steps) - 1 if step is None else step
        else:
            k = int(np.argmax(h.lam))
        order = np.argsort(h.coord)
        for ax, name in zip(axes, ("pressure", "shear")):
            ax.plot(h.coord[order], h.field(k, name)[order], style, ms=3, color=colour,
                    label="%s (incr. %d, load factor %.4g)" % (lab, h.steps[k].number, h.lam[k]))
    axes[0].set_ylabel("normal pressure p_n [%s]" % units["stress"])
    axes[1].set_ylabel("shear stress p_T [%s]" % units["stress"])
    for ax in axes:
        ax.set_xlabel("position of the pairs along the interface [%s]" % units["length"])
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("contact stresses %s" % ("at the compared state" if which == "last" else "at the peak load"),
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def _plot_history(curves, labels, out, units):
    fig, axes = plt.subplots(2, 4, figsize=(21, 9))
    for (c, lab), colour, style in zip(zip(curves, labels), ("C0", "C3"), ("o-", "s--")):
        kw = dict(ms=3, color=colour, label=lab)
        axes[0, 3].plot(c["number"], c["mean_slip"], style, **kw)
        axes[1, 3].plot(c["number"], c["tangential_force"], style, **kw)
        axes[0, 0].plot(c["approach"], c["lam"], style, **kw)
        axes[0, 1].plot(c["lam"], c["peak"], style, **kw)
        axes[0, 2].plot(c["lam"], c["width"], style, **kw)
        axes[1, 0].plot(c["lam"], c["slipping"], style, **kw)
        axes[1, 1].plot(c["number"], c["drift"], style, **kw)
        axes[1, 2].plot(c["number"], c["solutions"], style, **kw)
    axes[0, 0].set_xlabel("approach of the bodies [%s]" % units["length"])
    axes[0, 0].set_ylabel("load factor")
    axes[0, 1].set_ylabel("peak pressure [%s]" % units["stress"])
    axes[0, 2].set_ylabel("contact width [%s]" % units["length"])
    axes[1, 0].set_ylabel("slipping pairs")
    for ax in (axes[0, 1], axes[0, 2], axes[1, 0]):
        ax.set_xlabel("load factor")
    axes[1, 1].set_ylabel("law drift (relative)")
    axes[1, 1].set_yscale("symlog", linthresh=1e-3)
    axes[1, 2].set_ylabel("solutions of the increment")
    axes[0, 3].set_ylabel("mean u_T of the closed pairs [%s]" % units["length"])
    axes[1, 3].set_ylabel("total tangential force [%s]" % units["force"])
    for ax in (axes[1, 1], axes[1, 2], axes[0, 3], axes[1, 3]):
        ax.set_xlabel("increment (kept in the result file)")
    for ax in axes.ravel():
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def shown_path(deck):
    """A deck's path as the report shows it: relative to the project for a deck inside it (the
    variant of --vary, a hidden file beside its deck, by the name of the copy kept with the
    report), else its name."""
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    d = os.path.abspath(deck)
    base = os.path.basename(d)
    if base.startswith("."):
        return base.lstrip(".") + " (kept beside this report)"
    return os.path.relpath(d, root) if d.startswith(root + os.sep) else base


def compare_runs(runs, out, exe, title="", approach_nodes=None, log=print):
    """Run the decks `runs` = [(label, deck path)] (two) into the directory `out`, write
    out/report.md, its figures and out/report.json; returns the report's path.  The figures are
    compared at like states (like_states); a failed run is named at the top of the report and in
    report.json ("failed": its labels), which tools/compare.py turns into exit code 3."""
    os.makedirs(out, exist_ok=True)
    h5s, labels, measured = [], [], []
    for label, deck in runs:
        slug = re.sub(r"[^A-Za-z0-9_.-]+", "_", label)
        h5 = os.path.join(out, slug + ".h5")
        for ext in (".h5", ".xdmf", ".lis", ".log"):
            if os.path.exists(h5[:-3] + ext):
                os.remove(h5[:-3] + ext)
        log("compare: running %s (%s)" % (label, deck))
        rc, wall, cpu, _ = run_measured(exe, deck, h5, h5[:-3] + ".log", extra=["-l", h5[:-3] + ".lis"])
        if not os.path.exists(h5):
            raise CompareError("%s: kontakt2d wrote no result file (exit code %d); see %s"
                               % (deck, rc, h5[:-3] + ".log"))
        measured.append((cpu, wall, rc))
        h5s.append(h5)
        labels.append(label)
    res = [Result(h) for h in h5s]
    note = None
    steps = [None, None]
    if all(r.steps for r in res):
        ka, kb, note = like_states(res[0], res[1])
        steps = [ka, kb]
    else:
        note = "no like states: %s kept no increment" % " and ".join(
            lab for lab, r in zip(labels, res) if not r.steps)
    figs = [run_figures(h, cpu, wall, rc, approach_nodes, h[:-3] + ".log", step=k)
            for h, (cpu, wall, rc), k in zip(h5s, measured, steps)]
    bad = [lab for lab, fg in zip(labels, figs) if failed(fg)]
    comparable = note is None or note.startswith("like states")
    units = unit_labels(res[0])
    lines = ["# %s" % (title or "Comparison: %s against %s" % (labels[1], labels[0])), ""]
    for lab in bad:
        fg = figs[labels.index(lab)]
        lines += ["**The run %s failed** (exit code %s, status: %s)." % (lab, fg["exit_code"], fg["status"]), ""]
    for (label, deck), h5 in zip(runs, h5s):
        lines.append("* **%s**: `%s` -> `%s`" % (label, shown_path(deck), os.path.basename(h5)))
    where = "the last increment of each run (like states: the same load factors and load path)"
    if note and comparable:
        where = "increment %s of %s and %s of %s (%s)" % (figs[0].get("increment"), labels[0],
                                                           figs[1].get("increment"), labels[1], note)
    elif note:
        where = "the last increment of each run. **Note: %s.**" % note
    lines += ["", "Figures at %s; the difference is the second run's against the first, in per cent where both "
              "values are above round-off (%g of the run's largest value of that kind), else absolute." %
              (where, ROUND_OFF), "",
              "| | %s | %s | difference |" % tuple(labels), "|---|---|---|---|"]
    for name, key, fmt in ROWS:
        a, b = figs[0].get(key, ""), figs[1].get(key, "")
        if a == "" and b == "":
            continue
        d = "-"
        if fmt and (key in RUN_ROWS or comparable):
            kind = ROW_SCALE.get(key)
            floor = 0.0
            if kind:
                floor = ROUND_OFF * max(figs[0]["scale"][kind], figs[1]["scale"][kind])
            d = difference(a, b, floor, fmt)
        lines.append("| %s | %s | %s | %s |" % (name.format(**units), _cell(a, fmt), _cell(b, fmt), d))
    curves = [_curves(h) for h in h5s]
    pngs = []
    if all(c is not None for c in curves):
        base = os.path.join(out, "compare")
        _plot_distributions(curves, labels, base + "_last.png", units, "last", steps)
        pngs.append(("Contact stresses at the compared state", base + "_last.png"))
        if any(np.argmax(c["lam"]) != len(c["lam"]) - 1 for c in curves):
            _plot_distributions(curves, labels, base + "_peak.png", units, "peak")
            pngs.append(("Contact stresses at the peak load", base + "_peak.png"))
        _plot_history(curves, labels, base + "_history.png", units)
        pngs.append(("Approach, peak pressure, width, slipping pairs, tangential displacement and force, law drift "
                     "and solutions per increment", base + "_history.png"))
    lines.append("")
    for cap, png in pngs:
        lines += ["## %s" % cap, "", "![%s](%s)" % (cap, os.path.basename(png)), ""]
    lines += ["Definitions: approach = relative normal displacement of the bodies' far faces; width = extent of "
              "the closed pairs along the interface; area = sum of their lumped areas; slipping pairs = pairs in "
              "slip that carry a normal force (a pair at zero force is not counted); mean u_T = area-weighted "
              "mean tangential displacement of the closed pairs; law drift = largest "
              "departure of a spring force from the interface law (result attribute `law_drift`); CPU time = "
              "user + system time of the kontakt2d process.", ""]
    md = os.path.join(out, "report.md")
    with open(md, "w") as f:
        f.write("\n".join(lines))
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump({"runs": [{"label": lab, "deck": shown_path(d), "h5": os.path.basename(h), "figures": fg}
                            for (lab, d), h, fg in zip(runs, h5s, figs)],
                   "failed": bad, "note": note}, f, indent=1, default=float)
    for lab in bad:
        log("compare: the run %s failed (exit code %s, status: %s)"
            % (lab, figs[labels.index(lab)]["exit_code"], figs[labels.index(lab)]["status"]))
    if note and not note.startswith("like states: the last"):
        log("compare: note: %s" % note)
    elif note:
        log("compare: compared at increment %s of %s and %s of %s (%s)" % (
            figs[0]["increment"], labels[0], figs[1]["increment"], labels[1], note))
    return md
