"""Plots of the history of a run with contact (tools/plot_history.py is the command line):

    from k2d.history_plot import plot_history
    pngs = plot_history("run.h5")                      # [] for a deck without contact or with one increment
    pngs = plot_history("run.h5", pairs=[3, 7], increments=[10, 40], approach_nodes=(120, 4))

writes beside the result file

    NAME_approach.png    (a) load factor and total normal force against the approach of the bodies
    NAME_pairs.png       (b) pressure-closure path of chosen pairs (default: the most and the least
                             loaded) over the law's virgin curve and its unloading curves
    NAME_interface.png   (c) pressure and shear along the interface at several increments
                             (loading solid, unloading dashed, holding dotted)
    NAME_slip.png        (d) the slip zone against the load: pair states along the interface per
                             increment, and the slipping share of the closed area against the load factor

Pairs are numbered as in the result file (1-based, the order of /contact); increments by their
numbers.  Definitions of the figures: k2d.history.  Reads the results through k2d.results only.
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import laws  # noqa: E402
from .history import KIND_STYLE, History, law_curves, unit_labels  # noqa: E402
from .loops import NSUB, default_loop_pairs, energy_points, normal_path, plot_energy, plot_loops  # noqa: E402
from .results import Result  # noqa: E402

__all__ = ["STYLE", "DNAME", "KIND_STYLE", "STATE_COLOURS", "plot_approach", "reversal_points", "plot_pairs",
           "plot_interface", "pair_states", "plot_slip", "plot_history", "stage_table", "residual_after"]

STYLE = {1: "-", -1: "--", 0: ":"}
DNAME = {1: "loading", -1: "unloading", 0: "holding"}
STATE_COLOURS = {"open": "0.85", "stick": "C0", "hardening branch": "C1", "slip": "C3"}


def _lam_label(h):
    return "load factor" if h.result.load_factors().shape[1] == 1 else "load factor of case %d" % (h.case + 1)


def _coord_name(h):
    ax = "r" if h.ntype == 3 else "x"
    if h.axis == 1:
        ax = "z" if h.ntype == 3 else "y"
    return ax


def _direction_segments(ax, x, y, kind, colour, label, origin=None, law=None):
    """Draw y(x) step by step with the line style of what changes in each step (KIND_STYLE:
    solid loading, dashed unloading, dash-dot tangential -, dotted holding), from the point
    `origin` (the unloaded state) when given.  law: (xs, ys, on) of k2d.loops, the path drawn
    along the law with NSUB points per increment where on[k] (else the chord)."""
    shown = set()
    if origin is not None:
        x = np.concatenate([[origin[0]], x])
        y = np.concatenate([[origin[1]], y])
    else:
        kind = kind[1:]
    pos = 0
    for k in range(1, len(x)):
        d = str(kind[k - 1])
        lab = None
        if d not in shown:
            lab = "%s (%s)" % (label, d) if label else d
            shown.add(d)
        if law is not None:
            n = NSUB if law[2][k - 1] else 1
            xs, ys = law[0][pos:pos + n + 1], law[1][pos:pos + n + 1]
            pos += n
        else:
            xs, ys = x[k - 1:k + 1], y[k - 1:k + 1]
        ax.plot(xs, ys, KIND_STYLE[d], color=colour, label=lab)
    ax.plot(x, y, "o", ms=3, color=colour)


def plot_approach(h, out, units):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    f = [h.figures(k) for k in range(len(h.steps))]
    fn = np.array([v["normal_force"] for v in f])
    # from the unloaded origin: zero load, zero approach, zero force
    _direction_segments(axes[0], h.approach, h.lam, h.kind, "C0", "", origin=(0.0, 0.0))
    axes[0].set_ylabel(_lam_label(h))
    _direction_segments(axes[1], h.approach, fn, h.kind, "C2", "", origin=(0.0, 0.0))
    axes[1].set_ylabel("total normal contact force sum F_n [%s]" % units["force"])
    for ax in axes:
        ax.set_xlabel("approach of the bodies [%s]" % units["length"])
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("%s\napproach = relative normal displacement of the bodies' far faces"
                 % h.result.attrs.get("title", ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def reversal_points(h, j):
    """(u_A, p_A) where pair j leaves the virgin curve (loading state followed by an unloading
    one, or by an open one while the load falls), from the kept increments.  Under a tangential
    cycle a pair unloads while the load factor rises too (the couple of the shear)."""
    pts = []
    ns = [h.field(k, "normal_state")[j] for k in range(len(h.steps))]
    for k in range(len(ns) - 1):
        if ns[k] == 1 and (ns[k + 1] == 2 or (ns[k + 1] != 1 and h.direction[k + 1] < 0)):
            pts.append((float(h.field(k, "closure")[j]), float(h.field(k, "pressure")[j])))
    return pts


def plot_pairs(h, pairs, out, units):
    n = len(pairs)
    fig, axes = plt.subplots(1, n, figsize=(6 * n, 5), squeeze=False)
    ifaces = h.result.contact.interfaces
    iface_of = h.result.contact.interface
    for ax, j in zip(axes[0], pairs):
        path = normal_path(h, j)
        u = np.array([h.field(k, "closure")[j] for k in range(len(h.steps))])
        p = np.array([h.field(k, "pressure")[j] for k in range(len(h.steps))])
        law = ifaces[int(iface_of[j]) - 1] if len(ifaces) else {}
        if str(law.get("law", "ROUGH")).upper() == "ROUGH" and "normal_model" in law:
            pmax = 1.1 * max(p.max(), 1e-30)
            for i, (lab, cu, cp) in enumerate(law_curves(law, reversal_points(h, j), pmax)):
                ax.plot(cu, cp, color="0.6" if i == 0 else "0.4", lw=1.0 if i == 0 else 0.8,
                        ls="-" if i == 0 else "-.", label=lab if i < 2 else None, zorder=1)
        _direction_segments(ax, u, p, h.kind, "C3", "pair path", origin=(path[0][0], path[1][0]), law=path)
        if not path[2].all():
            ax.text(0.02, 0.95, "%d of %d increments drawn as chords (ends off the law or law unknown)"
                    % ((~path[2]).sum(), len(path[2])), transform=ax.transAxes, fontsize=7)
        ax.set_xlabel("closure u_n [%s]" % units["length"])
        ax.set_ylabel("pressure p_n [%s]" % units["stress"])
        x, y = h.position[j]
        ax.set_title("pair %d at (%.4g, %.4g)" % (j + 1, x, y), fontsize=9)
        ax.set_xlim(left=min(0.0, u.min(), path[0][0]))
        ax.set_ylim(bottom=0.0)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("%s\npressure-closure path of the pairs over the interface law, from the unloaded origin"
                 % h.result.attrs.get("title", ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_interface(h, incs, out, units):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    order = np.argsort(h.coord)
    xc = h.coord[order]
    cmap = plt.get_cmap("viridis")
    for i, k in enumerate(incs):
        colour = cmap(i / max(len(incs) - 1, 1))
        d = str(h.kind[k])
        lab = "incr. %d, %s %.4g (%s)" % (h.steps[k].number, "lambda", h.lam[k], d)
        for ax, name in zip(axes, ("pressure", "shear")):
            ax.plot(xc, h.field(k, name)[order], KIND_STYLE[d], marker="o", ms=2.5, color=colour, label=lab)
    cn = _coord_name(h)
    axes[0].set_ylabel("normal pressure p_n [%s]" % units["stress"])
    axes[1].set_ylabel("shear stress p_T [%s]" % units["stress"])
    for ax in axes:
        ax.set_xlabel("%s of the pairs [%s]" % (cn, units["length"]))
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("%s\ncontact stresses along the interface: loading solid, unloading dashed, tangential - "
                 "dash-dot, holding dotted"
                 % h.result.attrs.get("title", ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def pair_states(h, k):
    """State name of every pair in step index k: open, stick, hardening branch, slip (a closed
    pair at zero normal force, which holds nothing tangentially, is shown as stick, not slip)."""
    ns = h.field(k, "normal_state")
    ts = h.field(k, "tangential_state")
    slip = (ts == 2) & h.carrying(k)
    names = np.where(ns == 0, "open", np.where(slip, "slip", np.where(ts == 1, "hardening branch", "stick")))
    return names


def plot_slip(h, out, units):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    ax = axes[0]
    shown = set()
    for k in range(len(h.steps)):
        st = pair_states(h, k)
        for name, colour in STATE_COLOURS.items():
            sel = st == name
            if sel.any():
                ax.scatter(h.coord[sel], np.full(sel.sum(), h.steps[k].number), s=12, marker="s", color=colour,
                           label=name if name not in shown else None)
                shown.add(name)
    ax.set_xlabel("%s of the pairs [%s]" % (_coord_name(h), units["length"]))
    ax.set_ylabel("increment")
    ax.set_title("state of every pair per increment", fontsize=9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=4)
    # the load factor of the increments beside the map
    sec = ax.twinx()
    sec.set_ylim(ax.get_ylim())
    ticks = [s.number for s in h.steps][:: max(1, len(h.steps) // 8)]
    sec.set_yticks(ticks)
    sec.set_yticklabels(["%.3g" % h.lam[[s.number for s in h.steps].index(t)] for t in ticks], fontsize=7)
    sec.set_ylabel(_lam_label(h), fontsize=8)
    f = [h.figures(k) for k in range(len(h.steps))]
    share = np.array([v["slip_share"] for v in f])
    nslip = np.array([v["slipping"] for v in f])
    _direction_segments(axes[1], h.lam, share, h.kind, "C3", "", origin=(0.0, 0.0))
    axes[1].set_xlabel(_lam_label(h))
    axes[1].set_ylabel("slipping share of the closed contact area")
    axes[1].set_ylim(-0.02, 1.02)
    axes[1].grid(True, alpha=0.3)
    axes[1].legend(fontsize=7)
    for k in range(len(h.steps)):
        if nslip[k] and (k == 0 or nslip[k] != nslip[k - 1]):
            axes[1].annotate("%d" % nslip[k], (h.lam[k], share[k]), fontsize=6, xytext=(2, 2),
                             textcoords="offset points")
    axes[1].set_title("slip zone against the load (numbers: slipping pairs)", fontsize=9)
    fig.suptitle(h.result.attrs.get("title", ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_history(path, pairs=None, increments=None, approach_nodes=None, prefix=None, loop_pairs=None):
    """Write the history plots of the result file `path`; returns the PNG paths ([] when the file
    has no contact pairs or fewer than two increments).  pairs: pair numbers (1-based);
    increments: increment numbers for the interface plot; approach_nodes: (node of A, node of B)
    between which the approach is measured.  ValueError for a pair or increment the file does
    not hold."""
    res = Result(path)
    if res.contact is None or len(res.steps) < 2:
        return []
    h = History(res, approach_nodes=approach_nodes)
    units = unit_labels(res)
    if pairs:
        for j in pairs:
            if not 1 <= j <= h.npair:
                raise ValueError("%s: no pair %d (pairs 1..%d)" % (path, j, h.npair))
        pidx = [j - 1 for j in pairs]
    else:
        pidx = h.default_pairs()
    kidx = [h.index_of(n) for n in increments] if increments else h.default_increments()
    base = prefix or os.path.splitext(path)[0]
    out = []
    plot_approach(h, base + "_approach.png", units)
    out.append(base + "_approach.png")
    if pidx:
        plot_pairs(h, pidx, base + "_pairs.png", units)
        out.append(base + "_pairs.png")
    plot_interface(h, kidx, base + "_interface.png", units)
    out.append(base + "_interface.png")
    plot_slip(h, base + "_slip.png", units)
    out.append(base + "_slip.png")
    # the shear-slip loops where the pairs move tangentially
    if loop_pairs:
        for j in loop_pairs:
            if not 1 <= j <= h.npair:
                raise ValueError("%s: no pair %d (pairs 1..%d)" % (path, j, h.npair))
        lidx = [j - 1 for j in loop_pairs]
    else:
        lidx = default_loop_pairs(h)
    if lidx and any(k.startswith("tangential") for k in h.kind):
        plot_loops(h, lidx, base + "_loops.png", units)
        out.append(base + "_loops.png")
    # the energy per cycle against the amplitude, where the program found cycles (/cycles)
    if energy_points(path) is not None:
        plot_energy([path], base + "_energy.png")
        out.append(base + "_energy.png")
    return out


def stage_table(path, approach_nodes=None):
    """Markdown table of the figures at the end of every load stage of a result file with contact
    (the figures of k2d.history.History.figures)."""
    res = Result(path)
    h = History(res, approach_nodes=approach_nodes)
    u = unit_labels(res)
    rows = []
    for i, (a, b) in enumerate(h.stages()):
        f = h.figures(b)
        rows.append("| %d | %s | %d-%d | %.4g | %.4g at (%.4g, %.4g) | %.4g | %.4g | %.4g | %.4g | %.4g "
                    "| %d of %d | %s |"
                    % (i + 1, h.stage_name(a, b), h.steps[a].number, h.steps[b].number, f["load_factor"],
                       f["peak_pressure"], f["peak_at"][0], f["peak_at"][1], f["width"], f["area"],
                       f["approach"], f["normal_force"], f["tangential_force"], f["slipping"], f["closed"],
                       _fmt_residual(h, a, b)))
    head = ("| stage | kind | increments | load factor | peak pressure [%s] at | width [%s] | area [%s²] | "
            "approach [%s] | sum F_n [%s] | sum F_T | slipping pairs | residual closure [%s] |\n"
            % (u["stress"], u["length"], u["length"], u["length"], u["force"], u["length"])
            + "|" + "---|" * 12 + "\n")
    return head + "\n".join(rows) + "\n"


def _fmt_residual(h, a, b):
    if h.stage_name(a, b) != "unloading":
        return "-"
    r = residual_after(h, a, b)
    return "-" if np.isnan(r) else "%.3g" % r


def residual_after(h, a, b):
    """The permanent set max(u_A - c_n2 p_A^m2, 0) left in the pairs by the unloading stage a..b (the
    reversal point A of each pair: its last loading state before the stage), largest over the
    pairs that left the virgin curve in the stage (SPEC D8); NaN when none did."""
    if a == 0:
        return float("nan")
    ifaces = h.result.contact.interfaces
    iface_of = h.result.contact.interface
    best = float("nan")
    ua = h.field(a - 1, "closure")
    pa = h.field(a - 1, "pressure")
    ns = h.field(a - 1, "normal_state")
    ns_end = h.field(b, "normal_state")
    p_end = h.field(b, "pressure")
    for j in range(h.npair):
        law = ifaces[int(iface_of[j]) - 1]
        # pairs unloaded in the stage: off the virgin curve and below their reversal pressure (a
        # pair that holds its pressure, e.g. under a tangential unloading, stays at A)
        if ns[j] != 1 or ns_end[j] == 1 or p_end[j] >= pa[j] * (1.0 - 1e-9) or \
                str(law.get("law", "")).upper() != "ROUGH":
            continue
        cn2, m2 = (float(v) for v in np.atleast_1d(law["normal_model"])[2:4])
        # max(u_res, 0): beyond the law's admissible range p* (docs/contact.md)
        r = laws.residual_closure(ua[j], pa[j], cn2, m2)
        best = r if np.isnan(best) else max(best, r)
    return best
