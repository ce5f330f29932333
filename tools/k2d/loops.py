"""The paths of the contact pairs drawn along the interface law, the tangential loops and the
energy per cycle (tools/plot_history.py and tools/plot_energy.py are the command lines).

    from k2d.results import Result
    from k2d.history import History
    from k2d import loops
    h = History(Result("joint.h5"))
    u, p, on_law = loops.normal_path(h, j)        # pressure-closure path of pair j (0-based)
    ut, pt, on_law = loops.tangential_path(h, j)  # shear-slip path
    x, f = loops.interface_loop(h, iface=1)       # sum F_T against the mean u_T of the interface
    loops.plot_loops(h, [j1, j2], "joint_loops.png", units)
    loops.plot_energy(["a.h5", "b.h5"], "energy.png")      # energy per cycle against amplitude

Every path starts at the unloaded origin (zero load: closure -g0, the initial gap, zero
pressure; u_T = 0, F_T = 0).  Between two increment ends a path follows the law where the law
is known and both ends lie on it (within ON_LAW of the pair's largest force): the normal law's
virgin curve and unloading branch through the pair's reversal point A (its last state on the
virgin curve; k2d.laws.normal_law_pressure), the tangential law integrated by Masing's rule at
the increment's normal force (k2d.laws.masing_return, docs/contact.md) -- not the chord, which
cuts the curved branches and looks like a departure from the law.  Elsewhere (the ideal law, a
scheme off the law, a file keeping only every N-th increment) the chord is drawn, and the
on_law flags say which segments are chords.

Reads the results through k2d.results only.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

from . import laws  # noqa: E402
from .history import unit_labels  # noqa: E402
from .results import Result  # noqa: E402

__all__ = ["ON_LAW", "NSUB", "law_of", "normal_path", "tangential_path", "interface_loop", "default_loop_pairs",
           "plot_loops", "energy_points", "plot_energy"]

ON_LAW = 1e-3     # an increment end lies on the law within this fraction of the pair's largest force
NSUB = 24         # points drawn along the law inside one increment


def law_of(h, j):
    """The attributes of pair j's interface, with its local index (for r_model)."""
    c = h.result.contact
    iface = int(c.interface[j])
    law = c.interfaces[iface - 1] if len(c.interfaces) >= iface else {}
    local = int(np.sum(c.interface[:j] == iface))
    return law, local


def _rough(law):
    return str(law.get("law", "")).upper() == "ROUGH" and "normal_model" in law


def _consecutive(h):
    """True when the file keeps every increment from the first (the law can be followed)."""
    nums = [s.number for s in h.steps]
    return nums == list(range(1, len(nums) + 1))


def _series(h, name, j):
    return np.array([h.field(k, name)[j] for k in range(len(h.steps))])


def normal_path(h, j, nsub=NSUB):
    """(closure, pressure, on_law) of pair j from the unloaded origin through every kept
    increment; on_law[k] tells whether the segment ending at step k was drawn along the law."""
    law, _ = law_of(h, j)
    gap = float(getattr(h.result.contact, "gap", np.zeros(h.npair))[j])
    u = np.concatenate([[-gap], _series(h, "closure", j)])
    p = np.concatenate([[0.0], _series(h, "pressure", j)])
    ns = np.concatenate([[1], _series(h, "normal_state", j)])
    on = np.zeros(len(h.steps), dtype=bool)
    if not _rough(law):
        return u, p, on
    # with increments left out of the file only the virgin curve is certain between two ends on it
    every = _consecutive(h)
    cn, m, cn2, m2 = (float(v) for v in np.atleast_1d(law["normal_model"])[:4])
    tol = ON_LAW * max(np.max(np.abs(p)), np.finfo(float).tiny)
    xs, ys = [u[0]], [p[0]]
    rev = None                 # the reversal point A in force at the start of the segment
    for k in range(1, len(u)):
        # A: the last end on the virgin curve before the pair left it
        new_rev = rev
        if ns[k] == 1:
            new_rev = None
        elif ns[k] == 2 and ns[k - 1] == 1:
            new_rev = (u[k - 1], p[k - 1])
        ok = False
        if not every and not (ns[k] == 1 and ns[k - 1] == 1):
            new_rev = None
        elif ns[k] > 0 or ns[k - 1] > 0:
            pend = laws.normal_law_pressure(u[k], cn, m, cn2, m2, new_rev)
            ok = abs(pend - p[k]) <= tol
        elif p[k] == 0.0 and p[k - 1] == 0.0:
            ok = True               # open at both ends: zero pressure is the law
            new_rev = rev
        if ok and ns[k] == 0 and ns[k - 1] == 0:
            s = np.linspace(u[k - 1], u[k], nsub + 1)[1:]
            xs.extend(s)
            ys.extend(np.zeros(nsub))
        elif ok:
            s = np.linspace(u[k - 1], u[k], nsub + 1)[1:]
            xs.extend(s)
            ys.extend(np.atleast_1d(laws.normal_law_pressure(s, cn, m, cn2, m2, new_rev)))
        else:
            xs.append(u[k])
            ys.append(p[k])
        on[k - 1] = ok
        rev = new_rev
    # the end of every increment exactly as in the file
    return np.array(xs), np.array(ys), on


