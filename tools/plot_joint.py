#!/usr/bin/python3
"""The joint outputs of a run with a pretension section: figures and a table.

    plot_joint.py RESULT.h5 [-o PREFIX] [--section 1] [--interface 1]

Writes PREFIX_joint.png (the joint diagram: bolt force F_S and clamp force F_K against the
service load F_A, to separation), PREFIX_cone.png (the joint interface's pressure along r at the
preload, the largest service load, after unloading and at the end, with the contact radius) and
PREFIX_joint.md (F_V, Phi, k_S, k_P, the separation load, and the diagram's points); prints the
table.  docs/bolts.md explains the quantities (module k2d.joint).

Past the separation: the separation load is bracketed by the last increment k whose joint
interface carries force and the next one, and estimated inside that bracket by extrapolating the
clamp force of the increments k-1 and k to zero; the chord load factor Phi_k = (F_S,k - F_V)/F_A,k
gives the textbook F_V/(1 - Phi_k) beside it (the rough interface softens as it unloads: the
initial Phi underestimates the separation load).  The pressure cone then also shows increment k,
the last before the separation.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from k2d.joint import interface_pressure, joint_history, joint_summary  # noqa: E402
from k2d.results import Result  # noqa: E402


def fmt(v, f="%.5g"):
    return "-" if v is None else f % v


def separation(h):
    """(k, k+1, estimate, chord Phi_k) of the first separation on a rising service load, or None."""
    fa, fs, fk = h["F_A"], h["F_S"], h["F_K"]
    for k1 in range(1, len(fa)):
        k = k1 - 1
        if fa[k1] > fa[k] and fk[k] > 0.0 and not fk[k1] > 0.0:
            est = fa[k1]
            if k >= 1 and fk[k - 1] > fk[k] and fa[k] > fa[k - 1]:
                est = fa[k] + fk[k] * (fa[k] - fa[k - 1]) / (fk[k - 1] - fk[k])
            phi = (fs[k] - fs[0]) / fa[k] if fa[k] > 0 else None
            return k, k1, float(min(max(est, fa[k]), fa[k1])), phi
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("-o", "--prefix", default="")
    ap.add_argument("--section", type=int, default=1)
    ap.add_argument("--interface", type=int, default=1)
    args = ap.parse_args()
    res = Result(args.result)
    prefix = args.prefix or os.path.splitext(args.result)[0]
    h = joint_history(res, args.section, args.interface)
    if len(h["F_S"]) == 0:
        print("plot_joint: %s has no pretension section" % args.result)
        return 2
    s = joint_summary(h)
    sep = separation(h)
    if sep is not None:
        s["separation"] = sep[2]
    lines = ["| quantity | value |", "|---|---|",
             "| preload F_V | %s |" % fmt(s["F_V"]),
             "| section shortening at the preload | %s |" % fmt(s["delta_V"]),
             "| load factor Φ = dF_S/dF_A | %s |" % fmt(s["Phi"], "%.4f"),
             "| bolt stiffness k_S | %s |" % fmt(s["k_S"]),
             "| members' stiffness k_P | %s |" % fmt(s["k_P"]),
             "| separation load F_A (clamp force 0) | %s |" % (fmt(s["separation"]) if s["separation"] else
                                                             "not reached"),
             ]
    if sep is not None:
        k, k1, est, phi = sep
        pred = s["F_V"] / (1.0 - phi) if phi is not None else None
        lines += ["| separation between increments | %d (F_A = %.6g, F_K = %.4g) and %d "
                  "(F_A = %.6g, F_K = 0) |" % (h["steps"][k], h["F_A"][k], h["F_K"][k],
                                               h["steps"][k1], h["F_A"][k1]),
                  "| chord load factor Φ_k = (F_S,k − F_V)/F_A,k | %s |" % fmt(phi, "%.4f"),
                  "| F_V/(1 − Φ_k) | %s |" % fmt(pred),
                  "| F_V/(1 − Φ), Φ the initial tangent | %s |"
                  % fmt(s["F_V"] / (1.0 - s["Phi"])),
                  "| largest F_S − F_A past the separation | %s |"
                  % fmt(float(np.max(np.abs(h["F_S"][k1:] - h["F_A"][k1:]))), "%.3g")]
    lines += ["", "| increment | F_A | F_S | F_K | shortening |", "|---|---|---|---|---|"]
    for k in range(len(h["F_S"])):
        lines.append("| %d | %.6g | %.8g | %.6g | %.6g |" % (h["steps"][k], h["F_A"][k], h["F_S"][k], h["F_K"][k],
                                                            h["shortening"][k]))
    text = "\n".join(lines)
    print(text)
    with open(prefix + "_joint.md", "w") as f:
        f.write(text + "\n")

    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(h["F_A"], h["F_S"], "o-", label="bolt force F_S")
    ax.plot(h["F_A"], h["F_K"], "s-", label="clamp force F_K (joint interface)")
    if s["Phi"] is not None:
        fa = np.linspace(0.0, max(h["F_A"].max(), 1e-300), 50)
        ax.plot(fa, s["F_V"] + s["Phi"] * fa, "k:", lw=1, label="F_V + Φ F_A, Φ = %.3f" % s["Phi"])
        ax.plot(fa, s["F_V"] - (1.0 - s["Phi"]) * fa, "k--", lw=1, label="F_V - (1 - Φ) F_A")
        ax.plot(fa, fa, "g-.", lw=1, label="F_S = F_A (separated)")
    if s["separation"]:
        ax.axvline(s["separation"], color="r", lw=1, label="separation F_A = %.4g" % s["separation"])
    ax.set_xlabel("service load F_A")
    ax.set_ylabel("force")
    ax.set_title("Joint diagram: %s" % os.path.basename(args.result))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(prefix + "_joint.png", dpi=120)
    plt.close(fig)

    # the interface's pressure at the preload, the largest service load, after unloading, the end
    steps = {s_.number: s_ for s_ in res.steps}
    picks = []
    i_pre = int(np.argmax(h["F_A"] > 1e-9 * max(h["F_S"].max(), 1e-300))) - 1
    picks.append(("preload", h["steps"][max(i_pre, 0)]))
    fa = h["F_A"]
    down = [k for k in range(len(fa) - 1) if fa[k + 1] < fa[k]]
    i_top = down[0] if down else int(np.argmax(fa))
    picks.append(("largest F_A of the first stroke", h["steps"][i_top]))
    after = [k for k in range(i_top, len(fa)) if fa[k] <= 1e-9 * h["F_S"].max()]
    if after:
        picks.append(("unloaded", h["steps"][after[0]]))
    if sep is not None:
        k = sep[0]
        mid = [j for j in range(max(i_top, after[0] if after else 0), k)
               if fa[j] >= 0.5 * (fa[i_top] + fa[k])]
        if mid:
            picks.append(("F_A = %.4g" % fa[mid[0]], h["steps"][mid[0]]))
        picks.append(("last before separation, F_A = %.4g" % fa[k], h["steps"][k]))
    else:
        picks.append(("end", h["steps"][-1]))
    fig, ax = plt.subplots(figsize=(7, 5))
    seen = set()
    for label, n in picks:
        if n in seen:
            continue
        seen.add(n)
        r, p, rc = interface_pressure(res, steps[int(n)], args.interface)
        line, = ax.plot(r, p, "o-", ms=3, label="%s (increment %d), contact radius %.3g" % (label, n, rc))
        if rc > 0:
            ax.axvline(rc, color=line.get_color(), lw=0.8, ls=":")
    ax.set_xlabel("r")
    ax.set_ylabel("interface pressure")
    ax.set_title("Pressure cone: the joint interface")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(prefix + "_cone.png", dpi=120)
    plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
