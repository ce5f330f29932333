"""The paper's examples (Altenbach & Buczkowski, section 5): run the decks of k2d.examples and
turn their results into the paper's tables and figures, each beside the paper's own numbers
(CSV, PNG and Markdown).  tools/paper_figures.py is the command line.

    from k2d import paper
    paper.run_examples(exe, out, names, jobs)     # write the decks into out/decks and run them
    paper.draw(out, "5.1")                        # the tables and figures of one example into out
    paper.EXAMPLES                                # "5.1" -> (deck name prefix, drawing function)

Reads the results through k2d.results only.
"""
import csv
import math
import os

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import examples as ex  # noqa: E402
from . import laws  # noqa: E402
from .analysis import Pairs, at, contact_radius, rel  # noqa: E402
from .batch import run_decks  # noqa: E402
from .published import TABLE1, TABLE1_LABEL, TABLE1_X, TABLE2_Q8, TABLE2_Q8B, TABLE2_T3  # noqa: E402
from .results import Result  # noqa: E402
from .tables import markdown_table, write_csv  # noqa: E402

__all__ = ["DPI", "run_examples", "load", "radius", "md_table", "savefig", "example_51", "hertz_p", "example_52",
           "example_53", "EXAMPLES", "names_of", "draw"]

DPI = 90


# ============================================================================ running
def run_examples(exe, out, names, jobs):
    """Write the decks `names` of k2d.examples.variants() into out/decks and run them (results in
    out/h5, terminal output and listings in out/logs); out/runtimes.csv gets their exit codes
    and wall times.  Returns {name: (exit code, seconds)}."""
    os.makedirs(os.path.join(out, "decks"), exist_ok=True)
    print("writing %d decks ..." % len(names), flush=True)
    paths = ex.write_variants(os.path.join(out, "decks"), set(names))
    done = run_decks(exe, paths, out, jobs, report=lambda name, rc, dt: print(
        "  %-36s %s %7.1f s" % (name, "ok " if rc == 0 else "rc=%d" % rc, dt), flush=True))
    old = {}
    rt = os.path.join(out, "runtimes.csv")
    if os.path.exists(rt):
        with open(rt) as f:
            old = {r["deck"]: r for r in csv.DictReader(f)}
    for name, (rc, dt) in done.items():
        old[name] = {"deck": name, "exit_code": rc, "seconds": "%.2f" % dt}
    with open(rt, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["deck", "exit_code", "seconds"])
        w.writeheader()
        for name in sorted(old):
            w.writerow(old[name])
    return done


# ============================================================================ reading results
def load(out, name):
    """The contact pairs of out/h5/<name>.h5 (k2d.analysis.Pairs), None if the run left no
    result file or no increment."""
    path = os.path.join(out, "h5", name + ".h5")
    if not os.path.exists(path):
        return None
    r = Result(path)
    return Pairs(r) if r.steps else None


def radius(r):
    """The contact radius of the last increment (k2d.analysis.contact_radius)."""
    return contact_radius(r.x, r.last("closure"), r.last("normal_state"))


def _csv(out, name, header, rows):
    write_csv(os.path.join(out, name), header, rows)


def md_table(md, title, header, rows, fmt=None):
    md.append(markdown_table(title, header, rows, fmt))


def savefig(fig, out, name):
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=DPI)
    plt.close(fig)


