#!/usr/bin/python3
"""Regression checks of the paper's examples: coarse versions of the decks of
k2d.examples (tools/make_examples.py) are run and their results checked against what the paper
states (section 5), not against stored numbers.

    check_examples.py punch|sphere|cylinder --exe KONTAKT2D --work DIR

Exit code 0 when every check holds; each check prints one line.  Needs the
package tools/k2d on the Python path (ctest sets PYTHONPATH); reads the results
through k2d.results.
"""
import argparse
import os
import sys

import numpy as np

from k2d import examples as ex
from k2d import laws
from k2d.analysis import Pairs, contact_radius as radius
from k2d.build import run_deck
from k2d.published import TABLE1, TABLE1_X
from k2d.results import Result

FAILED = []


def check(ok, what, detail=""):
    print("%s  %s%s" % ("PASS" if ok else "FAIL", what, ("  [" + detail + "]") if detail else ""))
    if not ok:
        FAILED.append(what)


class Run:
    """Write a deck with a k2d.examples generator, run it, read its contact pairs."""

    def __init__(self, args, name, fn, **kw):
        deck = os.path.join(args.work, name + ".dat")
        h5 = os.path.join(args.work, name + ".h5")
        log = os.path.join(args.work, name + ".log")
        fn(deck, **kw)
        self.rc = run_deck(args.exe, deck, h5, log=log)
        # the paper's explicit scheme drifts off the normal law: such a run completes with
        # doubts (exit code 4, status "doubtful"); any other run must complete plainly
        with open(deck) as f:
            explicit = any(line.split()[:2] in (["UPDATE", "EXPLICIT"], ["SCHEME", "INCREMENTAL"],
                                                ["SCHEME", "EXPLICIT"]) for line in f)
        if self.rc != 0:
            with open(log) as f:
                print(f.read())
        check(self.rc == 0 or (explicit and self.rc == 4), "%s runs to completion" % name)
        self.result = Result(h5)
        self.pairs = Pairs(self.result)
        self.x = self.pairs.x
        self.node_a = self.result.contact.node_a
        self.steps = self.result.steps
        check(sum(int(s.attrs["invariant_violations"]) for s in self.steps) == 0,
              "%s: no invariant violations" % name)

    def last(self, key):
        return self.pairs.last(key)

    def history(self, key, k):
        """Contact quantity `key` of pair k (in the order of x) over the increments."""
        return np.array([self.pairs.of_step(s, key)[k] for s in self.steps])


def at(r, key, x):
    return float(r.last(key)[np.argmin(np.abs(r.x - x))])


# ---------------------------------------------------------------------------- 5.1
# Table 1, column 5 (the ideal model, mu = 0): u_T in um at 2x/B = 0.1, 0.2, ..., 0.8, 0.85, 0.9, 0.95, 1
TABLE1_COL5_X = TABLE1_X[1:]
TABLE1_COL5_UT = TABLE1[5][0][1:]


