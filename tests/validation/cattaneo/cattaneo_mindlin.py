#!/usr/bin/python3
"""Plane-strain Cattaneo-Mindlin: an elastic cylinder on an elastic half-plane of the
same material (ideal contact, Coulomb friction mu) under a constant normal force P
and a tangential force cycled 0 -> +Q* -> -Q* -> +Q*.  The energy dissipated in the
steady cycle (+Q* -> -Q* -> +Q*, the result file's /cycles/energy) is compared with
the closed form of docs/validation-contact.md ("Cattaneo-Mindlin in 2D"):

    E = (2 mu^2 P^2 / (pi E*)) [2q - q^2 + 2 (1 - q) ln(1 - q)],   q = Q*/(mu P)

per unit thickness (E* = E / (2 (1 - nu^2)) for two bodies of one material); for
small q, E -> 2 Q*^3 / (3 pi mu P E*).

The decks are generated here (fine meshes: not committed).  Usage:

    cattaneo_mindlin.py --exe build/kontakt2d --work DIR [--h 40 60] [--q 0.25 0.5 0.75]
                        [--n 10] [--tol 0.03] [--table]

Each (h, q, n) is one run: h elements across the contact half-width a in the fine
zone, n increments per quarter cycle.  With --tol the run fails (exit 1) when an
energy is off the closed form by more than tol (relative); --table prints the
markdown table of docs/validation-contact.md.
"""
import argparse
import math
import os
import resource
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "tools"))
from k2d.deck import Deck, fine_then_graded  # noqa: E402
from k2d.results import Result, dataset  # noqa: E402

E, NU = 21000.0, 0.3          # both bodies (Dundurs beta = 0: no normal-tangential coupling)
R, P, MU = 10.0, 10.0, 0.3    # cylinder radius [mm], normal force [N/mm] (a/R = 0.0105), Coulomb mu
ESTAR = E / (2.0 * (1.0 - NU ** 2))
A_H = math.sqrt(4.0 * P * R / (math.pi * ESTAR))   # Hertz half-width a
L_FAR = 150.0 * A_H           # radius of the half-plane (half disc), fixed on its arc


def set_force(p):
    """Another normal force P: the Hertz half-width a and the far radius follow."""
    global P, A_H, L_FAR
    P = p
    A_H = math.sqrt(4.0 * P * R / (math.pi * ESTAR))
    L_FAR = 150.0 * A_H


def energy_closed(q):
    """Energy per cycle [N mm per mm] of the plane-strain Cattaneo-Mindlin cycle +-q mu P."""
    return 2.0 * MU ** 2 * P ** 2 / (math.pi * ESTAR) * (2.0 * q - q * q + 2.0 * (1.0 - q) * math.log(1.0 - q))


def _ring(d, body, boundary, arc, radial, mat, mapping=lambda p: p):
    """One block from the core's boundary polyline (parameter s, points boundary(s)) out to an
    arc (points arc(s)), v the radial parameter: (1 - v) boundary + v arc, then `mapping`."""
    params = [k for k in range(len(boundary))]

    def mp(s, v):
        k = int(round(s))
        bx, by = boundary[k]
        ax, ay = arc[k]
        return mapping(((1 - v) * bx + v * ax, (1 - v) * by + v * ay))
    d.block(body, params, radial, mat, mapping=mp)


def _arc_points(boundary, radius, th0, th1):
    """Points of the arc of `radius` from angle th0 to th1 spread like the boundary's arclength."""
    s = [0.0]
    for (x0, y0), (x1, y1) in zip(boundary[:-1], boundary[1:]):
        s.append(s[-1] + math.hypot(x1 - x0, y1 - y0))
    return [(radius * math.cos(th0 + (th1 - th0) * t / s[-1]), radius * math.sin(th0 + (th1 - th0) * t / s[-1]))
            for t in s]


def surface_grid(h_frac):
    """Grid lines x >= 0 of the contact surfaces: cells of a/h_frac where the slip zones of
    Q*/(mu P) = 0.25 ... 0.75 lie (0.45a <= |x| <= 1.1a: the stick zone's edge c = a sqrt(1 - q)
    is 0.87a, 0.71a, 0.5a), twice as large (at most a/40) in the middle, growing by 10 %
    per cell beyond 1.1a up to 1.6a."""
    h = A_H / h_frac
    hc = min(2.0 * h, A_H / 40.0)
    x0 = 0.45 * A_H
    n0 = max(1, int(round(x0 / hc)))
    lines = [x0 * k / n0 for k in range(n0 + 1)]
    n1 = int(round((1.1 * A_H - x0) / h))
    lines += [x0 + (1.1 * A_H - x0) * k / n1 for k in range(1, n1 + 1)]
    lines += fine_then_graded(1.1 * A_H, 1.6 * A_H, h, 0.0, 1.1)[1:]
    return lines, h