# ============================================================================ example 5.1
def example_51(out, md):
    # column 5 is the paper's ideal model (LAW IDEAL); the rough normal law without tangential
    # springs (its former stand-in) is reported beside it
    cols = {c: load(out, "punch_col%d" % c) for c in range(1, 5)}
    cols[5] = load(out, "punch_col5_ideal")
    rough5 = load(out, "punch_col5")
    if any(v is None for v in cols.values()):
        print("5.1: results missing, skipped")
        return
    xs = np.array(TABLE1_X) * 50.0
    # ---- Table 1
    rows = []
    for i, s in enumerate(TABLE1_X):
        row = [s]
        for c in range(1, 6):
            r = cols[c]
            ut = 1e3 * at(r.x, r.last("slip"), xs[i])
            up = 1e3 * at(r.x, r.last("slip_irreversible"), xs[i]) if c != 5 else ut
            row += [TABLE1[c][0][i], ut, rel(ut, TABLE1[c][0][i]) if i else float("nan"), TABLE1[c][1][i], up]
        ur = 1e3 * at(rough5.x, rough5.last("slip"), xs[i]) if rough5 is not None else float("nan")
        row += [ur, rel(ur, TABLE1[5][0][i]) if i else float("nan"), rel(ur, row[-4]) if i else float("nan")]
        rows.append(row)
    header = ["2x/B"]
    for c in range(1, 6):
        header += ["c%d uT paper" % c, "c%d uT ours" % c, "c%d uT diff %%" % c, "c%d uTp paper" % c, "c%d uTp ours" % c]
    header += ["c5 uT rough law", "c5 rough diff %", "c5 rough vs ideal %"]
    _csv(out, "table1.csv", header, rows)
    for c in range(1, 5):
        md_table(md, "Table 1, column %d: %s (u in um)" % (c, TABLE1_LABEL[c]),
                 ["2x/B", "u_T paper", "u_T ours", "diff %", "u_T^p paper", "u_T^p ours", "state"],
                 [[r[0], r[1 + 5 * (c - 1)], r[2 + 5 * (c - 1)], r[3 + 5 * (c - 1)], r[4 + 5 * (c - 1)],
                   r[5 + 5 * (c - 1)],
                   {0: "stick", 1: "branch", 2: "slip"}[int(at(cols[c].x, cols[c].last("tangential_state"), xs[i]))]]
                  for i, r in enumerate(rows)], fmt={"diff %": "%+.1f", "2x/B": "%.2f"})
    md_table(md, "Table 1, column 5: %s (u in um; u_T^p = u_T, frictionless); beside it the rough normal law "
             "without tangential springs (FRICTION NONE), the former stand-in" % TABLE1_LABEL[5],
             ["2x/B", "u_T paper", "u_T ideal", "diff %", "u_T rough", "rough diff %", "rough vs ideal %"],
             [[r[0], r[21], r[22], r[23], r[26], r[27], r[28]] for r in rows],
             fmt={"diff %": "%+.1f", "rough diff %": "%+.1f", "rough vs ideal %": "%+.1f", "2x/B": "%.2f"})

    fig, axs = plt.subplots(1, 2, figsize=(10, 4.2))
    colors = {1: "C3", 2: "C0", 3: "C2", 4: "C1", 5: "C4"}
    for c in range(1, 6):
        r = cols[c]
        axs[0].plot(r.x / 50.0, 1e3 * r.last("slip"), "-", color=colors[c],
                    label="ours, col. %d%s" % (c, " (ideal law)" if c == 5 else ""))
        axs[0].plot(TABLE1_X, TABLE1[c][0], "o", color=colors[c], mfc="none", ms=5)
        up = 1e3 * (r.last("slip") if c == 5 else r.last("slip_irreversible"))
        axs[1].plot(r.x / 50.0, up, "-", color=colors[c])
        axs[1].plot(TABLE1_X, TABLE1[c][1], "o", color=colors[c], mfc="none", ms=5)
    if rough5 is not None:
        axs[0].plot(rough5.x / 50.0, 1e3 * rough5.last("slip"), ":", color=colors[5],
                    label="col. 5, rough normal law")
    axs[0].plot([], [], "ko", mfc="none", label="paper (Table 1)")
    axs[0].set_title("total tangential displacement u_T", fontsize=10)
    axs[1].set_title("irreversible part u_T^p (col. 5: u_T^p = u_T)", fontsize=10)
    for ax in axs:
        ax.set_xlabel("2x/B")
        ax.set_ylabel("um")
        ax.grid(alpha=0.3)
    axs[0].legend(fontsize=7)
    fig.suptitle("Example 5.1, Table 1: punch on foundation, Q4, 20 increments", fontsize=10)
    savefig(fig, out, "table1.png")

    # ---- Table 2
    t3, q4, q8 = load(out, "punch_col2_t3"), cols[2], load(out, "punch_col2_q8")
    rows = []
    for lab, r, ref in (("T3", t3, TABLE2_T3), ("Q4", q4, TABLE2_T3), ("Q8", q8, TABLE2_Q8)):
        if r is None:
            continue
        for k, x in enumerate(ref["x"]):
            pn, pt = at(r.x, r.last("pressure"), x, 1e-3), at(r.x, r.last("shear"), x, 1e-3)
            st = int(at(r.x, r.last("tangential_state"), x, 1e-3))
            rows.append([lab, x, ref["pn"][k], pn, rel(pn, ref["pn"][k]), ref["pT"][k], pt,
                         rel(pt, ref["pT"][k]) if k else float("nan"), pt / pn,
                         {0: "stick", 2: "slip"}.get(st, "branch")])
    header = ["mesh", "x", "pn paper", "pn ours", "pn diff %", "pT paper", "pT ours", "pT diff %", "pT/pn ours",
              "state"]
    _csv(out, "table2.csv", header, rows)
    md_table(md, "Table 2: contact stresses, Coulomb 0.2 (column 2); N/mm2; paper's 3-node values for T3 and Q4, "
             "its first 8-node block for Q8", header, rows,
             fmt={"x": "%.3f", "pn diff %": "%+.1f", "pT diff %": "%+.1f", "pn paper": "%.4f", "pn ours": "%.4f",
                  "pT paper": "%.4f", "pT ours": "%.4f", "pT/pn ours": "%.4f"})
    fig, axs = plt.subplots(1, 2, figsize=(10, 4.2))
    for lab, r, st in (("T3", t3, "-"), ("Q4", q4, "--"), ("Q8", q8, ":")):
        if r is None:
            continue
        axs[0].plot(r.x, r.last("pressure"), st, label="ours, " + lab)
        axs[1].plot(r.x, r.last("shear"), st, label="ours, " + lab)
    for ref, mk, lab in ((TABLE2_T3, "o", "paper, 3-node"), (TABLE2_Q8, "s", "paper, 8-node"),
                         (TABLE2_Q8B, "^", "paper, 8-node (2nd block)")):
        axs[0].plot(ref["x"], ref["pn"], mk, mfc="none", color="k", label=lab)
        axs[1].plot(ref["x"], ref["pT"], mk, mfc="none", color="k", label=lab)
    axs[0].set_title("normal pressure p_n", fontsize=10)
    axs[1].set_title("shear stress p_T", fontsize=10)
    for ax in axs:
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("N/mm2")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Example 5.1, Table 2: contact stresses, Coulomb mu = 0.2, no hardening branch", fontsize=10)
    savefig(fig, out, "table2.png")

    # ---- acceptance targets of SPEC 6.1
    acc = []
    c2, c5 = cols[2], cols[5]
    ut2 = [1e3 * at(c2.x, c2.last("slip"), x) for x in xs]
    ut5 = [1e3 * at(c5.x, c5.last("slip"), x) for x in xs]
    d5 = max(abs(rel(ut5[i], TABLE1[5][0][i])) for i in range(1, 13))
    acc.append(["col 5: u_T within 10 % at every node", "max |diff| = %.1f %%" % d5, d5 <= 10.0])
    d2 = max(abs(rel(ut2[i], TABLE1[2][0][i])) for i in range(1, 12))
    acc.append(["col 2: u_T within 20 % for 0.1 <= 2x/B <= 0.95", "max |diff| = %.1f %%" % d2, d2 <= 20.0])
    de = abs(rel(ut2[12], TABLE1[2][0][12]))
    acc.append(["col 2: u_T within 25 % at the edge", "%.1f %%" % de, de <= 25.0])
    st = c2.last("tangential_state")
    slipset = sorted(round(x / 50.0, 3) for x in c2.x[st == 2])
    acc.append(["col 2: slipping set = {0.9, 0.95, 1.0}", str(slipset), slipset == [0.9, 0.95, 1.0]])
    ratio = (c2.last("shear") / c2.last("pressure"))[st == 2]
    dev = float(np.max(np.abs(ratio - 0.2))) if len(ratio) else float("nan")
    acc.append(["col 2: p_T/p_n = 0.2000 +- 1e-6 at slipping nodes", "max |p_T/p_n - 0.2| = %.1e" % dev, dev <= 1e-6])
    pn = [at(c2.x, c2.last("pressure"), x) for x in TABLE2_T3["x"]]
    dc = abs(rel(pn[0], TABLE2_T3["pn"][0]))
    acc.append(["p_n at the centre within 3 % (Table 2, 3-node)", "%.1f %%" % dc, dc <= 3.0])
    dm = max(abs(rel(pn[k], TABLE2_T3["pn"][k])) for k in (3, 4, 5, 6))
    acc.append(["p_n within 8 % for 0.6 <= 2x/B <= 0.95", "max %.1f %%" % dm, dm <= 8.0])
    dd = abs(rel(pn[7], TABLE2_T3["pn"][7]))
    acc.append(["p_n at the edge within 15 %", "%.1f %%" % dd, dd <= 15.0])
    fsum = float(np.sum(c2.last("force_normal")))
    acc.append(["sum F_n = 600 N to 1e-8", "%.10g N (rel. %.1e)" % (fsum, abs(fsum / 600.0 - 1)),
                abs(fsum / 600.0 - 1) <= 1e-8])
    up = 1e3 * c2.last("slip_irreversible")
    ok = bool(np.all(up[st != 2] == 0.0) and np.all(up[st == 2] > 0) and np.all(np.diff(up[st == 2]) > 0))
    acc.append(["col 2: u_T^p > 0 exactly at the slipping nodes, growing towards the edge",
                " ".join("%.3f" % v for v in up[st == 2]) + " um", ok])
    c3 = cols[3]
    up3 = 1e3 * c3.last("slip_irreversible")
    onset = float(c3.x[np.where(up3 > 0)[0].min()] / 50.0) if np.any(up3 > 0) else float("nan")
    acc.append(["col 3: slip onset at 2x/B <= 0.3, u_T^p monotonic, edge u_T^p 2-4 um",
                "onset %.2f, edge %.2f um" % (onset, up3[-1]),
                onset <= 0.3 + 1e-9 and bool(np.all(np.diff(up3) >= 0)) and 2.0 <= up3[-1] <= 4.0])
    _csv(out, "acceptance_5_1.csv", ["target (SPEC 6.1)", "measured", "met"], acc)
    md_table(md, "Example 5.1: the acceptance targets of SPEC §6.1", ["target (SPEC 6.1)", "measured", "met"],
             [[a, b, "yes" if c else "**no**"] for a, b, c in acc])

    # ---- sensitivity to the assumptions
    rows = []
    variants = (("", "reference: hp = hf = 100 mm, Q4, 20 increments, EXPLICIT"),
                ("_gross", "effective slip = gross slip only (SLIP GROSS)"),
                ("_n550", "hardening rate n = 550/mm (twice the printed value)"),
                ("_hp50", "punch height 50 mm"), ("_hp190", "punch height 190 mm"),
                ("_hf75", "foundation height 75 mm"), ("_hf150", "foundation height 150 mm"),
                ("_fine", "mesh refined 2 x 2"), ("_t3", "T3 elements"), ("_q8", "Q8 (other contact nodes)"),
                ("_n10", "10 increments"), ("_n40", "40 increments"),
                ("_newton", "NEWTON (on the laws, converged)"))
    for c in (2, 5, 3, 1):
        runs = [("punch_col%d%s" % (c, tag), label) for tag, label in variants]
        if c == 5:
            runs = [("punch_col5_ideal%s" % tag, label.replace(", 20 increments, EXPLICIT", ", ideal law"))
                    for tag, label in variants] + [
                ("punch_col5", "rough normal law, FRICTION NONE (former stand-in), EXPLICIT"),
                ("punch_col5_newton", "rough normal law, FRICTION NONE, NEWTON")]
        for name, label in runs:
            tag = name[len("punch_col%d" % c):]
            r = load(out, name)
            if r is None:
                continue
            u50 = 1e3 * at(r.x, r.last("slip"), 25.0)
            u100 = 1e3 * at(r.x, r.last("slip"), 50.0)
            up100 = 1e3 * at(r.x, r.last("slip_irreversible"), 50.0) if c != 5 else u100
            p0 = at(r.x, r.last("pressure"), 0.0)
            pe = at(r.x, r.last("pressure"), 50.0)
            pt40 = at(r.x, r.last("shear"), 40.0) if tag != "_q8" else at(r.x, r.last("shear"), 250 / 6)
            st = r.last("tangential_state")
            nslip = int(np.sum(st == 2))
            rows.append([c, label, u50, rel(u50, TABLE1[c][0][5]), u100, rel(u100, TABLE1[c][0][12]), up100,
                         TABLE1[c][1][12], p0, pe, pt40 if c != 5 else float("nan"), nslip if c != 5 else "—",
                         float(r.result.last.attrs.get("law_drift", float("nan")))])
    header = ["col", "variant", "u_T(0.5) um", "diff %", "u_T(1.0) um", "diff % ", "u_T^p(1.0) um", "paper",
              "p_n(0)", "p_n(edge)", "p_T(0.8)", "slipping nodes", "law drift"]
    _csv(out, "sensitivity_5_1.csv", header, rows)
    md_table(md, "Example 5.1: sensitivity to the assumptions (differences against Table 1)", header, rows,
             fmt={"diff %": "%+.1f", "diff % ": "%+.1f", "p_n(0)": "%.4f", "p_n(edge)": "%.4f", "p_T(0.8)": "%.4f",
                  "law drift": "%.3f"})
    # (col 1 and col 3 are not targets of SPEC 6.1; their rows show what moves them)

    # ---- Bild 5: load and unloading at the punch edge
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    rows = []
    for cn2, col in ((0.5, "C0"), (0.25, "C3")):
        r = load(out, "punch_fig5_cn2_%g" % cn2)
        if r is None:
            continue
        k = int(np.argmax(r.position[:, 0]))
        u = np.array([1e3 * s.contact("closure")[k] for s in r.steps])
        p = np.array([s.contact("pressure")[k] for s in r.steps])
        lam = np.array([s.load_factor[0] for s in r.steps])
        ns = np.array([s.contact("normal_state")[k] for s in r.steps])
        imax = int(np.argmax(lam))
        closed = ns > 0
        ax.plot(np.r_[0.0, p[:imax + 1]], np.r_[0.0, u[:imax + 1]], "k.-", lw=1, ms=3,
                label="loading (virgin curve)" if cn2 == 0.5 else None)
        j = np.where(closed[imax:])[0] + imax
        ax.plot(p[j], u[j], ".-", color=col, ms=3, label="unloading, c_n2 = %g" % cn2)
        # the residual closure of the unloading branch at the reversal point A
        ua, pa = u[imax], p[imax]
        ures = laws.residual_closure(ua, ex.KGF * pa, cn2, 0.5)     # um, kgf/cm2
        ax.plot([p[j[-1]], 0.0], [u[j[-1]], ures], ":", color=col)
        ax.plot([0.0], [ures], "o", color=col)
        ax.annotate("B (c_n2 = %g): %.2f um" % (cn2, ures), (0.0, ures), xytext=(0.25, ures - 0.35), fontsize=8,
                    color=col)
        for i in range(len(lam)):
            rows.append([cn2, i + 1, lam[i], p[i], u[i], int(ns[i])])
        rows.append([cn2, "B", 0.0, 0.0, ures, 0])
    pp = np.linspace(0.0, 2.3, 200)
    ax.plot(pp, laws.virgin_closure(ex.KGF * pp, 1.0, 0.5), "--", color="0.5", lw=1,
            label="virgin curve u = c_n p^m (exact)")
    ax.set_xlabel("normal pressure p_n at the punch edge [N/mm2]")
    ax.set_ylabel("closure u_n [um]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Example 5.1, Bild 5: load and unloading at the punch edge\n(tangential springs off; "
                 "c_n = 1.0, m = m2 = 0.5; B = irreversible closure)", fontsize=9)
    savefig(fig, out, "fig5_load_unload.png")
    _csv(out, "fig5_load_unload.csv", ["c_n2", "increment", "load factor", "p_n edge", "u_n edge um",
                                            "normal state"], rows)


