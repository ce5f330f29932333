"""The figure of `tools/calibrate.py topography`: the surface, its power spectral density, the
BEM's pressure-closure curve with the fitted law (and Kontakt2D's closures after --replay), and
the contact area ratio.  matplotlib with the Agg backend; PNG at the calibration plots' DPI."""
import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from k2d import calibration as cal  # noqa: E402
from k2d.calibration_plots import COLOURS, DPI  # noqa: E402
from k2d.topography import POWER_LAW_TOL  # noqa: E402

__all__ = ["radial_psd", "plot_topography"]


def radial_psd(surface, bins=40):
    """The radially averaged PSD C(q) of the periodic sample (q in 1/mm, C in mm^4)."""
    h = surface.heights - surface.heights.mean()
    area = float(np.prod(surface.sizes))
    C = np.abs(np.fft.fftn(h)) ** 2 * area / h.size ** 2
    qs = np.meshgrid(*[2.0 * np.pi * np.fft.fftfreq(n, d=s / n) for n, s in zip(surface.shape, surface.sizes)],
                     indexing="ij")
    q = np.sqrt(sum(x ** 2 for x in qs)).ravel()
    C = C.ravel()
    keep = q > 0
    edges = np.geomspace(q[keep].min(), q.max(), bins + 1)
    idx = np.digitize(q[keep], edges)
    qb, Cb = [], []
    for k in range(1, bins + 1):
        sel = idx == k
        if sel.any():
            qb.append(float(np.mean(q[keep][sel])))
            Cb.append(float(np.mean(C[keep][sel])))
    return np.array(qb), np.array(Cb)


def plot_topography(tf, path, replay=None):
    s, units, fit = tf.surface, tf.fit.units, tf.fit
    p, u, area, branch = tf.curve.arrays()
    P, U = p / units.pressure, u / units.length
    fig, axs = plt.subplots(2, 2, figsize=(10.0, 8.0))
    fig.subplots_adjust(left=0.1, right=0.96, top=0.93, bottom=0.07, hspace=0.3, wspace=0.28)
    fig.suptitle("Normal law from the surface %s" % s.name, fontsize=11)
    ax = axs[0, 0]
    im = ax.imshow(s.heights.T * 1e3, origin="lower", cmap="viridis",
                   extent=[0, s.sizes[0], 0, s.sizes[1]])
    fig.colorbar(im, ax=ax, label="height [um]")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title("levelled surface: rms %.3g um, rms slope %.3g" % (s.rms_height() * 1e3, s.rms_gradient()),
                 fontsize=9)
    ax = axs[0, 1]
    q, C = radial_psd(s)
    ax.loglog(q, C, ".-", ms=3)
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("wavevector q [1/mm]")
    ax.set_ylabel("radial PSD C(q) [mm^4]")
    ax.set_title("power spectral density", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax = axs[1, 0]
    for b in ("L", "U"):
        sel = branch == b
        if sel.any():
            ax.plot(P[sel], U[sel], "o", ms=4, color=COLOURS[b], label="BEM, %s" % cal.BRANCH_NAMES[b])
    # the fitted law: the virgin curve (dashed below PMIN, where it was not fitted) and the unloading branch
    c, m = fit.value("c_n"), fit.value("m")
    pl = P[(branch == "L") & (P > 0)]
    x = np.linspace(0.0, pl[0], 40)
    ax.plot(x, c * x ** m, "--", color="k", lw=0.8)
    x = np.linspace(pl[0], pl[-1], 100)
    ax.plot(x, c * x ** m, "-", color="k", lw=1, label="fitted law")
    if len(fit.constants) == 4:
        c2, m2, pa = fit.value("c_n2"), fit.value("m2"), pl[-1]
        x = np.linspace(0.0, pa, 100)
        ax.plot(x, c * pa ** m - c2 * (pa ** m2 - x ** m2), "-", color="k", lw=1)
    if tf.valid is not None:
        L = branch == "L"
        ax.axvspan(P[L][tf.valid[0]], P[L][tf.valid[1]], color="0.92", zorder=0,
                   label="power law within %g %%" % (100 * POWER_LAW_TOL))
    if replay is not None:
        ax.plot(P[replay.rows], replay.computed[replay.rows], "x", color="tab:red", ms=5, label="Kontakt2D")
    ax.set_xlabel("pressure p [%s]" % units.pressure_name)
    ax.set_ylabel("closure u [%s]" % units.length_name)
    ax.set_title(fit.cards[-1].strip(), fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    ax = axs[1, 1]
    L = (branch == "L") & (P > 0)
    ax.plot(P[L], area[L], "o-", ms=4, label="BEM")
    ax.set_xlabel("pressure p [%s]" % units.pressure_name)
    ax.set_ylabel("contact area ratio A/A0")
    ax.set_title("real contact area", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
