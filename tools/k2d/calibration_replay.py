"""Close the calibration loop: run fitted CONTACT cards through Kontakt2D on a uniform block
that replays the measured history, and read the computed closures (or tractions) back.

The model (written with k2d.deck.Deck): body A, one plane-stress Q4 element 1 x 1 mm (unit
thickness), on body B, one element held fixed, with two node-to-node pairs of 0.5 mm2 each;
E = 1000 N/mm2 (1e9 for the tangential deck), nu = 0, so that the contact pressure is the
load per unit area at every pair.  SCHEME NEWTON returns every increment to the laws, so each
increment ends on the law to the solver's tolerances (CONVERGE 1e-10, 1e-8).

* normal:  a uniform pressure PN on the top edge, PN = one data pressure unit in model units;
  load factor of increment k = the k-th measured pressure in data units, unloading to exactly
  zero included (the program returns every pair to the law's zero-force point there).  With
  `floor` > 0, unloading and reloading rows below `floor` x the largest pressure are replayed
  at that floor and not compared (default 0: every row as measured).
* tangent: one run per curve; the normal force p_n A in two point loads on the top, tied in y
  (case 1, 5 increments), then the contact face of A driven tangentially (case 2: UX = one
  data length unit in mm, factor = the measured u_T in data units), one increment per row.

Results are read through k2d.results.Result only.
"""
import os

import numpy as np

from k2d.build import find_or_build, run_deck
from k2d.calibration import card
from k2d.deck import Deck
from k2d.results import Result

__all__ = ["ReplayError", "Replay", "replay_normal", "replay_tangent", "summary"]


class ReplayError(Exception):
    pass


class Replay:
    """Computed values per data row (NaN where not replayed) and what was compared."""

    def __init__(self):
        self.rows = []            # data rows compared
        self.computed = None      # per data row, data units
        self.clipped = []         # rows replayed at the floor pressure
        self.decks = []
        self.max_error = 0.0      # max |computed - data| over compared rows, data units
        self.max_model_error = 0.0  # max |computed - fitted law|, data units
        self.scale = 1.0          # the largest |data| value, for relative figures


def _block(title, E):
    d = Deck(title, ntype=1, nnode=4)
    d.block("A", [0.0, 1.0], [0.0, 1.0], 1)
    d.block("B", [0.0, 1.0], [-1.0, 0.0], 2)
    d.material(1, E, 0.0, 1.0)
    d.material(2, E, 0.0, 1.0)
    for n in d.nodes_where("B", lambda x, y: True):
        d.fix(n, "11")
    sa = d.nodes_where("A", lambda x, y: abs(y) < 1e-12)
    sb = d.nodes_where("B", lambda x, y: abs(y) < 1e-12)
    surf = ["SURFACE   A"] + d.node_list_cards(sa) + ["SURFACE   B"] + d.node_list_cards(sb)
    return d, surf


def _run(deck_path, exe):
    h5 = os.path.splitext(deck_path)[0] + ".h5"
    log = os.path.splitext(deck_path)[0] + ".log"
    if os.path.exists(h5):
        os.remove(h5)
    rc = run_deck(exe, deck_path, h5, quiet=True, log=log)
    if rc != 0 or not os.path.exists(h5):
        with open(log) as f:
            tail = f.read()[-2000:]
        raise ReplayError("Kontakt2D failed on %s (exit code %d):\n%s" % (deck_path, rc, tail))
    r = Result(h5)
    if r.status != "completed":
        raise ReplayError("Kontakt2D did not complete %s: status %s" % (deck_path, r.status))
    return r


def replay_normal(fit, workdir, exe=None, floor=0.0, name="replay_normal"):
    """Replay the pressure history of a normal fit (k2d.calibration.fit_normal)."""
    exe = find_or_build(exe)
    os.makedirs(workdir, exist_ok=True)
    t, units = fit.table, fit.units
    p = t.values["p"]                                  # data units
    pcol, ucol = t.column("p"), t.column("u")
    pmin = floor * float(np.max(p))
    d, surf = _block("Calibration replay: the measured pressure history on a uniform block", 1000.0)
    d.comments = ["Written by tools/calibrate.py from %s: a uniform pressure history on one element,"
                  % os.path.basename(fit.path),
                  "load factor = the measured pressure in %s; closure = the law's (SCHEME NEWTON)." % pcol.unit,
                  ("Unloading rows below %g of the peak pressure are replayed at that floor." % floor
                   if floor > 0.0 else "Every row is replayed as measured, unloading to zero included.")]
    pn = pcol.scale / units.model_pressure              # one data pressure unit, model units
    d.edge_pressure("A", lambda x, y: abs(y - 1.0) < 1e-12, pn)
    for n in d.nodes_where("A", lambda x, y: abs(x) < 1e-12):
        d.fix(n, "10")
    d.contact = ["UNITS     %s" % units.card, fit.normal_card, "FRICTION  NONE", "SCHEME    NEWTON"] + surf
    rp = Replay()
    inc_of_row = np.full(len(t), -1, dtype=int)
    lam, ninc = 0.0, 0
    for k in range(len(t)):
        target = p[k]
        if floor > 0.0 and fit.code[k] != "L" and target < pmin:
            target = pmin
            rp.clipped.append(k)
        if target == lam:
            inc_of_row[k] = ninc                       # a hold: the state of the last increment
            continue
        ninc += 1
        lam = target
        d.increments.append((1, [lam]))
        inc_of_row[k] = ninc
    deck_path = os.path.join(workdir, name + ".dat")
    d.write(deck_path)
    rp.decks.append(deck_path)
    r = _run(deck_path, exe)
    rp.computed = np.full(len(t), np.nan)
    rp.pressure = np.full(len(t), np.nan)
    for k in range(len(t)):
        if inc_of_row[k] <= 0:
            continue                                   # before the first load: the initial state
        s = r.step(inc_of_row[k])
        clo = s.contact("closure") * units.model_length / ucol.scale
        pr = s.contact("pressure") * units.model_pressure / pcol.scale
        if np.ptp(clo) > 1e-9 * max(abs(clo).max(), 1e-300):
            raise ReplayError("the replay block is not uniform: closures %s at increment %d" % (clo, inc_of_row[k]))
        rp.computed[k] = float(np.mean(clo))
        rp.pressure[k] = float(np.mean(pr))
    clipped = set(rp.clipped)
    # compared: the rows the fit used (with --loading-only the loading curve) that were replayed as measured
    rp.rows = [k for k in range(len(t)) if fit.fitted[k] and k not in clipped and np.isfinite(rp.computed[k])]
    u = t.values["u"]
    rp.scale = float(np.max(np.abs(u)))
    err = rp.computed[rp.rows] - u[rp.rows]
    model = fit.model * units.length / ucol.scale
    merr = rp.computed[rp.rows] - model[rp.rows]
    rp.max_error = float(np.max(np.abs(err))) if err.size else 0.0
    rp.max_model_error = float(np.nanmax(np.abs(merr))) if merr.size else 0.0
    rp.unit = ucol.unit
    rp.floor = floor
    return rp