def make_deck(path, h_frac, q, n_quarter):
    """The deck: cylinder on half-plane, contact surfaces on surface_grid(h_frac), the
    bodies' cells growing from h at the surface by 12 % per cell into the depth."""
    half, h = surface_grid(h_frac)
    c = half[-1]
    xs = [-x for x in reversed(half[1:])] + half
    depth = fine_then_graded(0.0, c, h, 0.1 * A_H, 1.12)
    d = Deck("Cattaneo-Mindlin in plane strain: cylinder on half-plane, Q*/(mu P) = %g" % q, ntype=2, nnode=4,
             solver="AUTO")
    d.comments = ["Plane-strain Cattaneo-Mindlin (docs/validation-contact.md): elastic cylinder R = %g mm on an" % R,
                  "elastic half-plane, both E = %g, nu = %g (E* = %.1f);" % (E, NU, ESTAR),
                  "P = %g N/mm, a = %.5f mm;" % (P, A_H),
                  "ideal contact, Coulomb mu = %g; Q cycled 0 -> +Q* -> -Q* -> +Q*, Q* = %g mu P;" % (MU, q),
                  "surface cells a/%g for 0.45a <= |x| <= 1.1a, growing into the depth;" % h_frac,
                  "%d increments per quarter cycle." % n_quarter,
                  "Generated by tests/validation/cattaneo/cattaneo_mindlin.py."]
    # half-plane: core [-c, c] x [-c, 0], a ring out to the half disc of radius L_FAR
    ys = [-x for x in reversed(depth)]
    d.block("HS", xs, ys, 2)
    bnd = [(c, y) for y in reversed(ys)] + [(x, -c) for x in reversed(xs[:-1])] + [(-c, y) for y in ys[1:]]
    hr = half[-1] - half[-2]
    radial = fine_then_graded(0.0, 1.0, hr / (L_FAR - c), hr / (L_FAR - c), 1.15)
    _ring(d, "HS", bnd, _arc_points(bnd, L_FAR, 0.0, -math.pi), radial, 2)

    # cylinder: the flat half disc |z| <= 2R, Im z >= 0 mapped by w = z / (1 - i z / 2R), which
    # maps the real axis onto the cylinder, the arc onto its flat top y = R, and is the identity
    # to first order at the contact; core [-cf, cf] x [0, cf] in the flat plane
    def flat_of_r(r):
        if r == 0.0:
            return 0.0
        return math.copysign((2 * R * R / abs(r)) * (1.0 - math.sqrt(1.0 - (r / R) ** 2)), r)

    def w(p):
        z = complex(p[0], p[1])
        m = z / (1 - 1j * z / (2 * R))
        return (m.real, m.imag)

    fx = [flat_of_r(x) for x in xs]          # surface nodes over the half-plane's (node-to-node pairs)
    cf = fx[-1]
    ts = [cf * t / c for t in depth]
    d.block("CYL", fx, ts, 1, mapping=lambda x, y: w((x, y)))
    bnd = [(cf, t) for t in ts] + [(x, cf) for x in reversed(fx[:-1])] + [(-cf, t) for t in reversed(ts[:-1])]
    radial = fine_then_graded(0.0, 1.0, hr / (2 * R - cf), hr / (2 * R - cf), 1.15)
    _ring(d, "CYL", bnd, _arc_points(bnd, 2 * R * (1 - 1e-12), 0.0, math.pi), radial, 1, mapping=w)
    d.material(1, E, NU, 1.0)
    d.material(2, E, NU, 1.0)

    on_cyl = lambda x, y: abs(x) <= 1.5 * A_H and y < 1e-9 + R - math.sqrt(max(R * R - x * x, 0.0))  # noqa: E731
    on_hs = lambda x, y: abs(x) <= 1.5 * A_H and abs(y) < 1e-12  # noqa: E731
    sa = d.nodes_where("CYL", on_cyl)
    sb = d.nodes_where("HS", on_hs)
    top = d.nodes_where("CYL", lambda x, y: abs(y - R) < 1e-6 * R)
    top.sort(key=lambda k: abs(d.nodes[k - 1][0]))
    links = [(a, b) for a, b in zip(sorted(sa, key=lambda k: d.nodes[k - 1][0]),
                                    sorted(sb, key=lambda k: d.nodes[k - 1][0]))]
    d.renumber(links)
    sa = d.nodes_where("CYL", on_cyl)
    sb = d.nodes_where("HS", on_hs)
    top = d.nodes_where("CYL", lambda x, y: abs(y - R) < 1e-6 * R)
    top.sort(key=lambda k: abs(d.nodes[k - 1][0]))
    for k in d.nodes_where("HS", lambda x, y: abs(math.hypot(x, y) - L_FAR) < 1e-6 * L_FAR):
        d.fix(k, "11")
    # the top face moves as one (no rotation: the moment Q R is taken by the tie, as in
    # Cattaneo's problem, where Q acts in the contact plane); P and Q on its middle node
    d.tie("11", top)
    d.point_load(top[0], 0.0, -P, case=1)
    d.point_load(top[0], q * MU * P, 0.0, case=2)
    d.contact = ["LAW       IDEAL", "FRICTION  COULOMB   %10g" % MU, "START               %10d" % 1,
                 "SURFACE   A"] + d.node_list_cards(sa) + ["SURFACE   B"] + d.node_list_cards(sb)
    n = n_quarter
    d.increments = [(1, [1.0, 0.0]), (n, [None, 1.0]), (2 * n, [None, -1.0]), (2 * n, [None, 1.0])]
    d.write(path)
    inside = sum(1 for x in xs if abs(x) < A_H)     # surface nodes within the Hertz width
    return len(d.nodes), len(sa), inside


