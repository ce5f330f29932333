"""Compare two runs of a joint: a deck against a variant of itself (one card changed: the
interface law, or the contact scheme), or two decks.  tools/compare.py is the command line.

    from k2d.compare import vary_deck, compare_runs
    text = vary_deck(open("punch.dat").read(), "LAW", "IDEAL")     # the deck with LAW IDEAL
    report = compare_runs([("rough", "a.dat"), ("ideal", "b.dat")], "out/", exe)

Each run is a separate kontakt2d process (CPU time: the rusage of that process).  The report
(Markdown, out/report.md, with PNG figures beside it and the figures as JSON in
out/report.json) holds per run: status, increments, solutions, CPU time, and at the last
increment the peak pressure, contact width and area, approach, total normal and tangential
force, slipping pairs, worst law drift; the differences of the second run from the first in
per cent; figures of the pressure and shear along the interface overlaid (at the last
increment, and at the peak load when the history unloads), approach and peak pressure against
the load factor, slipping pairs, law drift and solutions per increment.  The figures are those
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

__all__ = ["VARY", "CompareError", "parse_vary", "vary_deck", "run_totals", "run_figures", "pct", "ROWS",
           "shown_path", "compare_runs"]

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


def run_figures(h5, cpu, wall, rc, approach_nodes=None, log=None):
    """The figures of one run (a dict), from its result file (and the totals of its log)."""
    res = Result(h5)
    f = {"exit_code": rc, "status": res.status, "kept": len(res.steps), "cpu_s": cpu, "wall_s": wall,
         "solutions": int(np.nansum(res.history("iterations"))) if res.steps else 0, "increments": res.completed}
    totals = run_totals(log) if log else None
    if totals:
        f["solutions"], f["increments"] = totals
    if res.contact is None or not res.steps:
        return f
    h = History(res, approach_nodes=approach_nodes)
    last = h.figures(len(h.steps) - 1)
    drift = res.history("law_drift")
    f.update({k: last[k] for k in ("load_factor", "peak_pressure", "width", "area", "approach", "normal_force",
                                   "tangential_force", "slipping", "closed")})
    f["peak_at"] = list(last["peak_at"])
    f["worst_drift"] = float(np.nanmax(drift)) if np.isfinite(drift).any() else float("nan")
    return f


def pct(a, b):
    """Difference of b from a in per cent ('' when a is zero or either is missing)."""
    try:
        a, b = float(a), float(b)
    except (TypeError, ValueError):
        return ""
    if a == 0.0 or math.isnan(a) or math.isnan(b):
        return ""
    return "%+.3g %%" % (100.0 * (b / a - 1.0))


ROWS = [("status", "status", None), ("exit code", "exit_code", None), ("increments", "increments", "%d"),
        ("increments kept in the result file", "kept", "%d"), ("solutions (all increments)", "solutions", "%d"),
        ("CPU time [s]", "cpu_s", "%.3g"),
        ("load factor at the end", "load_factor", "%.6g"), ("peak pressure [{stress}]", "peak_pressure", "%.6g"),
        ("contact width [{length}]", "width", "%.6g"), ("contact area [{length}²]", "area", "%.6g"),
        ("approach [{length}]", "approach", "%.6g"), ("total normal force [{force}]", "normal_force", "%.6g"),
        ("total tangential force [{force}]", "tangential_force", "%.6g"), ("closed pairs", "closed", "%d"),
        ("slipping pairs", "slipping", "%d"), ("worst law drift", "worst_drift", "%.3g")]


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
            "number": np.array([s.number for s in res.steps])}


def _plot_distributions(curves, labels, out, units, which):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for (c, lab), colour, style in zip(zip(curves, labels), ("C0", "C3"), ("o-", "s--")):
        h = c["h"]
        k = len(h.steps) - 1 if which == "last" else int(np.argmax(h.lam))
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
    fig.suptitle("contact stresses %s" % ("at the last increment" if which == "last" else "at the peak load"),
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def _plot_history(curves, labels, out, units):
    fig, axes = plt.subplots(2, 3, figsize=(16, 9))
    for (c, lab), colour, style in zip(zip(curves, labels), ("C0", "C3"), ("o-", "s--")):
        kw = dict(ms=3, color=colour, label=lab)
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
    for ax in (axes[1, 1], axes[1, 2]):
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
    out/report.md, its figures and out/report.json; returns the report's path."""
    os.makedirs(out, exist_ok=True)
    figs, h5s, labels = [], [], []
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
        figs.append(run_figures(h5, cpu, wall, rc, approach_nodes, h5[:-3] + ".log"))
        h5s.append(h5)
        labels.append(label)
    res0 = Result(h5s[0])
    units = unit_labels(res0)
    lines = ["# %s" % (title or "Comparison: %s against %s" % (labels[1], labels[0])), ""]
    for (label, deck), h5 in zip(runs, h5s):
        lines.append("* **%s**: `%s` -> `%s`" % (label, shown_path(deck), os.path.basename(h5)))
    lines += ["", "Figures at the last increment of each run; the difference is the second run's "
              "against the first.", "",
              "| | %s | %s | difference |" % tuple(labels), "|---|---|---|---|"]
    for name, key, fmt in ROWS:
        a, b = figs[0].get(key, ""), figs[1].get(key, "")
        if a == "" and b == "":
            continue
        d = pct(a, b) if fmt and key not in ("exit_code",) else ""
        lines.append("| %s | %s | %s | %s |" % (name.format(**units), _cell(a, fmt), _cell(b, fmt), d or "-"))
    curves = [_curves(h) for h in h5s]
    pngs = []
    if all(c is not None for c in curves):
        base = os.path.join(out, "compare")
        _plot_distributions(curves, labels, base + "_last.png", units, "last")
        pngs.append(("Contact stresses at the last increment", base + "_last.png"))
        if any(np.argmax(c["lam"]) != len(c["lam"]) - 1 for c in curves):
            _plot_distributions(curves, labels, base + "_peak.png", units, "peak")
            pngs.append(("Contact stresses at the peak load", base + "_peak.png"))
        _plot_history(curves, labels, base + "_history.png", units)
        pngs.append(("Approach, peak pressure, law drift, slipping pairs and solutions per increment",
                     base + "_history.png"))
    lines.append("")
    for cap, png in pngs:
        lines += ["## %s" % cap, "", "![%s](%s)" % (cap, os.path.basename(png)), ""]
    lines += ["Definitions: approach = relative normal displacement of the bodies' far faces; width = extent of "
              "the closed pairs along the interface; area = sum of their lumped areas; law drift = largest "
              "departure of a spring force from the interface law (result attribute `law_drift`); CPU time = "
              "user + system time of the kontakt2d process.", ""]
    md = os.path.join(out, "report.md")
    with open(md, "w") as f:
        f.write("\n".join(lines))
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump({"runs": [{"label": lab, "deck": shown_path(d), "h5": os.path.basename(h), "figures": fg}
                            for (lab, d), h, fg in zip(runs, h5s, figs)]}, f, indent=1, default=float)
    return md
