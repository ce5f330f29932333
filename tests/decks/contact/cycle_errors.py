#!/usr/bin/python3
"""Closure error per increment of the load-unload-reload cycle (issue 16), default scheme
(NEWTON) against the paper's (SCHEME INCREMENTAL), and the unload to exactly zero.

    tests/decks/contact/cycle_errors.py KONTAKT2D [WORKDIR]

Runs cycle_default.dat, cycle_incremental.dat, unload_zero.dat, unload_zero_autoinc.dat and
unload_zero_incremental.dat, and prints for every increment the applied pressure, the exact
closure of the normal law (c_n = 1, m = 0.5, c_n2 = 0.5, m2 = 0.5 in um and kgf/cm2) and each
scheme's largest relative closure error over the pairs; then the CPU seconds of each run
(user + system of the child process) and the end state of the unloading to zero."""
import os
import resource
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "tools"))
from k2d import laws  # noqa: E402
from k2d.results import Result  # noqa: E402

CN = laws.model_constant(1.0, 0.5, "KGF_UM")     # mm / (N/mm2)^0.5
CN2 = laws.model_constant(0.5, 0.5, "KGF_UM")


def law(pressures):
    """Exact closures along a pressure path: virgin, then the branch through A = (CN, 1)."""
    out, pa, ua = [], 0.0, 0.0
    for k, p in enumerate(pressures):
        if pa > 0.0 and p < pa:
            out.append(laws.unloading_closure(p, ua, pa, CN2, 0.5))
        else:
            out.append(laws.virgin_closure(p, CN, 0.5))
            if k + 1 < len(pressures) and pressures[k + 1] < p and p >= pa:
                pa, ua = p, laws.virgin_closure(p, CN, 0.5)
    return np.array(out)


def run(exe, deck, work):
    h5 = os.path.join(work, deck + ".h5")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    rc = subprocess.run([exe, os.path.join(HERE, deck + ".dat"), "-q", "-o", h5],
                        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return rc, h5, cpu


def closures(h5):
    r = Result(h5)
    un = np.array([st.contact("closure") for st in r.steps])
    fn = np.array([st.contact("force_normal") for st in r.steps])
    lam = np.array([st.load_factor[0] for st in r.steps])
    sol = np.array([int(np.atleast_1d(st.attrs["iterations"])[0]) for st in r.steps])
    return un, fn, lam, sol, r.status


def main():
    exe = sys.argv[1]
    work = sys.argv[2] if len(sys.argv) > 2 else "."
    res = {}
    for deck in ["cycle_default", "cycle_incremental"]:
        rc, h5, cpu = run(exe, deck, work)
        un, fn, lam, sol, status = closures(h5)
        res[deck] = (un, lam, sol, cpu, rc.returncode, status)
    lam = res["cycle_default"][1]
    exact = law(lam)
    print("| inc | p/p_max | exact closure [mm] | NEWTON error | INCREMENTAL error |")
    print("|----:|--------:|-------------------:|-------------:|------------------:|")
    for i, p in enumerate(lam):
        e = [(res[d][0][i] - exact[i]) / exact[i] for d in ["cycle_default", "cycle_incremental"]]
        e = [x[np.argmax(np.abs(x))] for x in e]
        print("| %d | %.3f | %.6e | %.1e | %+.2f %% |" % (i + 1, p, exact[i], abs(e[0]), 100.0 * e[1]))
    for d in ["cycle_default", "cycle_incremental"]:
        un, lam_d, sol, cpu, rc, status = res[d]
        print("%s: exit %d, status %s, %d solutions, CPU %.3f s" % (d, rc, status, sol.sum(), cpu))
    for deck in ["unload_zero", "unload_zero_autoinc", "unload_zero_incremental"]:
        rc, h5, cpu = run(exe, deck, work)
        print("%s: exit %d, CPU %.3f s, %s" % (deck, rc.returncode, cpu, rc.stderr.strip().splitlines()[-1:] or ""))
        if os.path.exists(h5):
            un, fn, lam_d, sol, status = closures(h5)
            if len(lam_d):
                ures = CN - CN2
                k10 = int(np.argmax(lam_d))
                print("   status %s; %d increments, last load factor %.3g, %d solutions in the last;"
                      " closure error at the end %.1e (u_res = %.6e mm), max |p|/p_max %.1e"
                      % (status, len(lam_d), lam_d[-1], sol[-1],
                         np.max(np.abs(un[-1] - ures)) / ures, ures, np.max(np.abs(fn[-1] / fn[k10]))))


if __name__ == "__main__":
    main()