def _tangent_law(h, j):
    """(ke per kept step, mu per step, kappa, hardening) of pair j's tangential law, or None."""
    law, local = law_of(h, j)
    if not _rough(law) or "r_model" not in law or "tangent_s" not in law:
        return None
    r = float(np.atleast_1d(law["r_model"])[local])
    s_exp = float(np.atleast_1d(law["tangent_s"])[0])
    kappa = float(np.atleast_1d(law.get("kappa", 0.045))[0])
    hard = law.get("hardening", 1)
    hard = str(hard).upper() not in ("0", "OFF", "FALSE", "NO")
    return r, s_exp, kappa, hard


def tangential_path(h, j, nsub=NSUB, per_increment=False):
    """(u_T, p_T, on_law) of pair j from the unloaded origin: the tangential law (Masing's
    rule) integrated over each increment at the increment's normal force, from the force and
    back force at its start, with the elastic stiffness that brings the law to the increment's
    end (stick or hardening branch; the law's p^S/R at the start pressure when the pair ends in
    slip).  With per_increment=True also the parameter points (a list of arrays of F_T per
    increment, for the interface's loop)."""
    area = float(h.area[j])
    ut = np.concatenate([[0.0], _series(h, "slip", j)])
    ft = np.concatenate([[0.0], _series(h, "force_tangential", j)])
    fn = np.concatenate([[0.0], _series(h, "force_normal", j)])
    ns = np.concatenate([[0], _series(h, "normal_state", j)])
    ts = np.concatenate([[0], _series(h, "tangential_state", j)])
    mu = np.concatenate([[0.0], _series(h, "friction", j)])
    on = np.zeros(len(h.steps), dtype=bool)
    tl = _tangent_law(h, j)
    segs = []
    scale = max(np.max(np.abs(ft)), np.max(mu * fn), np.finfo(float).tiny)
    x = 0.0
    xs, ys = [ut[0]], [ft[0]]
    for k in range(1, len(ut)):
        t = np.linspace(0.0, 1.0, nsub + 1)[1:]
        seg = ft[k - 1] + t * (ft[k] - ft[k - 1])
        closed = ns[k] > 0 and fn[k] > h.fn_floor
        if tl is not None and _consecutive(h) and closed and area > 0:
            r, s_exp, kappa, hard = tl
            f0, x0 = (ft[k - 1], x) if (ns[k - 1] > 0 and fn[k - 1] > h.fn_floor) else (0.0, 0.0)
            du = ut[k] - ut[k - 1]
            limit = mu[k] * fn[k]
            ry = 0.625 * limit if hard else limit
            xc = min(max(x0, -max(limit - ry, 0.0)), max(limit - ry, 0.0))
            p0 = fn[k - 1] / area if fn[k - 1] > h.fn_floor else fn[k] / area
            ke = area * laws.tangential_stiffness(p0, s_exp, r)
            if du != 0.0 and ts[k] == 0:
                ke = (ft[k] - f0) / du
            elif du != 0.0 and ts[k] == 1 and hard and kappa > 0:
                sg = 1.0 if ft[k] - xc >= 0 else -1.0
                ke = ((ft[k] - xc - sg * ry) / kappa + xc + sg * ry - f0) / du
            if ke > 0 and np.isfinite(ke):
                vals = [laws.masing_return(f0, v * du, ke, kappa, limit, x0, hard) for v in t]
                fend, xend, _ = vals[-1]
                if abs(fend - ft[k]) <= ON_LAW * scale:
                    seg = np.array([v[0] for v in vals])
                    x = xend
                    on[k - 1] = True
            if not on[k - 1]:
                # the back force from the state the file gives (stick keeps it)
                x = xc if ts[k] == 0 else (ft[k] - np.sign(ft[k] - xc) * ry if ts[k] == 1 else
                                           np.sign(ft[k]) * max(limit - ry, 0.0))
        else:
            x = 0.0
            # open or at zero force at both ends: F_T = 0 is the law
            on[k - 1] = ft[k] == 0.0 and ft[k - 1] == 0.0
        segs.append(seg)
        if on[k - 1]:
            xs.extend(ut[k - 1] + t * (ut[k] - ut[k - 1]))
            ys.extend(seg)
        else:
            xs.append(ut[k])
            ys.append(ft[k])
    ys = np.array(ys) / area if area > 0 else np.array(ys)
    if per_increment:
        return np.array(xs), ys, on, segs
    return np.array(xs), ys, on


