#!/usr/bin/python3
"""Check the ideal-contact conditions at every increment end of a result file.

    check_ideal_contact.py RESULT.h5 --hmin H [--max-solutions N] [--rest | --rest-free]

For every kept increment (docs/contact.md, "Ideal contact"):

* converged (attribute `converged` = 1);
* non-penetration to the documented tolerance: every pair's closure u_n <= TOL h_min
  (TOL the second value of /contact@augmented, h_min the smallest contact element length,
  given by --hmin from the deck's mesh), and a closed pair has |u_n| <= TOL h_min (no gap
  under load: the complementarity defect);
* F_n >= 0, an open pair carries no force;
* Coulomb: |F_T| <= mu F_n (to 1e-10 of the largest normal force of the run, the
  round-off allowance of the solver's own check);
* stick / slip consistency (frictional pairs): a sticking pair moved tangentially in the increment by at
  most TOL h_min; a slipping pair carries |F_T| = mu F_n, and, where it slipped by more
  than the tolerance under a force above round-off, F_T has the direction of its slip;
* solutions per increment (attribute `iterations`) at most --max-solutions;
* --rest: the last increment holds a zero load: every contact force vanishes (1e-10 of
  the largest of the run) and the bodies are back at rest where they started (every
  displacement within 1e-9 of the largest of the run): elastic bodies with no load and no
  contact force are stress-free, and a body held only by contact is at rest touching;
* --rest-free: as --rest for a body that only friction held tangentially: the forces vanish
  and the bodies are stress-free (every nodal stress within 1e-9 of the largest of the run),
  but the body may rest anywhere along its free direction (a rigid translation, which no
  friction fixes at zero force), so its displacement is not checked.

Prints one line per increment (load factor, solutions, closed / slipping pairs) and exits 1
when a condition fails.  Needs tools/k2d on the Python path.
"""
import argparse
import sys

import numpy as np

from k2d.results import Result


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("--hmin", type=float, required=True, help="smallest contact element length")
    ap.add_argument("--max-solutions", type=int, default=0)
    ap.add_argument("--rest", action="store_true")
    ap.add_argument("--rest-free", action="store_true", help="--rest without the displacement (a free translation)")
    args = ap.parse_args()
    r = Result(args.result)
    fails = []
    if r.status != "completed":
        fails.append("status %r, not completed" % r.status)
    tol = float(np.atleast_1d(r.contact.attrs["augmented"])[1]) * args.hmin
    fmax = max(float(np.max(s.contact("force_normal"))) for s in r.steps)
    umax = max(float(np.max(np.abs(s.field("displacement")))) for s in r.steps)
    fround = 1.0e-10 * fmax
    slip_prev = np.zeros(r.contact.npair)
    print("tolerance TOL h_min = %.3e, largest normal force %.6e, largest |u| %.6e" % (tol, fmax, umax))
    print(" inc  load factor  solutions  closed  slipping  largest |u_n| closed")
    for s in r.steps:
        c = s.contact_all()
        n = s.number
        closed = c["normal_state"] > 0
        un, fn, ft, mu = c["closure"], c["force_normal"], c["force_tangential"], c["friction"]
        # (a frictionless pair has no tangential state to check: it carries no F_T)
        slipping = closed & (c["tangential_state"] == 2) & (mu > 0.0)
        sticking = closed & (c["tangential_state"] == 0) & (mu > 0.0)
        dslip = c["slip"] - slip_prev
        slip_prev = c["slip"]
        sols = int(np.atleast_1d(s.attrs["iterations"])[0])
        print("%4d  %11.5f  %9d  %6d  %8d  %.3e" % (n, s.load_factor[0], sols, closed.sum(), slipping.sum(),
                                                    np.max(np.abs(un[closed]), initial=0.0)))

        def bad(what, mask):
            js = np.flatnonzero(mask)
            if js.size:
                fails.append("increment %d: %s at pair(s) %s" % (n, what, ", ".join(str(j + 1) for j in js[:8])))

        if int(np.atleast_1d(s.attrs["converged"])[0]) != 1:
            fails.append("increment %d not converged" % n)
        if args.max_solutions and sols > args.max_solutions:
            fails.append("increment %d: %d solutions > %d" % (n, sols, args.max_solutions))
        bad("penetration beyond the tolerance", un > tol)
        bad("a gap under load (closed, |u_n| > tolerance)", closed & (np.abs(un) > tol))
        bad("a tensile normal force", fn < -fround)
        bad("an open pair with a force", ~closed & ((fn != 0.0) | (ft != 0.0)))
        bad("|F_T| > mu F_n", np.abs(ft) > mu * np.maximum(fn, 0.0) + fround)
        bad("a sticking pair slipped beyond the tolerance", sticking & (np.abs(dslip) > tol))
        bad("a slipping pair off |F_T| = mu F_n", slipping & (np.abs(np.abs(ft) - mu * fn) > fround))
        bad("a slipping pair's force against its slip",
            slipping & (np.abs(dslip) > tol) & (np.abs(ft) > fround) & (ft * dslip < 0.0))
    if args.rest or args.rest_free:
        last = r.last
        if np.any(np.abs(last.load_factor) > 0.0):
            fails.append("--rest: the last increment's load factor is not zero")
        f = np.concatenate([np.abs(last.contact("force_normal")), np.abs(last.contact("force_tangential"))])
        if np.max(f) > fround:
            fails.append("--rest: a contact force %.3e > %.3e left at zero load" % (np.max(f), fround))
        smax = max(float(np.max(np.abs(s.field("stress_nodal")))) for s in r.steps)
        sig = float(np.max(np.abs(last.field("stress_nodal"))))
        if sig > 1.0e-9 * smax:
            fails.append("--rest: stress %.3e > 1e-9 of the largest (%.3e) at zero load" % (sig, smax))
        u = np.max(np.abs(last.field("displacement")))
        if args.rest and u > 1.0e-9 * umax:
            fails.append("--rest: displacement %.3e > 1e-9 of the largest (%.3e) at zero load" % (u, umax))
    for f in fails:
        print("FAIL  " + f)
    print("%s: %d increment(s), %d failure(s)" % ("PASS" if not fails else "FAIL", len(r.steps), len(fails)))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
