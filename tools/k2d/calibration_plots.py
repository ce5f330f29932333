"""One figure per calibration fit: the data, the fitted law and its residuals, and the
closures (or tractions) Kontakt2D computed with the written cards when the loop was closed
(k2d.calibration_replay).  matplotlib with the Agg backend; PNG at 80 dpi."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from k2d import calibration as cal  # noqa: E402

__all__ = ["DPI", "COLOURS", "plot_normal", "plot_tangent", "plot_friction"]

DPI = 80
COLOURS = {"L": "tab:blue", "U": "tab:orange", "R": "tab:green"}


def _figure():
    fig, (ax, ar) = plt.subplots(2, 1, figsize=(6.4, 5.6), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    fig.subplots_adjust(left=0.13, right=0.97, top=0.93, bottom=0.1, hspace=0.08)
    return fig, ax, ar


def _finish(fig, ax, ar, path, title, xlabel, ylabel, rlabel, headroom=False):
    ax.set_title(title, fontsize=10)
    ax.set_ylabel(ylabel)
    ar.set_xlabel(xlabel)
    ar.set_ylabel(rlabel)
    ar.axhline(0.0, color="0.5", lw=0.8)
    ax.grid(alpha=0.3)
    ar.grid(alpha=0.3)
    if headroom:
        # room above the curves for the legend
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi + 0.45 * (hi - lo))
        ax.legend(fontsize=7, loc="upper left", ncol=2)
    else:
        ax.legend(fontsize=7, loc="lower right")
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path


def _dense_history(p, per=24):
    """A history (from 0) with `per` points between consecutive rows: the same reversals."""
    out = [np.linspace(0.0, p[0], per + 1)[1:]]
    for a, b in zip(p[:-1], p[1:]):
        out.append(np.linspace(a, b, per + 1)[1:])
    return np.concatenate(out)


def plot_normal(fit, path, replay=None):
    t, units = fit.table, fit.units
    ucol, pcol = t.column("u"), t.column("p")
    us = units.length / ucol.scale                 # card length -> data length
    p_data, u_data = t.values["p"], t.values["u"]
    c, m = fit.value("c_n"), fit.value("m")
    fig, ax, ar = _figure()
    for b in ("L", "U", "R"):
        sel = fit.code == b
        if np.any(sel):
            ax.plot(p_data[sel], u_data[sel], "o", ms=3.5, mfc="none", color=COLOURS[b],
                    label="data, %s" % cal.BRANCH_NAMES[b])
    if fit.loading_only:
        pd = np.linspace(0.0, float(np.max(fit.p)), 300)
        ax.plot(pd * units.pressure / pcol.scale, cal.virgin(pd, c, m) * us, "-", color="k", lw=1.0,
                label="fit: c_n = %.4g, m = %.4g" % (c, m))
    else:
        c2, m2 = fit.value("c_n2"), fit.value("m2")
        pd = _dense_history(fit.p)
        code, rev = cal.normal_history(pd)
        ud = cal.normal_closure(pd, rev, c, m, c2, m2)
        ax.plot(pd * units.pressure / pcol.scale, ud * us, "-", color="k", lw=1.0,
                label="fit: c_n = %.4g, m = %.4g, c_n2 = %.4g, m2 = %.4g" % (c, m, c2, m2))
    if replay is not None:
        rows = replay.rows
        ax.plot(replay.pressure[rows], replay.computed[rows], "+", color="tab:red", ms=6,
                label="Kontakt2D with the cards")
    res = fit.model - fit.u
    for b in ("L", "U", "R"):
        sel = (fit.code == b) & fit.fitted
        if np.any(sel):
            ar.plot(p_data[sel], res[sel] * us, "o", ms=3, mfc="none", color=COLOURS[b])
    return _finish(fig, ax, ar, path, "Normal law, %s (UNITS %s)" % (_name(fit.path), units.card),
                   "p [%s]" % pcol.unit, "closure u [%s]" % ucol.unit, "fit - data [%s]" % ucol.unit)


def plot_tangent(fit, path, replay=None):
    t, units = fit.table, fit.units
    utcol, ptcol = t.column("ut"), t.column("pt")
    ls = units.length / utcol.scale
    ps = units.pressure / ptcol.scale
    fig, ax, ar = _figure()
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, (idx, lv) in enumerate(zip(fit.curves, fit.levels)):
        col = colours[j % len(colours)]
        ax.plot(t.values["ut"][idx], t.values["pt"][idx], "o", ms=3, mfc="none", color=col,
                label="data, p_n = %.4g %s" % (lv * units.pressure / t.column("pn").scale, t.column("pn").unit))
        ud = _dense_history(fit.ut[idx], per=12)
        pd, _ = cal.tangent_curve(ud, lv, fit.R, fit.S, fit.mu, fit.kappa, fit.hardening)
        ax.plot(np.concatenate([[0.0], ud]) * ls, np.concatenate([[0.0], pd]) * ps, "-", color=col, lw=1.0)
        ar.plot(t.values["ut"][idx], (fit.model[idx] - fit.pt[idx]) * ps, "o", ms=3, mfc="none", color=col)
        if replay is not None:
            ax.plot(t.values["ut"][idx], replay.computed[idx], "+", color="tab:red", ms=5,
                    label="Kontakt2D with the cards" if j == 0 else None)
    ax.plot([], [], "-", color="k", lw=1.0, label="fit: R = %.4g, S = %.4g%s" % (
        fit.R, fit.S, "" if fit.mu is None else ", mu = %.4g%s" % (
            fit.mu, ", kappa = %.4g" % fit.kappa if fit.hardening else "")))
    return _finish(fig, ax, ar, path, "Tangential law, %s (UNITS %s)" % (_name(fit.path), units.card),
                   "u_T [%s]" % utcol.unit, "p_T [%s]" % ptcol.unit, "fit - data [%s]" % ptcol.unit,
                   headroom=True)


def plot_friction(fit, path):
    t, units = fit.table, fit.units
    scol = t.column("slip")
    fig, ax, ar = _figure()
    v_data = t.values["slip"]
    ax.plot(v_data, fit.mu, "o", ms=3, mfc="none", color="tab:blue", label="data")
    vd = np.linspace(0.0, float(np.max(fit.v)), 400)
    mu_m, beta, n = fit.value("mu_m"), fit.value("beta"), fit.value("n")
    ax.plot(vd * units.model_length / scol.scale, cal.fredriksson(vd, mu_m, beta, n), "-", color="k", lw=1.0,
            label="fit: mu_m = %.4g, beta = %.4g, n = %.4g 1/%s" % (mu_m, beta, n, units.model[0]))
    ar.plot(v_data, fit.model - fit.mu, "o", ms=3, mfc="none", color="tab:blue")
    return _finish(fig, ax, ar, path, "Friction law (Fredriksson), %s" % _name(fit.path),
                   "effective slip v_e [%s]" % scol.unit, "friction coefficient", "fit - data")


def _name(path):
    return os.path.basename(path)
