#!/usr/bin/python3
"""Check a run of a robust_slip deck: the expected values of its .check file
(k2d.checks, as tests/decks/check_deck.py) and the tangential law replayed.

    check_law.py RESULT.h5 DECK.check

The replay integrates the tangential law of docs/contact.md ("The tangential law after a
reversal": elastic band |F_T - X| <= 0.625 mu F_n, branch of slope kappa K_T^e at its edge,
gross slip at |F_T| = mu F_n, X clamped to |X| <= 0.375 mu F_n) pair by pair over the
committed increments, written here independently of the program: from the committed force
and back force of increment i-1, the committed slip increment, K_T^e = A p_(i-1)^S / R (the
pressure at the start of the increment), the friction coefficient mu(v_e of i-1) (Coulomb
or Fredriksson, SPEC D1) and the committed F_n of increment i.  Every committed F_T must be
the law's to 1e-8 of the pair's mu F_n (the program returns F_T = the law's exactly for the
displacement it converged to; the replay differs from it by the round-off of a difference of
totals, about 1e-15), the friction coefficient mu(v_e) to 1e-12 and the effective slip
v_e = sum |du_T - dF_T/K_T^e| over the non-elastic increments to 1e-8 of its value (plus
1e-12 mm).  The states (stick / branch / slip) must agree except within 1e-8 of a kink.
Increment 1 (the normal load's first step, K_T^e from the start pressure) is checked for
stick only: every pair starts from X = 0.  Prints the solutions of every increment.
Exit 0 when everything holds, 1 otherwise, 2 when the check file is malformed."""
import math
import sys

from k2d import laws
from k2d.checks import CheckFormatError, check_result, parse
from k2d.results import Result

TOL_F = 1.0e-8


def replay(f0, du, ke, kappa, limit, x0, hardening):
    """The tangential law over one increment at fixed F_n: (F_T, X, state 0/1/2, distance
    of the trial from the nearest kink relative to the limit)."""
    ry = 0.625 * limit if hardening else limit
    xcap = max(limit - ry, 0.0)
    x = min(max(x0, -xcap), xcap)
    trial = f0 + ke * du
    if abs(trial - x) <= ry:
        return trial, x, 0, abs(abs(trial - x) - ry)
    s = math.copysign(1.0, trial - x)
    if hardening:
        f = x + s * ry + kappa * (trial - x - s * ry)
        if abs(f) <= limit:
            return f, f - s * ry, 1, min(abs(trial - x) - ry, limit - abs(f))
        # kink to slip: the trial beyond the branch's end
        return s * limit, s * xcap, 2, abs(f) - limit
    return s * limit, s * xcap, 2, abs(trial - x) - ry


def check_law(path):
    r = Result(path)
    ifc = r.contact.interfaces[0]
    mu_m, beta, nh = [float(v) for v in ifc["friction_parameters"]]
    fredriksson = ifc["friction"].startswith("FREDRIKSS")
    hardening = bool(ifc["hardening"])
    kappa = float(ifc["kappa"][0])
    s_exp = float(ifc["tangent_s"][0])
    rt = [float(v) for v in ifc["r_model"]]
    area = r.contact.area
    steps = sorted(r.steps, key=lambda s: s.number)
    bad = []
    if [s.number for s in steps] != list(range(1, len(steps) + 1)):
        bad.append("the increments kept are not 1, 2, ..., n: the replay needs every one")
    sols = [int(s.attrs["iterations"]) for s in steps]
    print("solutions per increment: " + " ".join(str(k) for k in sols))
    print("solutions: total %d, mean %.2f, largest %d (increment %d)"
          % (sum(sols), sum(sols) / len(sols), max(sols), 1 + sols.index(max(sols))))
    c0 = steps[0].contact_all()
    npair = len(area)
    if any(c0["tangential_state"] != 0):
        bad.append("increment 1: a pair left stick under the normal load's first step (X unknown)")
    f = [float(v) for v in c0["force_tangential"]]
    x = [0.0] * npair
    ve = [float(v) for v in c0["effective_slip"]]
    worst = 0.0
    nslip = nbranch = 0
    for i in range(1, len(steps)):
        prev, cur = steps[i - 1].contact_all(), steps[i].contact_all()
        for j in range(npair):
            if cur["normal_state"][j] == 0 or prev["normal_state"][j] == 0:
                bad.append("increment %d pair %d: open (these decks keep every pair closed)" % (i + 1, j + 1))
                continue
            mu = mu_m * (1.0 - (1.0 - beta) * math.exp(-nh * ve[j])) if fredriksson else mu_m
            if abs(cur["friction"][j] - mu) > 1.0e-12 * mu:
                bad.append("increment %d pair %d: friction %.15g, the law mu(v_e) gives %.15g"
                           % (i + 1, j + 1, cur["friction"][j], mu))
            ke = area[j] * laws.tangential_stiffness(prev["pressure"][j], s_exp, rt[j])
            fn = float(cur["force_normal"][j])
            du = float(cur["slip"][j] - prev["slip"][j])
            ft, xn, ts, dist = replay(f[j], du, ke, kappa, mu * fn, x[j], hardening)
            err = abs(cur["force_tangential"][j] - ft) / (mu * fn)
            worst = max(worst, err)
            if err > TOL_F:
                bad.append("increment %d pair %d: F_T %.15g, the law gives %.15g (%.2e of mu F_n)"
                           % (i + 1, j + 1, cur["force_tangential"][j], ft, err))
            if ts != cur["tangential_state"][j] and dist > TOL_F * mu * fn:
                bad.append("increment %d pair %d: state %d, the law gives %d"
                           % (i + 1, j + 1, cur["tangential_state"][j], ts))
            if ts != 0:
                ve[j] += abs(du - (ft - f[j]) / ke)
            if abs(cur["effective_slip"][j] - ve[j]) > 1.0e-8 * ve[j] + 1.0e-12:
                bad.append("increment %d pair %d: v_e %.15g, the law gives %.15g"
                           % (i + 1, j + 1, cur["effective_slip"][j], ve[j]))
            nslip += ts == 2
            nbranch += ts == 1
            f[j], x[j] = float(cur["force_tangential"][j]), xn
    print("tangential law replayed: %d pair-increments, %d on the branch, %d in slip; largest |F_T - law| "
          "%.2e of mu F_n (tolerance %g)" % ((len(steps) - 1) * npair, nbranch, nslip, worst, TOL_F))
    if nslip == 0 or nbranch == 0:
        bad.append("the deck reached no slip or no branch: it tests nothing of the kinks")
    return bad


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    try:
        checks = parse(sys.argv[2])
    except CheckFormatError as e:
        print("check_law: %s" % e)
        return 2
    failed = 0
    for c, ok, msg in check_result(sys.argv[1], checks):
        print("%s  %s: %s\n        %s" % ("PASS" if ok else "FAIL", c.where, c.label, msg))
        failed += not ok
    print("%d of %d checks hold" % (len(checks) - failed, len(checks)))
    bad = check_law(sys.argv[1])
    for b in bad[:20]:
        print("FAIL  " + b)
    if len(bad) > 20:
        print("... and %d more" % (len(bad) - 20))
    return 1 if failed or bad else 0


if __name__ == "__main__":
    sys.exit(main())