def punch(args):
    c2 = Run(args, "punch_col2", ex.punch, column=2)
    c3 = Run(args, "punch_col3", ex.punch, column=3)
    c5 = Run(args, "punch_col5", ex.punch, column=5)
    for r, lab in ((c2, "Coulomb"), (c5, "frictionless")):
        p = r.last("pressure")
        check(int(np.argmax(p)) == len(p) - 1, "%s: the pressure peaks at the punch edge" % lab,
              "p(0) = %.4f, p(edge) = %.4f" % (p[0], p[-1]))
        fsum = float(np.sum(r.last("force_normal")))
        check(abs(fsum / 600.0 - 1.0) < 1e-8, "%s: sum F_n = p0 B t / 2 = 600 N" % lab, "%.12g" % fsum)
        check(bool(np.all(np.diff(r.last("slip")) > 0)), "%s: u_T grows from the centre to the edge" % lab)
    st = c2.last("tangential_state")
    up = c2.last("slip_irreversible")
    slipping = list(np.round(c2.x[st == 2] / 50.0, 3))
    check(slipping == [0.9, 0.95, 1.0], "Coulomb 0.2: the outer three nodes slip (Table 1, column 2)", str(slipping))
    check(bool(np.all(up[st != 2] == 0.0)), "Coulomb 0.2: u_T^p is zero in the stick zone")
    check(bool(np.all(up[st == 2] > 0.0) and np.all(np.diff(up[st == 2]) > 0.0)),
          "Coulomb 0.2: u_T^p grows towards the edge in the slip zone", " ".join("%.3g" % v for v in 1e3 * up[st == 2]))
    ratio = (c2.last("shear") / c2.last("pressure"))[st == 2]
    check(bool(np.all(np.abs(ratio - 0.2) < 1e-6)), "Coulomb 0.2: p_T / p_n = 0.2 at the slipping nodes")
    check(bool(np.all(c5.last("slip")[1:] > c2.last("slip")[1:])), "friction reduces u_T at every node")
    # the paper's ideal model (column 5): SPEC 6.1's acceptance target, u_T within 10 % of the
    # paper at every node (the unknown foundation height alone moves u_T by 5-13 %,
    # docs/validation.md); the rough layer spreads the pressure away from the edge
    ci = Run(args, "punch_col5_ideal", ex.punch, column=5, law="IDEAL")
    ut = np.array([1e3 * at(ci, "slip", 50.0 * s) for s in TABLE1_COL5_X])
    dev = 100.0 * (ut / np.array(TABLE1_COL5_UT) - 1.0)
    check(bool(np.all(np.abs(dev) <= 10.0)), "ideal, mu = 0: u_T within 10 % of Table 1, column 5 at every node",
          "%+.1f ... %+.1f %%" % (dev.min(), dev.max()))
    fsum = float(np.sum(ci.last("force_normal")))
    check(abs(fsum / 600.0 - 1.0) < 1e-8, "ideal, mu = 0: sum F_n = 600 N", "%.12g" % fsum)
    pi = ci.last("pressure")
    check(int(np.argmax(pi)) == len(pi) - 1 and float(pi[-1]) > float(c5.last("pressure")[-1]),
          "the pressure peaks at the punch edge, higher on the ideal interface than on the rough one",
          "p(edge) = %.4f ideal, %.4f rough" % (pi[-1], c5.last("pressure")[-1]))
    up3 = c3.last("slip_irreversible")
    check(int(np.sum(up3 > 0)) > int(np.sum(up > 0)) and float(up3[-1]) > float(up[-1]),
          "Fredriksson (beta = 0.2): slip starts further in and u_T^p is larger than with Coulomb 0.2",
          "%d vs %d nodes" % (np.sum(up3 > 0), np.sum(up > 0)))
    check(float(c3.x[np.argmax(up3 > 0)]) / 50.0 <= 0.3 + 1e-9, "Fredriksson: slip from 2x/B <= 0.3 (Table 1, col. 3)")
    # Bild 5: unloading leaves an irreversible closure at the edge
    u = Run(args, "punch_unload", ex.punch, column=5, cn2=0.5, unload=True)
    k = int(np.argmax(u.x))
    closure = u.history("closure", k)
    press = u.history("pressure", k)
    imax = int(np.argmax([s.load_factor[0] for s in u.steps]))
    ures = laws.residual_closure(1e3 * closure[imax], ex.KGF * press[imax], 0.5, 0.5)   # um, kgf/cm2
    closed = u.history("normal_state", k) > 0
    check(ures > 0.0 and bool(np.all(closed[imax:] == (1e3 * closure[imax:] > ures - 1e-9))),
          "Bild 5: the edge pair unloads along its branch and opens at the irreversible closure u_A - c_n2 p_A^m",
          "u_res = %.3f um" % ures)
    check(bool(np.all(np.diff(press[imax:][closed[imax:]]) < 0)), "Bild 5: the edge pressure falls while unloading")


# ---------------------------------------------------------------------------- 5.2
def contact_radius(r):
    return radius(r.x, r.last("closure"), r.last("normal_state"))


