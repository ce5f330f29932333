#!/usr/bin/python3
"""The joint diagram of a bolted joint taken past its separation (joint_separation.dat).

    check_joint.py RESULT.h5 [CHECK_FILE]

Run as the check tool of run_good_deck.cmake: first the deck's own expected values
(CHECK_FILE, by tests/decks/check_deck.py's module k2d.checks), then three statements of the
joint diagram (docs/bolts.md, "Past the separation"), each printed with what it measured:

(a) beyond the separation (every pair of the joint interface open) the bolt force equals the
    service load, F_S = F_A -- the joint's force balance with the clamp force gone.  F_S is the
    section's force from the elements at the cut, F_A both the sum of the supports' reactions and
    the closed form of the applied traction (100 N/mm2 on 10 <= r <= 14: 9600 pi per unit factor).
    Both are exact to the solution's out-of-balance force (CONVERGE TOLR 1e-10 of the increment;
    the bodies' imbalance is checked to 1e-8): 1e-8 relative is allowed.
(b) the separation load against F_V/(1 - Phi), Phi the chord of the joint diagram measured from
    the run at the last increment k whose joint interface still carries force:
    Phi = (F_S,k - F_V)/F_A,k.  The rough interface softens as it unloads, so the joint diagram is
    no straight line and Phi must be the chord's up to the separation, not the initial tangent;
    the run resolves the separation only to its increment: F_V/(1 - Phi) must lie between F_A,k
    and F_A,k+1 (the first increment with the interface open), and within one increment of load
    of the separation load extrapolated from the clamp force of the increments k-1 and k.
(c) the service load's unload/reload is exact on the rough law: at every pair of increments of
    the service cycle (before the separation) with the same load factors, the same state -- bolt
    force, displacements, the rough interface's pressures.  The law is reversible between u_res
    and the reversal point A (docs/contact.md), the plates' interface frictionless; what is left
    is the ideal pairs under the head and nut, converged to AUGMENTED TOL 1e-10 of their element
    length (their pressures to 5e-8 of the peak; the bolt force, displacements and rough pressures
    to 6e-12 ... 5e-10 of theirs, measured): 1e-8 of each quantity's peak is allowed.  With the
    default TOL 1e-6 the bolt force differs by 2e-5, with Coulomb friction 0.2 on the plates'
    interface by 3e-4: both fail.
Exit 0 when all hold, 1 otherwise.
"""
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.normpath(os.path.join(HERE, "..", "..", "..", "tools"))
sys.path.insert(0, TOOLS)
from k2d.joint import joint_history  # noqa: E402
from k2d.results import Result  # noqa: E402

F_UNIT = 9600.0 * math.pi     # the service load at factor 1: 100 N/mm2 x pi (14^2 - 10^2)
TOL_BALANCE = 1e-8
TOL_CYCLE = 1e-8

failures = []