def replay_tangent(fit, workdir, exe=None, name="replay_tangent"):
    """Replay every tangential curve of a tangent fit (k2d.calibration.fit_tangent)."""
    exe = find_or_build(exe)
    os.makedirs(workdir, exist_ok=True)
    t, units = fit.table, fit.units
    ut = t.values["ut"]
    utcol, ptcol = t.column("ut"), t.column("pt")
    rp = Replay()
    rp.computed = np.full(len(t), np.nan)
    friction = [c for c in fit.cards if c.startswith("FRICTION")]
    hardening = [c for c in fit.cards if c.startswith("HARDENING")]
    if not friction:
        # elastic data: a friction coefficient the curves never reach
        top = max(float(np.max(np.abs(fit.pt[idx]))) / lv for idx, lv in zip(fit.curves, fit.levels))
        friction = [card("FRICTION", "COULOMB", float("%.3g" % (10.0 * top / 0.625)))]
        hardening = ["HARDENING OFF"]
    for j, (idx, lv) in enumerate(zip(fit.curves, fit.levels)):
        d, surf = _block("Calibration replay: tangential curve %d at p_n = %.6g" % (j + 1, lv), 1.0e9)
        d.comments = ["Written by tools/calibrate.py from %s: curve %d, normal pressure held, the contact face"
                      % (os.path.basename(fit.path), j + 1),
                      "driven tangentially (factor of case 2 = the measured u_T in %s)." % utcol.unit,
                      "NORMAL is a placeholder: the normal law does not change p_T at a given p_n."]
        top_nodes = d.nodes_where("A", lambda x, y: abs(y - 1.0) < 1e-12)
        d.tie("01", top_nodes)
        force = lv * units.pressure / units.model_pressure * 1.0      # p_n times the 1 mm2 area
        for n in top_nodes:
            d.point_load(n, 0.0, -0.5 * force, case=1)
        ux = utcol.scale / units.model_length
        for n in d.nodes_where("A", lambda x, y: abs(y) < 1e-12):
            d.fix(n, "10", ux=ux, case=2)
        d.contact = ["UNITS     %s" % units.card, "NORMAL           1.0       0.5",
                     [c for c in fit.cards if c.startswith("TANGENT")][0]] + friction + hardening + \
                    ["SCHEME    NEWTON"] + surf
        d.increments = [(1, [0.05, None]), (4, [1.0, None])]
        lam, ninc = 0.0, 5
        inc = {}
        for k in idx:
            if ut[k] != lam:
                ninc += 1
                lam = ut[k]
                d.increments.append((1, [None, lam]))
            inc[k] = ninc
        deck_path = os.path.join(workdir, "%s_%d.dat" % (name, j + 1))
        d.write(deck_path)
        rp.decks.append(deck_path)
        r = _run(deck_path, exe)
        for k in idx:
            s = r.step(inc[k])
            sh = s.contact("shear") * units.model_pressure / ptcol.scale
            rp.computed[k] = float(np.mean(sh))
    rp.rows = list(range(len(t)))
    pt = t.values["pt"]
    rp.scale = float(np.max(np.abs(pt)))
    model = fit.model * units.pressure / ptcol.scale
    rp.max_error = float(np.max(np.abs(rp.computed - pt)))
    rp.max_model_error = float(np.max(np.abs(rp.computed - model)))
    rp.unit = ptcol.unit
    return rp


def summary(rp, what):
    rel = rp.max_error / rp.scale if rp.scale else 0.0
    s = ("Kontakt2D replay (%s): %d rows compared; computed - data: worst %.3g %s (%.2g of the largest); "
         "computed - fitted law: worst %.3g %s"
         % (what, len(rp.rows), rp.max_error, rp.unit, rel, rp.max_model_error, rp.unit))
    if rp.clipped:
        s += ("\n  %d unloading row(s) below %g of the peak pressure replayed at that floor and not compared "
              "(--replay-floor)" % (len(rp.clipped), rp.floor))
    return s
