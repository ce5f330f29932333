"""A picture of a result file: the deformed mesh coloured by a stress measure and, when the
file holds contact results, the contact pressure and shear along the contact surface (slipping
pairs marked).  tools/plot_results.py is the command line.

    from k2d.plot import plot_result
    png = plot_result("run.h5", increment=0, component="mises")   # the last increment; returns the PNG path

Reads the results through k2d.results only.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402

from .history import unit_labels  # noqa: E402
from .results import Result  # noqa: E402

__all__ = ["COMPONENTS", "von_mises", "triangles", "outline", "load_factor_text", "plot_result"]

COMPONENTS = {"xx": 0, "yy": 1, "xy": 2, "zz": 3}


def von_mises(s):
    """Von Mises stress of (xx, yy, xy, zz) rows."""
    sxx, syy, sxy, szz = s[:, 0], s[:, 1], s[:, 2], s[:, 3]
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxy ** 2)


def triangles(conn, nnode):
    """Split every element into triangles over its corner nodes (0-based)."""
    tris = []
    for e, n in zip(conn, nnode):
        c = e[:3] if n == 3 else e[:4]
        c = c - 1
        if len(c) == 3:
            tris.append(c)
        else:
            tris.append([c[0], c[1], c[2]])
            tris.append([c[0], c[2], c[3]])
    return np.array(tris)


def outline(conn, nnode):
    """Element boundary polylines through corner and midside nodes (0-based)."""
    lines = []
    for e, n in zip(conn, nnode):
        e = e - 1
        if n == 3:
            ring = [e[0], e[1], e[2]]
        elif n == 4:
            ring = [e[0], e[1], e[2], e[3]]
        else:
            ring = [e[0], e[4], e[1], e[5], e[2], e[6], e[3], e[7]]
        lines.append(ring + [ring[0]])
    return lines


def load_factor_text(lam):
    """The load factors of an increment for a title: one number per load case."""
    lam = np.atleast_1d(lam)
    if lam.size == 1:
        return "load factor %.4g" % lam[0]
    return "load factors " + ", ".join("%.4g (case %d)" % (v, k + 1) for k, v in enumerate(lam))


def plot_result(path, output=None, increment=0, component="mises", scale=None, zoom="auto"):
    """Draw increment `increment` (0: the last) of the result file `path` into the PNG `output`
    (default: the result's name with .png); returns its path.  component: mises, xx, yy, xy
    or zz; scale: the displacement magnification (None: automatic); zoom "auto" shows the mesh
    around a contact zone that is small against the model, "none" the whole model.  ValueError
    when the file has no such increment."""
    res = Result(path)
    if not res.steps:
        raise ValueError(f"{path}: no completed increment to plot")
    if increment == 0:
        step = res.last
    else:
        try:
            step = res.step(increment)
        except KeyError:
            raise ValueError(f"{path}: no increment {increment} "
                             f"(have {res.steps[0].name}..{res.steps[-1].name})") from None
    xy = res.mesh.coordinates
    conn = res.mesh.connectivity
    nnode = res.mesh.element_nodes
    u = step.field("displacement")
    s = step.field("stress_nodal")
    lam = step.load_factor
    title = str(res.attrs["title"])
    ntype = int(res.attrs["ntype"])
    contact = None
    if res.contact is not None:
        contact = step.contact_all() or None
        if contact is not None:
            # the pair definition (positions, areas) is written once, in /contact
            for k in ("position", "area", "node_a", "node_b"):
                contact[k] = getattr(res.contact, k)

    size = max(np.ptp(xy[:, 0]), np.ptp(xy[:, 1]))
    window = None
    if contact is not None and zoom == "auto":
        # a contact zone small against the model: show the mesh around it
        closed = contact["normal_state"] > 0
        pts = contact["position"][closed] if closed.any() else contact["position"]
        ext = max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1]), 1e-12)
        if ext < 0.1 * size:
            c = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
            half = 1.5 * ext
            window = (max(c[0] - half, xy[:, 0].min()), min(c[0] + half, xy[:, 0].max()),
                      max(c[1] - half, xy[:, 1].min()), min(c[1] + half, xy[:, 1].max()))
    if window is not None:
        inside = ((xy[:, 0] >= window[0]) & (xy[:, 0] <= window[1]) & (xy[:, 1] >= window[2]) & (xy[:, 1] <= window[3]))
        umax = np.abs(u[inside]).max() if inside.any() else np.abs(u).max()
        span = window[1] - window[0]
    else:
        umax = np.abs(u).max()
        span = size
    scale = scale if scale is not None else (0.05 * span / umax if umax > 0 else 1.0)
    values = von_mises(s) if component == "mises" else s[:, COMPONENTS[component]]
    units = unit_labels(res)
    label = {"mises": "von Mises stress", "xx": "stress xx (rr)", "yy": "stress yy (zz)",
             "xy": "shear stress xy", "zz": "stress zz (hoop)"}[component] + " [%s]" % units["stress"]

    npanel = 2 if contact is not None else 1
    fig, axes = plt.subplots(1, npanel, figsize=(7 * npanel, 6), squeeze=False)
    ax = axes[0, 0]
    d = xy + scale * u
    tris = triangles(conn, nnode)
    rings = outline(conn, nnode)
    if window is not None:
        # only the elements near the window (drawing is clipped to it anyway)
        pad = 0.5 * (window[1] - window[0])
        near = np.array([((xy[r, 0] >= window[0] - pad) & (xy[r, 0] <= window[1] + pad) &
                          (xy[r, 1] >= window[2] - pad) & (xy[r, 1] <= window[3] + pad)).any() for r in rings])
        rings = [r for r, k in zip(rings, near) if k]
        tris = tris[np.repeat(near, [1 if n == 3 else 2 for n in nnode])]
    tri = mtri.Triangulation(d[:, 0], d[:, 1], tris)
    shown = np.unique(tris)
    pc = ax.tripcolor(tri, values, shading="gouraud", cmap="viridis",
                      vmin=values[shown].min(), vmax=values[shown].max())
    for ring in rings:
        ax.plot(d[ring, 0], d[ring, 1], color="k", lw=0.3)
    fig.colorbar(pc, ax=ax, label=label)
    ax.set_aspect("equal")
    if window is not None:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    ax.set_xlabel(("r" if ntype == 3 else "x") + " [%s]" % units["length"])
    ax.set_ylabel(("z" if ntype == 3 else "y") + " [%s]" % units["length"])
    note = ""
    if contact is not None:
        closed = contact["normal_state"] > 0
        cmax = float(contact["closure"][closed].max()) if closed.any() else 0.0
        if cmax > 0:
            # the layer has zero thickness: its closure is drawn magnified like every displacement
            note = ("\nnote: the contact layer's closure (up to %.3g %s) is magnified too:"
                    " body A appears sunk up to %.3g %s into body B" % (cmax, units["length"], scale * cmax,
                                                                         units["length"]))
    ax.set_title(f"{title}\nincrement {step.number}, {load_factor_text(lam)}, displacements x {scale:.3g}{note}",
                 fontsize=8)

    if contact is not None:
        ax2 = axes[0, 1]
        pos = contact["position"]
        # abscissa: the coordinate along which the pairs spread most (x or r for a flat surface)
        axis = 0 if np.ptp(pos[:, 0]) >= np.ptp(pos[:, 1]) else 1
        xc = pos[:, axis]
        order = np.argsort(xc)
        xc = xc[order]
        pn, pt = contact["pressure"][order], contact["shear"][order]
        closed = contact["normal_state"][order] > 0
        # slipping: in slip and carrying a normal force (a pair at zero force holds nothing
        # tangentially; 1e-12 of the increment's largest pair force is round-off)
        fn = contact["force_normal"][order]
        slip = closed & (contact["tangential_state"][order] == 2) & (fn > 1e-12 * max(fn.max(), 0.0))
        branch = closed & (contact["tangential_state"][order] == 1)
        ax2.plot(xc, pn, "o-", ms=3, color="C0", label="normal pressure p_n")
        ax2.plot(xc, pt, "s-", ms=3, color="C1", label="shear stress p_T")
        if slip.any():
            ax2.plot(xc[slip], pt[slip], "s", ms=6, color="C3", label="slipping pairs")
        if branch.any():
            ax2.plot(xc[branch], pt[branch], "s", ms=6, mfc="none", color="C2", label="hardening branch")
        if (~closed).any():
            ax2.plot(xc[~closed], np.zeros((~closed).sum()), "x", ms=4, color="0.5", label="open pairs")
            # zoom on the closed part of a contact that opens towards its end
            last = xc[closed].max() if closed.any() else xc.max()
            ax2.set_xlim(xc.min() - 0.02 * (last - xc.min()), last + 0.25 * (last - xc.min()))
        name = ("r" if ntype == 3 else "x") if axis == 0 else ("z" if ntype == 3 else "y")
        ax2.set_xlabel(name + " of the pairs (node b) [%s]" % units["length"])
        ax2.set_ylabel("contact stress [%s]" % units["stress"])
        ax2.axhline(0.0, color="0.7", lw=0.8)
        ax2.grid(True, alpha=0.3)
        ax2.legend(fontsize=8)
        ax2.set_title("contact stresses: %d of %d pairs closed, %d slipping; sum F_n = %.6g"
                      % (closed.sum(), len(closed), slip.sum(), contact["force_normal"].sum()), fontsize=9)

    out = output or path.rsplit(".", 1)[0] + ".png"
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out