# ============================================================================ example 5.2
def hertz_p(r, P):
    a, p0, _ = ex.hertz_sphere(P)
    return p0 * np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))


def example_52(out, md):
    res = {(P, s): load(out, "sphere_P%d_%s" % (P, s)) for P in ex.SPHERE_LOADS for s in ex.SPHERE_SURFACES}
    if res[(200.0, "smooth")] is None:
        print("5.2: results missing, skipped")
        return
    styles = {"smooth": ("k", "smooth (ideal law)"), "c0.3": ("C0", "rough, c_n = 0.3"),
              "c0.8": ("C3", "rough, c_n = 0.8")}
    for P, fname, bild in ((200.0, "fig7_sphere_200N", 7), (20000.0, "fig8_sphere_20kN", 8)):
        a, p0, d0 = ex.hertz_sphere(P)
        fig, ax = plt.subplots(figsize=(7, 4.5))
        rr = np.linspace(0, 2.2 * a, 400)
        ax.plot(rr / a, hertz_p(rr, P) / p0, "-", color="0.6", lw=4, alpha=0.5, label="Hertz")
        rows = []
        for s, (col, lab) in styles.items():
            r = res[(P, s)]
            if r is None:
                continue
            ax.plot(r.x / a, r.last("pressure") / p0, "-", color=col,
                    label=lab + ("" if s == "smooth" else " (NEWTON)"))
            for x, p in zip(r.x, r.last("pressure")):
                rows.append([s, "NEWTON", x, p, float(hertz_p(np.array([x]), P)[0])])
            rp = load(out, "sphere_P%d_%s_paper" % (P, s))
            if rp is not None:
                ax.plot(rp.x / a, rp.last("pressure") / p0, "--", color=col, lw=1,
                        label=lab + ", paper's scheme (NSTART 3, 40 inc.)")
                for x, p in zip(rp.x, rp.last("pressure")):
                    rows.append([s, "paper", x, p, float(hertz_p(np.array([x]), P)[0])])
        ax.set_xlim(0, 2.2)
        ax.set_xlabel("r / a_H   (a_H = %.4f mm)" % a)
        ax.set_ylabel("p_n / p_0H   (p_0H = %.1f N/mm2)" % p0)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        ax.set_title("Example 5.2, Bild %d: sphere on half-space, P = %g N" % (bild, P), fontsize=10)
        savefig(fig, out, fname + ".png")
        _csv(out, fname + ".csv", ["surface", "scheme", "r mm", "p_n N/mm2", "p Hertz N/mm2"], rows)

    # ---- peak pressures and radii at every load
    rows = []
    for P in ex.SPHERE_LOADS:
        a, p0, d0 = ex.hertz_sphere(P)
        for s in ex.SPHERE_SURFACES:
            r = res[(P, s)]
            if r is None:
                continue
            ac = radius(r)
            pc = float(r.last("pressure")[0])
            cn = ex.SPHERE_SURFACES[s]
            alpha = (1e-3 * cn * (ex.KGF * p0) ** 0.5 / d0) if cn else 0.0
            rows.append([P, s, a, ac, ac / a, p0, pc, pc / p0, alpha, 1e3 * (r.x[1] - r.x[0]),
                         int(r.result.last.attrs.get("invariant_violations", 0))])
    header = ["P N", "surface", "a_H mm", "a_c mm", "a_c/a_H", "p_0H", "p(0)", "p(0)/p_0H", "alpha_eq",
              "h um", "violations"]
    _csv(out, "fig9_contact_radius.csv", header, rows)
    md_table(md, "Example 5.2: contact radius and peak pressure (NEWTON, converged); alpha_eq = c_n p_0H^m / delta_H "
             "(SPEC V15)", header, rows,
             fmt={"P N": "%g", "a_H mm": "%.4f", "a_c mm": "%.4f", "a_c/a_H": "%.3f", "p_0H": "%.1f", "p(0)": "%.1f",
                  "p(0)/p_0H": "%.3f", "alpha_eq": "%.3f", "h um": "%.1f"})
    fig, axs = plt.subplots(1, 2, figsize=(10, 4.2))
    PP = np.logspace(np.log10(40), np.log10(25000), 100)
    axs[0].loglog(PP, [ex.hertz_sphere(p)[0] for p in PP], "-", color="0.6", lw=4, alpha=0.5, label="Hertz")
    for s, (col, lab) in styles.items():
        sel = [r for r in rows if r[1] == s]
        axs[0].loglog([r[0] for r in sel], [r[3] for r in sel], "o-", color=col, label=lab)
        axs[1].semilogx([r[0] for r in sel], [r[4] for r in sel], "o-", color=col, label=lab + ": a_c / a_H")
        axs[1].semilogx([r[0] for r in sel], [r[7] for r in sel], "s--", color=col, mfc="none",
                        label=lab + ": p(0) / p_0H")
    axs[0].set_xlabel("P [N]")
    axs[0].set_ylabel("contact radius a_c [mm]")
    axs[0].set_title("Bild 9: real contact radius against the load", fontsize=10)
    axs[1].set_xlabel("P [N]")
    axs[1].set_title("relative to Hertz", fontsize=10)
    axs[1].axhline(1.0, color="0.6")
    for ax in axs:
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    savefig(fig, out, "fig9_contact_radius.png")

    # ---- convergence and assumptions
    rows = []

    def add(name, label, ref=None):
        r = load(out, name)
        if r is None:
            return
        P = float(name.split("_")[1][1:])
        a, p0, d0 = ex.hertz_sphere(P)
        ac, pc = radius(r), float(r.last("pressure")[0])
        rr = ref if ref is not None else None
        rows.append([P, label, 1e3 * (r.x[1] - r.x[0]), pc / p0, ac / a,
                     rel(pc, rr[0]) if rr else float("nan"), rel(ac, rr[1]) if rr else float("nan"),
                     float(r.result.last.attrs.get("law_drift", float("nan")))])
        return pc, ac

    for P in (200.0, 20000.0):
        ref = add("sphere_P%d_c0.8" % P, "c_n = 0.8, reference: Q4, h = a_H/20, rho = 120, NEWTON")
        add("sphere_P%d_c0.8_h10" % P, "h = a_H/10", ref)
        add("sphere_P%d_c0.8_h40" % P, "h = a_H/40", ref)
        add("sphere_P%d_c0.8_q8" % P, "Q8, h = a_H/10", ref)
        add("sphere_P%d_c0.8_rho60" % P, "half-space radius 60 mm", ref)
        add("sphere_P%d_c0.8_rho240" % P, "half-space radius 240 mm", ref)
        add("sphere_P%d_c0.8_n5" % P, "NEWTON, 5 increments instead of 20", ref)
        add("sphere_P%d_c0.8_paper" % P, "paper's scheme, NSTART 3, 40 increments", ref)
        if P == 200.0:
            add("sphere_P200_c0.8_paper_n20", "paper's scheme, 20 increments", ref)
            add("sphere_P200_c0.8_paper_n80", "paper's scheme, 80 increments", ref)
            add("sphere_P200_c0.8_paper_iterate", "paper's scheme, FIRSTINC ITERATE", ref)
            add("sphere_P200_c0.8_paper_nstart40", "paper's scheme, NSTART 40", ref)
        refs = add("sphere_P%d_smooth" % P, "smooth (ideal law), h = a_H/20")
        add("sphere_P%d_smooth_h40" % P, "smooth (ideal law), h = a_H/40", refs)
        add("sphere_P%d_penalty" % P, "smooth (penalty limit, former stand-in), h = a_H/20", refs)
    header = ["P N", "variant", "h um", "p(0)/p_0H", "a_c/a_H", "p(0) diff %", "a_c diff %", "law drift"]
    _csv(out, "sphere_convergence.csv", header, rows)
    md_table(md, "Example 5.2: convergence and sensitivity (differences against the reference of each block)",
             header, rows, fmt={"P N": "%g", "h um": "%.1f", "p(0)/p_0H": "%.4f", "a_c/a_H": "%.4f",
                                "p(0) diff %": "%+.2f", "a_c diff %": "%+.2f", "law drift": "%.3f"})
    # smooth reference (ideal law) against Hertz (V6), and its former stand-in, the penalty limit
    rows = []
    for P in ex.SPHERE_LOADS:
        r = res[(P, "smooth")]
        if r is None:
            continue
        a, p0, d0 = ex.hertz_sphere(P)
        p = r.last("pressure")
        m = r.x <= 0.9 * a
        rms = float(np.sqrt(np.mean((p[m] - hertz_p(r.x[m], P)) ** 2)) / p0)
        row = [P, rel(float(p[0]), p0), rel(float(p.max()), p0), 100 * rms, radius(r) / a,
               1e3 * (r.x[1] - r.x[0]) / a / 1e3, float(np.sum(r.last("force_normal")) / P - 1.0)]
        rp = load(out, "sphere_P%d_penalty" % P)
        if rp is not None and np.allclose(rp.x, r.x):
            pp = rp.last("pressure")
            row += [rel(float(pp[0]), p0), 100.0 * float(np.max(np.abs(pp - p))) / p0,
                    radius(rp) / a]
        else:
            row += [float("nan")] * 3
        rows.append(row)
    header = ["P N", "p(0) vs p_0H %", "peak vs p_0H %", "RMS(p - p_H)/p_0H %", "a_c/a_H", "h/a_H", "sum F_n/P - 1",
              "penalty: p(0) vs p_0H %", "max |p_pen - p_ideal|/p_0H %", "penalty: a_c/a_H"]
    _csv(out, "sphere_hertz_check.csv", header, rows)
    md_table(md, "Example 5.2: the smooth surface (ideal law) against Hertz (SPEC V6); beside it the penalty limit "
             "of the rough law (the former stand-in)", header, rows,
             fmt={"P N": "%g", "p(0) vs p_0H %": "%+.2f", "peak vs p_0H %": "%+.2f", "RMS(p - p_H)/p_0H %": "%.2f",
                  "a_c/a_H": "%.4f", "h/a_H": "%.3f", "sum F_n/P - 1": "%.1e", "penalty: p(0) vs p_0H %": "%+.2f",
                  "max |p_pen - p_ideal|/p_0H %": "%.3f", "penalty: a_c/a_H": "%.4f"})