def interface_loop(h, iface=1, nsub=NSUB):
    """(mean u_T, sum F_T, ends) of interface `iface` from the unloaded origin, drawn along the
    law: inside an increment every pair's u_T moves linearly and its F_T follows its law
    (tangential_path), the sums taken at the same points.  `ends` = (mean u_T, sum F_T) at the
    increment ends as the file gives them (k2d.history.History.tangential_totals)."""
    sel = np.where(h.result.contact.interface == iface)[0]
    force_end, slip_end, _ = h.tangential_totals(iface)
    nk = len(h.steps)
    t = np.linspace(0.0, 1.0, nsub + 1)[1:]
    ftot = np.zeros((nk, nsub))
    for j in sel:
        _, _, _, segs = tangential_path(h, j, nsub, per_increment=True)
        for k in range(nk):
            s = segs[k]
            ftot[k] += s if len(s) == nsub else np.interp(t, np.linspace(0, 1, len(s) + 1)[1:], s)
    xs, ys = [0.0], [0.0]
    for k in range(nk):
        xs.extend(slip_end[k] + t * (slip_end[k + 1] - slip_end[k]))
        ys.extend(ftot[k])
    return np.array(xs), np.array(ys), (slip_end, force_end)


def default_loop_pairs(h, n=2):
    """The pairs with the largest range of u_T over the run among those that closed (at most n)."""
    ut = np.array([h.field(k, "slip") for k in range(len(h.steps))])
    closed = np.array([h.field(k, "normal_state") > 0 for k in range(len(h.steps))]).any(axis=0)
    rng = np.where(closed, np.ptp(np.vstack([np.zeros(h.npair), ut]), axis=0), -1.0)
    order = [int(j) for j in np.argsort(-rng, kind="stable") if rng[j] > 0]
    return order[:n]