def sphere(args):
    kw = dict(update="NEWTON", nincs=4, hdiv=6.0, q=1.3, reach=4.0)
    res = {}
    for P in (200.0, 20000.0):
        for cn in (None, 0.3, 0.8):
            r = Run(args, "sphere_P%d_%s" % (P, cn), ex.sphere, P=P, cn=cn, **kw)
            fsum = float(np.sum(r.last("force_normal")))
            check(abs(fsum / P - 1.0) < 1e-8, "P = %g, c_n = %s: sum F_n = P" % (P, cn), "%.12g" % fsum)
            res[(P, cn)] = (float(r.last("pressure")[0]), contact_radius(r), r.x[1] - r.x[0])
    for P in (200.0, 20000.0):
        a, p0, _ = ex.hertz_sphere(P)
        ps, as_, h = res[(P, None)]
        check(abs(ps / p0 - 1.0) < 0.05 and abs(as_ - a) < 2 * h,
              "P = %g: the smooth contact (ideal law) is Hertz's" % P,
              "p(0)/p0 = %.3f, a_c/a = %.3f" % (ps / p0, as_ / a))
        p3, a3, _ = res[(P, 0.3)]
        p8, a8, _ = res[(P, 0.8)]
        check(p8 < p3 < ps, "P = %g: roughness lowers the peak, more for larger c_n" % P,
              "%.1f > %.1f > %.1f" % (ps, p3, p8))
        check(a8 > a3 > as_, "P = %g: roughness widens the contact, more for larger c_n" % P,
              "%.3f < %.3f < %.3f" % (as_, a3, a8))
    for cn in (0.3, 0.8):
        lo = res[(200.0, cn)][0] / res[(200.0, None)][0]
        hi = res[(20000.0, cn)][0] / res[(20000.0, None)][0]
        alo = res[(200.0, cn)][1] / res[(200.0, None)][1]
        ahi = res[(20000.0, cn)][1] / res[(20000.0, None)][1]
        check(lo < hi < 1.0 and alo > ahi > 1.0, "c_n = %g: the roughness effect shrinks as the load grows" % cn,
              "p(0)/p_smooth %.3f -> %.3f, a_c/a_smooth %.3f -> %.3f" % (lo, hi, alo, ahi))


# ---------------------------------------------------------------------------- 5.3
def cylinder(args):
    spread = {}
    for P in (1.0e4, 1.0e6):
        pm = P / (np.pi * (ex.CYL_RA ** 2 - ex.CYL_RI ** 2))
        for cn in (0.2, 1.0):
            r = Run(args, "cyl_%g_%g" % (P, cn), ex.cylinder, P=P, cn=cn, h=2.5)
            if P == 1.0e6 and cn == 0.2:
                rigid_body = r
            p = r.last("pressure") / pm
            spread[(P, cn)] = float(p.max() - p.min())
            check(int(np.argmax(p)) == len(p) - 1 and p[0] > p[len(p) // 2],
                  "P = %g, c_n = %g: the pressure peaks at both edges of the annulus, highest outside" % (P, cn),
                  "p/p_m: %.3f ... %.3f ... %.3f" % (p[0], p[len(p) // 2], p[-1]))
            fsum = float(np.sum(r.last("force_normal")))
            check(abs(fsum / P - 1.0) < 1e-8, "P = %g, c_n = %g: sum F_n = P" % (P, cn))
            ft, fn = r.last("force_tangential"), r.last("force_normal")
            check(bool(np.all(np.abs(ft) <= 0.3 * fn * (1 + 1e-10))), "P = %g, c_n = %g: |p_T| <= 0.3 p_n" % (P, cn))
    for P in (1.0e4, 1.0e6):
        check(spread[(P, 1.0)] < spread[(P, 0.2)], "P = %g: larger c_n gives a more uniform pressure" % P,
              "spread %.3f (c_n = 1) < %.3f (c_n = 0.2)" % (spread[(P, 1.0)], spread[(P, 0.2)]))
    for cn in (0.2, 1.0):
        check(spread[(1.0e4, cn)] < spread[(1.0e6, cn)],
              "c_n = %g: the lower load gives the more uniform pressure (roughness matters more)" % cn)
    # the rigid body (RIGID FLAT) is the same physics as a tied layer of elements (u_r = 0,
    # one u_z): same pressures and shears to round-off
    t = Run(args, "cyl_1e6_0.2_ties", ex.cylinder, P=1.0e6, cn=0.2, h=2.5, rigid="TIES")
    uz = t.result.last.field("displacement")[t.node_a - 1, 1]
    check(float(np.ptp(uz)) <= 1e-12 * abs(float(uz[0])), "TIES: the tied cylinder moves rigidly")
    pm = 1.0e6 / (np.pi * (ex.CYL_RA ** 2 - ex.CYL_RI ** 2))
    dp = float(np.max(np.abs(t.last("pressure") - rigid_body.last("pressure")))) / pm
    dt = float(np.max(np.abs(t.last("shear") - rigid_body.last("shear")))) / pm
    check(bool(np.allclose(t.x, rigid_body.x)) and dp < 1e-8 and dt < 1e-8,
          "P = 1e6, c_n = 0.2: the rigid body and the tied mesh give the same contact stresses",
          "max |dp|/p_m = %.1e, max |dp_T|/p_m = %.1e" % (dp, dt))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("example", choices=["punch", "sphere", "cylinder"])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    {"punch": punch, "sphere": sphere, "cylinder": cylinder}[args.example](args)
    if FAILED:
        print("%d check(s) failed" % len(FAILED))
        return 1
    print("all checks hold")
    return 0


if __name__ == "__main__":
    sys.exit(main())