def run_case(exe, work, h_frac, q, n):
    name = "cm_h%g_q%g_n%d" % (h_frac, q, n) + ("" if P == 10.0 else "_P%g" % P)
    deck = os.path.join(work, name + ".dat")
    nodes, pairs, inside = make_deck(deck, h_frac, q, n)
    t0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run([exe, "-q", deck], cwd=work, capture_output=True, text=True)
    t1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (t1.ru_utime + t1.ru_stime) - (t0.ru_utime + t0.ru_stime)
    h5 = os.path.join(work, name + ".h5")
    if r.returncode != 0:
        sys.stderr.write(r.stdout + r.stderr)
        raise SystemExit("%s: kontakt2d exit %d" % (name, r.returncode))
    res = Result(h5)
    first = dataset(h5, "/cycles/first_increment")
    energy = dataset(h5, "/cycles/energy")
    if len(first) < 1:
        raise SystemExit("%s: no cycle found in the result file" % name)
    # the steady cycle: +Q* -> -Q* -> +Q*, from the end of the first quarter
    e_fe = float(energy[0, 0])
    last = res.last
    closed = int((last.contact("normal_state") != 0).sum())
    return dict(name=name, h=h_frac, q=q, n=n, nodes=nodes, pairs=pairs, closed=closed, inside=inside, e_fe=e_fe,
                e_cf=energy_closed(q), first=int(first[0]), cpu=cpu,
                loss=float(dataset(h5, "/cycles/loss_factor")[0, 0]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--h", type=float, nargs="+", default=[40.0])
    ap.add_argument("--q", type=float, nargs="+", default=[0.25, 0.5, 0.75])
    ap.add_argument("--n", type=int, nargs="+", default=[10])
    ap.add_argument("--tol", type=float, default=None)
    ap.add_argument("--force", type=float, default=P, help="normal force P [N/mm] (sets a/R)")
    ap.add_argument("--table", action="store_true")
    a = ap.parse_args(argv)
    set_force(a.force)
    os.makedirs(a.work, exist_ok=True)
    rows = []
    for h in a.h:
        for q in a.q:
            for n in a.n:
                rows.append(run_case(os.path.abspath(a.exe), a.work, h, q, n))
                r = rows[-1]
                print("%-22s nodes %6d pairs %4d closed %4d  E_FE %.5e  E_closed %.5e  error %+7.3f %%  "
                      "loss factor %.4f  cpu %.1f s" % (r["name"], r["nodes"], r["pairs"], r["closed"], r["e_fe"],
                                                        r["e_cf"], 100 * (r["e_fe"] / r["e_cf"] - 1), r["loss"],
                                                        r["cpu"]), flush=True)
    if a.table:
        print("| a/h | Q*/(mu P) | increments per quarter | E closed form [N mm/mm] | E computed | error |")
        print("|---|---|---|---|---|---|")
        for r in rows:
            print("| %g | %g | %d | %.4e | %.4e | %+.2f %% |" % (r["h"], r["q"], r["n"], r["e_cf"], r["e_fe"],
                                                             100 * (r["e_fe"] / r["e_cf"] - 1)))
    bad = []
    for r in rows:
        # the closed pairs are those within the Hertz width 2a (node-to-node: the surface
        # nodes with |x| < a, to one node at either edge)
        if abs(r["closed"] - r["inside"]) > 2:
            bad.append("%s: %d closed pairs, expected %d (|x| < a)" % (r["name"], r["closed"], r["inside"]))
        # the steady cycle starts at the end of the first quarter (increment 1 + n)
        if r["first"] != 1 + r["n"]:
            bad.append("%s: the first cycle starts at increment %d, expected %d" % (r["name"], r["first"], 1 + r["n"]))
        if a.tol is not None and abs(r["e_fe"] / r["e_cf"] - 1) > a.tol:
            bad.append("%s: energy per cycle %.5e off the closed form %.5e by %.2f %% (> %.1f %%)" %
                       (r["name"], r["e_fe"], r["e_cf"], 100 * (r["e_fe"] / r["e_cf"] - 1), 100 * a.tol))
    for b in bad:
        print("FAIL " + b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