def report(ok, text):
    print(("PASS " if ok else "FAIL ") + text)
    if not ok:
        failures.append(text)


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    path = sys.argv[1]
    if len(sys.argv) > 2:
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join([TOOLS] + [p for p in [env.get("PYTHONPATH")] if p])
        rc = subprocess.call([sys.executable, os.path.join(HERE, "..", "check_deck.py"), path,
                              sys.argv[2]], env=env)
        if rc != 0:
            return rc
    res = Result(path)
    h = joint_history(res)
    steps = {s.number: s for s in res.steps}
    lam = np.array([float(np.atleast_1d(steps[int(n)].load_factor)[0]) for n in h["steps"]])
    iface = np.asarray(res.contact.interface) == 1
    nclosed = np.array([int(np.sum(np.asarray(steps[int(n)].contact("normal_state"))[iface] > 0))
                        for n in h["steps"]])
    fa, fs, fk = h["F_A"], h["F_S"], h["F_K"]
    report(len(fa) >= 10, "%d increments with the bolt force (>= 10)" % len(fa))

    # (a) beyond the separation: F_S = F_A
    past = np.where((nclosed == 0) & (lam > 0.0))[0]
    report(len(past) >= 2, "(a) %d increments past the separation (>= 2)" % len(past))
    for k in past:
        closed_form = lam[k] * F_UNIT
        e1 = abs(fs[k] - fa[k]) / fa[k]
        e2 = abs(fs[k] - closed_form) / closed_form
        report(max(e1, e2) <= TOL_BALANCE and fk[k] == 0.0,
               "(a) increment %d: F_S = %.10g, F_A = %.10g (reactions; %.10g applied): "
               "relative %.2e, %.2e <= %.0e; clamp force %g" % (h["steps"][k], fs[k], fa[k],
                                                                 closed_form, e1, e2, TOL_BALANCE,
                                                                 fk[k]))

    # (b) the separation load against F_V / (1 - Phi)
    ramp = [k for k in range(1, len(fa))
            if lam[k] > lam[k - 1] and fk[k - 1] > 0.0 and fk[k] == 0.0]
    report(len(ramp) == 1, "(b) the separation found in %d increment(s) (1)" % len(ramp))
    if ramp:
        k1 = ramp[0]
        k = k1 - 1
        f_v = fs[0]
        phi = (fs[k] - f_v) / fa[k]
        phi0 = (fs[1] - f_v) / fa[1]
        pred = f_v / (1.0 - phi)
        sep = fa[k] + fk[k] * (fa[k] - fa[k - 1]) / (fk[k - 1] - fk[k])
        dfa = fa[k1] - fa[k]
        report(fa[k] <= pred <= fa[k1],
               "(b) Phi = %.5f (chord at increment %d, F_A = %.6g): F_V/(1 - Phi) = %.6g "
               "within the increment of the separation [%.6g, %.6g]"
               % (phi, h["steps"][k], fa[k], pred, fa[k], fa[k1]))
        report(abs(pred - sep) <= dfa,
               "(b) F_V/(1 - Phi) = %.6g against the clamp force's zero %.6g: %.3g <= one "
               "increment %.6g (%.2e relative); the initial tangent Phi_0 = %.5f would give %.6g"
               % (pred, sep, abs(pred - sep), dfa, abs(pred - sep) / sep, phi0, f_v / (1 - phi0)))

    # (c) equal load factors in the service cycle, the same state
    cycle = [k for k in range(len(fa)) if nclosed[k] > 0]
    pairs = [(a, b) for i, a in enumerate(cycle) for b in cycle[i + 1:]
             if abs(lam[a] - lam[b]) <= 1e-12]
    report(len(pairs) >= 4, "(c) %d pairs of increments at equal service load (>= 4)" % len(pairs))
    u = {k: steps[int(h["steps"][k])].field("displacement") for k in range(len(fa))}
    umax = max(np.max(np.abs(v)) for v in u.values())
    pmax = max(np.max(np.abs(np.asarray(steps[int(n)].contact("pressure"))[iface]))
               for n in h["steps"])
    for a, b in pairs:
        sa, sb = steps[int(h["steps"][a])], steps[int(h["steps"][b])]
        ef = abs(fs[a] - fs[b]) / fs[a]
        eu = np.max(np.abs(u[a] - u[b])) / umax
        pa = np.asarray(sa.contact("pressure"))[iface]
        pb = np.asarray(sb.contact("pressure"))[iface]
        ep = np.max(np.abs(pa - pb)) / pmax
        report(max(ef, eu, ep) <= TOL_CYCLE,
               "(c) increments %d and %d (factor %.3g): bolt force %.2e, displacements %.2e, rough "
               "pressures %.2e <= %.0e" % (h["steps"][a], h["steps"][b], lam[a], ef, eu, ep,
                                           TOL_CYCLE))
    print("%d check(s) failed" % len(failures) if failures else "all joint checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
