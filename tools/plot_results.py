#!/usr/bin/python3
"""Plot a Kontakt2D result file: deformed mesh coloured by a stress measure.

Reads only what docs/results-format.md documents.

    tools/plot_results.py RESULTS.h5 [-o PLOT.png] [--increment N]
                          [--component mises|xx|yy|xy|zz] [--scale S]

When the file holds contact results (group `contact` in the increment), a
second panel shows the contact pressure and shear along the contact surface.
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402

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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("-o", "--output", default=None, help="PNG file (default: results name with .png)")
    ap.add_argument("--increment", type=int, default=0, help="increment number (default: the last)")
    ap.add_argument("--component", default="mises", choices=["mises"] + list(COMPONENTS))
    ap.add_argument("--scale", type=float, default=None, help="displacement magnification (default: automatic)")
    args = ap.parse_args(argv)

    with h5py.File(args.results, "r") as f:
        incs = sorted(f["increments"].keys())
        if not incs:
            sys.exit(f"{args.results}: no completed increment to plot")
        key = incs[-1] if args.increment == 0 else "%05d" % args.increment
        if key not in f["increments"]:
            sys.exit(f"{args.results}: no increment {args.increment} (have {incs[0]}..{incs[-1]})")
        g = f["increments"][key]
        xy = f["mesh/coordinates"][...]
        conn = f["mesh/connectivity"][...]
        nnode = f["mesh/element_nodes"][...]
        u = g["displacement"][...]
        s = g["stress_nodal"][...]
        lam = g.attrs["load_factor"]
        title = f.attrs["title"]
        title = title.decode() if isinstance(title, bytes) else str(title)
        ntype = int(f.attrs["ntype"])
        contact = None
        if "contact" in g:
            c = g["contact"]
            contact = {k: c[k][...] for k in c.keys()}
            contact["position"] = f["contact/position"][...]     # written once, in /contact

    size = max(np.ptp(xy[:, 0]), np.ptp(xy[:, 1]))
    umax = np.abs(u).max()
    scale = args.scale if args.scale is not None else (0.05 * size / umax if umax > 0 else 1.0)
    values = von_mises(s) if args.component == "mises" else s[:, COMPONENTS[args.component]]
    label = {"mises": "von Mises stress", "xx": "stress xx (rr)", "yy": "stress yy (zz)",
             "xy": "shear stress xy", "zz": "stress zz (hoop)"}[args.component]

    npanel = 2 if contact is not None else 1
    fig, axes = plt.subplots(1, npanel, figsize=(7 * npanel, 6), squeeze=False)
    ax = axes[0, 0]
    d = xy + scale * u
    tri = mtri.Triangulation(d[:, 0], d[:, 1], triangles(conn, nnode))
    pc = ax.tripcolor(tri, values, shading="gouraud", cmap="viridis")
    for ring in outline(conn, nnode):
        ax.plot(d[ring, 0], d[ring, 1], color="k", lw=0.3)
    fig.colorbar(pc, ax=ax, label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("r" if ntype == 3 else "x")
    ax.set_ylabel("z" if ntype == 3 else "y")
    ax.set_title(f"{title}\nincrement {int(key)}, load factor {np.round(lam, 4)}, displacements x {scale:.3g}",
                 fontsize=9)

    if contact is not None:
        ax2 = axes[0, 1]
        pos = contact["position"]
        order = np.argsort(pos[:, 0])
        ax2.plot(pos[order, 0], contact["pressure"][order], "o-", label="normal pressure p_n")
        ax2.plot(pos[order, 0], contact["shear"][order], "s-", label="shear stress p_T")
        ax2.set_xlabel("r" if ntype == 3 else "x")
        ax2.set_ylabel("contact stress")
        ax2.grid(True, alpha=0.3)
        ax2.legend()
        ax2.set_title("contact stresses", fontsize=9)

    out = args.output or args.results.rsplit(".", 1)[0] + ".png"
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"plot: {out}")


if __name__ == "__main__":
    main()