def plot_loops(h, pairs, out, units):
    """The shear-slip paths p_T-u_T of `pairs` (0-based) and the interface's sum F_T against
    the mean u_T of its closed pairs (one panel per interface), along the law."""
    nif = max(1, len(h.result.contact.interfaces))
    n = len(pairs) + nif
    fig, axes = plt.subplots(1, n, figsize=(5.5 * n, 4.8), squeeze=False)
    lu = units["length"]
    for ax, j in zip(axes[0], pairs):
        x, y, on = tangential_path(h, j)
        ax.plot(x, y, "-", color="C3", lw=1.2, label="path (along the law)" if on.all() else "path")
        ends_u = np.concatenate([[0.0], [h.field(k, "slip")[j] for k in range(len(h.steps))]])
        ends_p = np.concatenate([[0.0], [h.field(k, "shear")[j] for k in range(len(h.steps))]])
        ax.plot(ends_u, ends_p, "o", ms=2.5, color="C3", label="increment ends")
        if not on.all():
            ax.text(0.02, 0.02, "%d of %d increments drawn as chords (law not followed)" % ((~on).sum(), len(on)),
                    transform=ax.transAxes, fontsize=7)
        px, py = h.position[j]
        ax.set_title("pair %d at (%.4g, %.4g)" % (j + 1, px, py), fontsize=9)
        ax.set_xlabel("tangential displacement u_T [%s]" % lu)
        ax.set_ylabel("shear stress p_T [%s]" % units["stress"])
    for i in range(nif):
        ax = axes[0][len(pairs) + i]
        x, y, (se, fe) = interface_loop(h, i + 1)
        ax.plot(x, y, "-", color="C0", lw=1.2, label="along the law")
        ax.plot(se, fe, "o", ms=2.5, color="C0", label="increment ends")
        ax.set_title("interface %d: total tangential force" % (i + 1), fontsize=9)
        ax.set_xlabel("relative displacement: mean u_T of the closed pairs [%s]" % lu)
        ax.set_ylabel("sum F_T [%s]" % units["force"])
    for ax in axes[0]:
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.axvline(0.0, color="0.7", lw=0.8)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("%s\nshear-slip loops from the unloaded origin" % h.result.attrs.get("title", ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def energy_points(path):
    """(slip amplitude, force amplitude, energy, loss factor) per cycle and interface of a result
    file, each (ncycle, ninterface), the loss factor NaN where it is not defined (an ideal
    interface, or slips that do not follow the total force); None when the file has no /cycles (written before the
    program wrote them, or a history without a cycle)."""
    c = Result(path).cycles
    if not c or "energy" not in c:
        return None
    get = lambda k: np.atleast_2d(np.asarray(c.get(k, np.full_like(c["energy"], np.nan)), dtype=float))  # noqa: E731
    e = get("energy")
    if e.shape[0] == 0:
        return None
    loss = get("loss_factor")
    if "ratios_defined" in c:
        # where the loss factor is not defined (docs/contact.md, "Load cycles"): NaN, not its 0
        defined = np.atleast_2d(np.asarray(c["ratios_defined"])).astype(bool)
        if defined.shape == loss.shape:
            loss[~defined] = np.nan
    return get("slip_amplitude"), get("force_amplitude"), e, loss


def _log_ticks(axis, values):
    """Readable ticks on a log axis spanning less than a decade: a few labelled values through
    the data (matplotlib would label every minor tick, overlapping)."""
    lo, hi = float(np.min(values)), float(np.max(values))
    if not (lo > 0 and hi < 10 * lo):
        return
    ticks = np.unique([float("%.2g" % v) for v in np.geomspace(lo, hi, 4)])
    axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    axis.set_major_locator(matplotlib.ticker.FixedLocator(ticks))
    axis.set_major_formatter(matplotlib.ticker.FixedFormatter(["%.3g" % t for t in ticks]))


def plot_energy(paths, out, labels=None):
    """Energy dissipated per cycle against the slip amplitude and against the force amplitude
    (log-log) from the /cycles groups of one or several result files (e.g. runs of one deck at
    different amplitudes), with the slope 3 against the force amplitude for reference (partial
    slip at small amplitude, Mindlin & Deresiewicz: energy ~ Q*^3).  Returns (out, skipped: the
    files without cycles), out None when no file has cycles."""
    pts, skipped = [], []
    for i, p in enumerate(paths):
        e = energy_points(p)
        if e is None:
            skipped.append(p)
        else:
            pts.append((labels[i] if labels else p.rsplit("/", 1)[-1], e))
    if not pts:
        return None, skipped
    first = next(p for p in paths if p not in skipped)
    units = unit_labels(Result(first))
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    allx = [[], []]
    for lab, (sa, fa, en, _) in pts:
        for i in range(en.shape[1]):
            ok = (en[:, i] > 0) & (sa[:, i] > 0) & (fa[:, i] > 0)
            if not ok.any():
                continue
            name = lab if en.shape[1] == 1 else "%s, interface %d" % (lab, i + 1)
            axes[0].plot(sa[ok, i], en[ok, i], "o-" if len(paths) == 1 else "o", ms=4, label=name)
            axes[1].plot(fa[ok, i], en[ok, i], "o-" if len(paths) == 1 else "o", ms=4, label=name)
            allx[0].append((sa[ok, i], en[ok, i]))
            allx[1].append((fa[ok, i], en[ok, i]))
    for ax, pairs, slope in zip(axes, allx, (None, 3)):
        if pairs and slope:
            x = np.concatenate([a for a, _ in pairs])
            y = np.concatenate([b for _, b in pairs])
            x0 = x.min()
            xs = np.array([x0, x.max() if x.max() > x0 else 2 * x0])
            ax.plot(xs, y[np.argmin(x)] * (xs / x0) ** slope, ":", color="0.5",
                    label="slope 3 (Mindlin's microslip, small amplitude)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        ax.set_ylabel("energy dissipated per cycle [%s x %s]" % (units["force"], units["length"]))
    for ax, pairs in zip(axes, allx):
        if pairs:
            _log_ticks(ax.xaxis, np.concatenate([a for a, _ in pairs]))
            _log_ticks(ax.yaxis, np.concatenate([b for _, b in pairs]))
    axes[0].set_xlabel("slip amplitude: half the range of the mean u_T per cycle [%s]" % units["length"])
    axes[1].set_xlabel("force amplitude: half the range of sum F_T per cycle [%s]" % units["force"])
    fig.suptitle("energy per cycle against the amplitude (/cycles of %d file(s))" % len(pts), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out, skipped