# ============================================================================ example 5.3
def example_53(out, md):
    r0 = load(out, "cyl_100kN_c0.44_E4e4")
    if r0 is None:
        print("5.3: results missing, skipped")
        return
    area = math.pi * (ex.CYL_RA ** 2 - ex.CYL_RI ** 2)
    cols = {0.2: "C3", 0.44: "C0", 1.0: "C2"}
    rows = []
    for lk, P in ex.CYL_LOADS.items():
        pm = P / area
        fig, axs = plt.subplots(1, 2, figsize=(10, 4.2))
        # the smooth surface: ideal law with Coulomb 0.3 (its pressure and shear are singular
        # at both edges: the axes are cut at the rough curves' range), and frictionless
        sm = load(out, "cyl_%s_ideal_E4e4" % lk)
        sm0 = load(out, "cyl_%s_ideal0_E4e4" % lk)
        if sm is not None:
            axs[0].plot(sm.x, sm.last("pressure") / pm, "-", color="0.6", lw=3, alpha=0.6,
                        label="smooth (ideal law), mu = 0.3")
            axs[1].plot(sm.x, sm.last("shear") / pm, "-", color="0.6", lw=3, alpha=0.6,
                        label="smooth (ideal law), mu = 0.3")
        if sm0 is not None:
            axs[0].plot(sm0.x, sm0.last("pressure") / pm, "--", color="0.4", lw=1,
                        label="smooth (ideal law), frictionless")
        tmax = 0.0
        for cn in ex.CYL_CN:
            r = load(out, "cyl_%s_c%g_E4e4" % (lk, cn))
            if r is None:
                continue
            axs[0].plot(r.x, r.last("pressure") / pm, "-", color=cols[cn], label="c_n = %g" % cn)
            axs[1].plot(r.x, r.last("shear") / pm, "-", color=cols[cn], label="c_n = %g" % cn)
            tmax = max(tmax, float(np.max(np.abs(r.last("shear")))) / pm)
            rp = load(out, "cyl_%s_c%g_E4e7" % (lk, cn))
            if rp is not None and cn == 0.2:
                axs[0].plot(rp.x, rp.last("pressure") / pm, ":", color="k", label="printed E = 4e7, c_n = 0.2")
            for x, p, t, s in zip(r.x, r.last("pressure"), r.last("shear"), r.last("tangential_state")):
                rows.append([lk, cn, x, p / pm, t / pm, int(s)])
        axs[0].set_title("normal pressure p_n / p_m", fontsize=10)
        axs[1].set_title("shear stress p_T / p_m (positive outwards on the half-space)", fontsize=9)
        for ax in axs:
            ax.set_xlabel("r [mm]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
        if sm is not None:
            axs[0].set_ylim(0, max(4.0, 1.1 * max(float(np.max(load(out, "cyl_%s_c0.2_E4e4" % lk).last("pressure")))
                                                  / pm, 1.0)))
            if tmax > 0.0:
                axs[1].set_ylim(-1.6 * tmax, 1.6 * tmax)
        bild = {"10kN": "Bild 12", "1MN": "Bild 11", "100kN": "text"}[lk]
        fig.suptitle("Example 5.3 (%s): rigid hollow cylinder on half-space, P = %s, p_m = %.3g N/mm2, "
                     "E = 4e4 N/mm2 (D10)" % (bild, lk, pm), fontsize=10)
        savefig(fig, out, "fig_cylinder_%s.png" % lk)
    _csv(out, "cylinder_pressure.csv", ["load", "c_n", "r mm", "p_n/p_m", "p_T/p_m", "tangential state"], rows)

    # ---- summary: uniformity, edge peaks, slip, moduli
    rows = []
    for lk, P in ex.CYL_LOADS.items():
        pm = P / area
        for ek in ex.CYL_MODULI:
            for cn in ex.CYL_CN:
                r = load(out, "cyl_%s_c%g_%s" % (lk, cn, ek))
                if r is None:
                    continue
                p = r.last("pressure") / pm
                t = r.last("shear") / pm
                st = r.last("tangential_state")
                rows.append([lk, ek, cn, float(p.min()), float(p[0]), float(p[-1]), float(p.max() - p.min()),
                             float(np.max(np.abs(t))), int(np.sum(st == 2)),
                             float(np.sum(r.last("force_normal")) / P - 1.0)])
        for tag, lab in (("ideal_E4e4", "smooth, ideal, mu = 0.3"), ("ideal0_E4e4", "smooth, ideal, frictionless"),
                         ("penalty_E4e4", "smooth, penalty (former stand-in)"),
                         ("c0.2_E4e4_newton", "0.2 NEWTON"), ("c0.2_E4e4_fine", "0.2 h/2"),
                         ("c0.2_E4e4_n40", "0.2, 40 inc."), ("c0.2_E4e4_rho250", "0.2, radius 250"),
                         ("c0.2_E4e4_rho1000", "0.2, radius 1000"), ("c0.2_E4e4_branch", "0.2, branch on"),
                         ("c0.2_E4e4_ties", "0.2, tied mesh (TIES)"), ("c1_E4e4_ties", "1.0, tied mesh (TIES)"),
                         ("ideal_E4e4_ties", "smooth, ideal, mu = 0.3, tied mesh")):
            r = load(out, "cyl_%s_%s" % (lk, tag))
            if r is None:
                continue
            p = r.last("pressure") / pm
            t = r.last("shear") / pm
            rows.append([lk, "E4e4", lab, float(p.min()), float(p[0]), float(p[-1]), float(p.max() - p.min()),
                         float(np.max(np.abs(t))), int(np.sum(r.last("tangential_state") == 2)),
                         float(np.sum(r.last("force_normal")) / P - 1.0)])
    header = ["load", "moduli", "c_n", "min p/p_m", "p(R_I)/p_m", "p(R_A)/p_m", "spread", "max |p_T|/p_m",
              "slipping", "sum F_n/P - 1"]
    _csv(out, "cylinder_summary.csv", header, rows)
    md_table(md, "Example 5.3: pressure spread (max - min of p_n/p_m), edge values and shear", header, rows,
             fmt={"min p/p_m": "%.3f", "p(R_I)/p_m": "%.3f", "p(R_A)/p_m": "%.3f", "spread": "%.3f",
                  "max |p_T|/p_m": "%.3f", "sum F_n/P - 1": "%.1e"})
    # ---- cross-checks: the rigid body against the tied mesh, the ideal law against the penalty
    # limit (its former stand-in), friction against none on the smooth surface
    rows = []
    pairs = [("cyl_%s_c0.2_E4e4" % lk, "cyl_%s_c0.2_E4e4_ties" % lk, "rigid body vs tied mesh, c_n = 0.2")
             for lk in ex.CYL_LOADS]
    pairs += [("cyl_1MN_c1_E4e4", "cyl_1MN_c1_E4e4_ties", "rigid body vs tied mesh, c_n = 1.0"),
              ("cyl_1MN_ideal_E4e4", "cyl_1MN_ideal_E4e4_ties", "rigid body vs tied mesh, ideal, mu = 0.3")]
    pairs += [("cyl_%s_ideal0_E4e4" % lk, "cyl_%s_penalty_E4e4" % lk, "frictionless: ideal vs penalty")
              for lk in ex.CYL_LOADS]
    pairs += [("cyl_%s_ideal_E4e4" % lk, "cyl_%s_ideal0_E4e4" % lk, "ideal: mu = 0.3 vs frictionless")
              for lk in ex.CYL_LOADS]
    for a, b, lab in pairs:
        ra, rb = load(out, a), load(out, b)
        if ra is None or rb is None or not np.allclose(ra.x, rb.x):
            continue
        P = ex.CYL_LOADS[a.split("_")[1]]
        pm = P / area
        pa, pb = ra.last("pressure") / pm, rb.last("pressure") / pm
        ta, tb = ra.last("shear") / pm, rb.last("shear") / pm
        rows.append([a.split("_")[1], lab, float(np.max(np.abs(pa - pb))), float(np.max(np.abs(ta - tb))),
                     float(pa[0]), float(pb[0]), float(pa[-1]), float(pb[-1])])
    header = ["load", "comparison", "max |dp|/p_m", "max |dp_T|/p_m", "p(R_I)/p_m first", "p(R_I)/p_m second",
              "p(R_A)/p_m first", "p(R_A)/p_m second"]
    _csv(out, "cylinder_crosscheck.csv", header, rows)
    md_table(md, "Example 5.3: cross-checks (first against second of each comparison)", header, rows,
             fmt={"max |dp|/p_m": "%.1e", "max |dp_T|/p_m": "%.1e", "p(R_I)/p_m first": "%.4f",
                  "p(R_I)/p_m second": "%.4f", "p(R_A)/p_m first": "%.4f", "p(R_A)/p_m second": "%.4f"})
    # the moduli: why the printed ones cannot be meant
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for ek, st in (("E4e4", "-"), ("E2.1e5", "--"), ("E4e7", ":")):
        for cn in (0.2, 1.0):
            r = load(out, "cyl_100kN_c%g_%s" % (cn, ek))
            if r is not None:
                ax.plot(r.x, r.last("pressure") / (1e5 / area), st, color=cols[cn],
                        label="E = %s, c_n = %g" % (ek[1:], cn))
    ax.set_xlabel("r [mm]")
    ax.set_ylabel("p_n / p_m")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Example 5.3, P = 100 kN: the half-space modulus. With the printed 4e7 N/mm2\n"
                 "the pressure is uniform for every c_n (SPEC D10)", fontsize=9)
    savefig(fig, out, "fig_cylinder_moduli.png")


# ============================================================================ drawing
EXAMPLES = {"5.1": ("punch_", example_51), "5.2": ("sphere_", example_52), "5.3": ("cyl_", example_53)}


def names_of(which):
    """The deck names of k2d.examples.variants() that the examples `which` ("5.1", ...) need."""
    return [n for n in ex.variants() if any(n.startswith(EXAMPLES[w][0]) for w in which)]


def draw(out, which):
    """The tables and figures of example `which` ("5.1", "5.2" or "5.3") from the results in
    out/h5, into out; its Markdown tables into out/tables_<which>.md."""
    md = []
    EXAMPLES[which][1](out, md)
    with open(os.path.join(out, "tables_%s.md" % which.replace(".", "_")), "w") as f:
        f.write("# Example %s: the tables of tools/paper_figures.py\n\n" % which + "\n".join(md))
