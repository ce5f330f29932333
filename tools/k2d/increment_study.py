"""The increment study: increment count against error for each contact scheme
(docs/accuracy-and-stability.md); tools/increment_study.py is the command line and describes it.

    from k2d import increment_study as st
    rows = st.measure(exe, work)       # run every case, scheme and increment count in `work`
    st.write_csv(path, rows); st.chart(rows, png)

Reads the results through k2d.results only.
"""
import os
import re
import subprocess
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import laws  # noqa: E402
from .build import ROOT  # noqa: E402
from .results import Result  # noqa: E402
from .tables import write_csv as write_csv_table  # noqa: E402

__all__ = ["CASES", "COUNTS", "SCHEMES", "KGF", "make_deck", "run", "measure", "write_csv", "chart"]

CASES = {
    "V1 normal patch test": os.path.join(ROOT, "tests", "decks", "contact", "v1_plane_q4.dat"),
    "punch, example 5.1 (coarse)": os.path.join(ROOT, "tests", "decks", "stability", "s2_first_increment_large.dat"),
}
COUNTS = [2, 3, 5, 10, 20, 40, 80]
SCHEMES = ["INCREMENTAL", "INCREMENTAL+ITERATE", "NEWTON"]
KGF = laws.KGF_PER_NMM2


def make_deck(base, n, scheme, path):
    """The base deck with N increments (5 % first) and the given scheme."""
    text = open(base).read()
    if n > 1:
        incs = "INCREMENTS\n    1      0.05\n%5d       1.0\nEND\n" % (n - 1)
    else:
        incs = "INCREMENTS\n    1       1.0\nEND\n"
    text = re.sub(r"INCREMENTS\n.*?END\n", incs, text, flags=re.S)
    first = "ITERATE" if scheme.endswith("+ITERATE") else "SECANT"
    scheme = scheme.split("+")[0]
    text = re.sub(r"^(SCHEME|UPDATE|FIRSTINC) .*\n", "", text, flags=re.M)
    text = text.replace("CONTACT\n", "CONTACT\nSCHEME    " + scheme + "\nFIRSTINC  " + first + "\n", 1)
    text = text.replace("REPEATS ", "#REPEATS ")
    with open(path, "w") as f:
        f.write(text)


def run(exe, deck, out):
    """Run a deck into the result file `out`; returns ({pressure, closure of the last increment,
    solutions of the run}, wall s, the terminal's error output), None for the first on failure."""
    t0 = time.perf_counter()
    r = subprocess.run([exe, deck, "-q", "-o", out], capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode not in (0, 4):          # 4: completed with doubts (the explicit scheme's drift)
        return None, dt, r.stderr.strip()
    result = Result(out)
    last = result.last
    res = {"pressure": last.contact("pressure"), "closure": last.contact("closure"),
           "solutions": int(sum(s.attrs["iterations"] for s in result.steps))}
    return res, dt, r.stderr.strip()


def measure(exe, work):
    """Every case, scheme and increment count of the study, run in the folder `work`: rows of
    increment_study.csv.  RuntimeError when the reference run fails."""
    rows = []
    for case, base in CASES.items():
        tag = "v1" if case.startswith("V1") else "punch"
        if tag == "v1":
            reference = None
        else:
            deck = os.path.join(work, "punch_reference.dat")
            make_deck(base, 160, "NEWTON", deck)
            ref, _, err = run(exe, deck, deck[:-4] + ".h5")
            if ref is None:
                raise RuntimeError("reference run failed: " + err)
            reference = ref["pressure"]
        for scheme in SCHEMES:
            for n in COUNTS:
                deck = os.path.join(work, f"{tag}_{scheme.lower().replace('+', '_')}_{n}.dat")
                make_deck(base, n, scheme, deck)
                res, dt, err = run(exe, deck, deck[:-4] + ".h5")
                if res is None:
                    rows.append([case, scheme, n, float("nan"), float("nan"), 0, round(dt, 3), "failed: " + err[:120]])
                    continue
                if reference is None:
                    uexact = 1e-3 * KGF ** 0.5          # c_n = 1 um/(kgf/cm2)^0.5, m = 0.5, p0 = 1 N/mm2
                    error = abs(res["closure"].max() / uexact - 1.0)
                    perr = abs(res["pressure"].max() - 1.0)
                else:
                    error = float(np.max(np.abs(res["pressure"] - reference) / reference))
                    perr = error
                rows.append([case, scheme, n, error, perr, res["solutions"], round(dt, 3), ""])
                print(f"{case:30s} {scheme:12s} N={n:4d}  error {error:9.3e}  solutions {res['solutions']:4d}")
    return rows


def write_csv(path, rows):
    """increment_study.csv (numbers as Python writes them)."""
    write_csv_table(path, ["case", "scheme", "increments", "error", "pressure_error", "solutions", "wall_s", "note"],
                    rows, fmt=None)


def chart(rows, png):
    """increment_study.png: the error against the number of increments, per case and scheme."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, case in zip(axes, CASES):
        for scheme, marker in zip(SCHEMES, ["o-", "^-", "s-"]):
            sel = [r for r in rows if r[0] == case and r[1] == scheme and r[3] == r[3]]
            n = [r[2] for r in sel]
            e = [max(r[3], 1e-12) for r in sel]
            ax.loglog(n, e, marker, label=scheme.lower())
        ax.loglog(COUNTS, [0.5 / c for c in COUNTS], "k:", lw=0.8, label="1/N")
        ax.set_xlabel("increments N (5 % first)")
        ax.set_ylabel("closure error" if case.startswith("V1") else "max pressure error vs reference")
        ax.set_title(case, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    plt.close(fig)
