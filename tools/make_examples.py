#!/usr/bin/python3
"""Write the decks of the paper's three examples (section 5 of Altenbach &
Buczkowski; SPEC §6 is the reconstruction) and of their variants.

    tools/make_examples.py                 # the example decks of inputs/
    tools/make_examples.py --all DIR       # every variant used by tools/paper_figures.py, into DIR
    tools/make_examples.py --list          # the names of the variants

Every deck states its units and its assumptions in its header comments
(docs/validation.md discusses them).  Geometry, heights, meshes and load
histories that the paper does not give are assumptions: they are parameters of
the functions below, and tools/paper_figures.py runs the sensitivity studies
with them.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from k2d.deck import Deck, f10, graded  # noqa: E402

ROOT = os.path.dirname(HERE)
KGF = 10.19716          # kgf/cm2 per N/mm2 (SPEC §1)
TOL = 1e-9


def surface_cards(d, pa, pb):
    """SURFACE A and SURFACE B cards from two predicates."""
    sa = d.nodes_where("A", pa)
    sb = d.nodes_where("B", pb)
    return ["SURFACE   A"] + d.node_list_cards(sa) + ["SURFACE   B"] + d.node_list_cards(sb)


def history(n, first=0.05, unload=0, lam_end=0.0):
    """The paper's load history (SPEC §6.1): `first` of the load in the first increment,
    then n - 1 equal increments to 1; optionally `unload` equal increments down to lam_end."""
    inc = [(1, [first]), (n - 1, [1.0])] if n > 1 else [(1, [1.0])]
    if unload:
        inc.append((unload, [lam_end]))
    return inc


def subdivide(xs, k):
    """Split every cell of the grid xs into k equal cells."""
    out = [xs[0]]
    for a, b in zip(xs[:-1], xs[1:]):
        out += [a + (b - a) * i / k for i in range(1, k + 1)]
    return out


# --------------------------------------------------------------------------------------------
# Example 5.1: elastic punch on an elastic foundation (Bild 4, Tables 1 and 2, Bild 5)
# --------------------------------------------------------------------------------------------
PUNCH_CONTACT_X = [0, 5, 10, 15, 20, 25, 30, 35, 40, 42.5, 45, 47.5, 50]     # Table 2, 13 nodes
PUNCH_COLUMNS = {
    # Table 1 columns: (label, FRICTION card, HARDENING card)
    1: ("hardening branch on, Coulomb mu = 0.2", "COULOMB         0.2", "ON        0.045"),
    2: ("no hardening branch, Coulomb mu = 0.2", "COULOMB         0.2", "OFF"),
    3: ("no hardening branch, Fredriksson mu_m = 0.2, beta = 0.2, n = 275/mm",
        "FREDRIKSS       0.2       0.2     275.0", "OFF"),
    4: ("no hardening branch, Coulomb mu = 0.001", "COULOMB       0.001", "OFF"),
    5: ("frictionless", "NONE", "OFF"),      # the paper's "ideal model", mu = 0: law = "IDEAL"
}


def punch(path, column=2, nnode=4, hp=100.0, hf=100.0, refine=1, nincs=20, update="EXPLICIT",
          unload=False, cn2=None, friction=None, hardening=None, slip=None, law="ROUGH", title=None, options=()):
    """Example 5.1 as a symmetric half model (SPEC §6.1).

    Punch (body A) 0 <= x <= 50, 0 <= y <= hp; foundation (body B) 0 <= x <= 95,
    -hf <= y <= 0, bottom clamped, u_x = 0 on x = 0.  Linear elements (Q4, or T3 with
    nnode = 3) have the paper's 13 contact nodes (Table 2); quadratic ones (Q8, Q9)
    6 contact edges of 50/6 mm (nodes 4.167 mm apart).  refine = k splits every
    cell into k x k.  law = "IDEAL": ideal contact (no roughness: non-penetration and the
    column's friction, augmented Lagrangian) instead of the rough springs; column 5 with
    law = "IDEAL" is the paper's ideal model with mu = 0."""
    quad = nnode >= 8
    if quad:
        xc = [50.0 * i / 6 for i in range(7)]
        yp = [0.0, 50.0 / 6, 50.0 / 3, 25.0, 37.5, 55.0, 75.0, 100.0]
        xo = [50.0, 60.0, 75.0, 95.0]
    else:
        xc = list(map(float, PUNCH_CONTACT_X))
        yp = [0.0, 2.5, 5.0, 7.5, 10.0, 15.0, 20.0, 30.0, 40.0, 55.0, 75.0, 100.0]
        xo = [50.0, 52.5, 55.0, 60.0, 67.5, 77.5, 95.0]
    # the foundation grid mirrors the punch's, both scaled to their heights
    yf = [-y * hf / 100.0 for y in yp[::-1]]
    yp = [y * hp / 100.0 for y in yp]
    xc, xo, yp, yf = (subdivide(g, refine) for g in (xc, xo, yp, yf))
    xf = xc + xo[1:]

    fr, hd = friction, hardening
    if column:
        label, fr0, hd0 = PUNCH_COLUMNS[column]
        fr = fr or fr0
        hd = hd or hd0
    ideal = law == "IDEAL"
    if column == 5:
        label = "frictionless, the ideal model with mu = 0" if ideal else \
            "frictionless rough normal law, no tangential springs"
    elname = {3: "T3", 4: "Q4", 8: "Q8", 9: "Q9"}[nnode]
    d = Deck(title or "Example 5.1, punch on foundation: %s, %s%s" % (
        label if column else fr, elname, ", ideal contact" if ideal and column != 5 else ""),
        ntype=1, nnode=nnode)
    d.block("A", xc, yp, 1)
    d.block("B", xf, yf, 2)
    d.material(1, 4000.0, 0.35, 10.0)
    d.material(2, 4000.0, 0.35, 10.0)
    for body in ("A", "B"):
        for n in d.nodes_where(body, lambda x, y: abs(x) < TOL):
            d.fix(n, "10")
    for n in d.nodes_where("B", lambda x, y: abs(y + hf) < TOL):
        d.fix(n, "11")
    d.edge_pressure("A", lambda x, y: abs(y - hp) < TOL, 1.2)
    normal = "NORMAL           1.0       0.5"
    if cn2 is not None:
        normal += "%10.4f%10.4f" % (cn2, 0.5)
    if ideal:
        d.contact = ["LAW       IDEAL", "FRICTION  " + fr, "UPDATE    " + update]
    else:
        d.contact = ["UNITS     KGF_UM", normal, "TANGENT          1.3       0.5",
                     "FRICTION  " + fr, "HARDENING " + hd] + (["SLIP      " + slip] if slip else []) + [
                     "UPDATE    " + update]
    d.contact += surface_cards(d, lambda x, y: abs(y) < TOL, lambda x, y: abs(y) < TOL and x <= 50.0 + TOL)
    d.increments = history(nincs)
    if unload:
        # back to (almost) zero: the punch is held by the springs only, so the last
        # load factors approach 0 without reaching it (at 0 every pair opens)
        d.increments += [(nincs - 1, [0.05]), (1, [0.02]), (1, [0.01]), (1, [0.005]), (1, [0.002]), (1, [0.001])]
    d.options = list(options)
    d.comments = [
        "Altenbach & Buczkowski, example 5.1 (Bild 4): elastic punch on an elastic foundation.",
        "Units: N, mm, N/mm2 (= MPa); roughness constants c_n, R in um and kgf/cm2 (UNITS KGF_UM,",
        "SPEC D2); the hardening rate n in 1/mm.",
        "Given: A = 190 mm (foundation width), B = 100 mm (punch width), p0 = 1.2 N/mm2 on the punch",
        "top, thickness 10 mm (plane stress), E = 4000 N/mm2, nu = 0.35 (both bodies);",
        "c_n = 1.0, m = 0.5, R = 1.3, S = 0.5, n = 275/mm.",
        ("Ideal contact (LAW IDEAL): no roughness, non-penetration and the friction below enforced by" if ideal
         else ""),
        ("an augmented Lagrangian; the roughness constants are not used." if ideal else ""),
        "Assumed (SPEC 6.1, D11; not in the paper): symmetric half model (u_x = 0 on x = 0),",
        "punch height %g mm, foundation height %g mm, foundation base clamped, sides free;" % (hp, hf),
        "%s elements%s; contact nodes at the positions of Table 2;" % (
            elname, "" if refine == 1 else ", every cell of the reference mesh split %d x %d" % (refine, refine)),
        "load 5 %% in the first increment, then %d equal increments to p0" % (nincs - 1),
        ("then unloaded in %d equal increments to 5 %% and in 5 more to 0.1 %% of p0 (unloading branch" % (nincs - 1))
        if unload else "(the paper does not give the load history; 20 increments reproduce Table 1).",
        ("c_n2 = %g, m2 = 0.5; at zero load every pair would open and the punch would be free)." % (
            cn2 if cn2 is not None else 0.5)) if unload else "",
        "Case: %s; %supdate %s%s." % (label if column else fr, "ideal contact; " if ideal and column != 5 else "",
                                        update,
                                     "; effective slip from gross slip only (SLIP %s)" % slip if slip else ""),
        "Generated by tools/make_examples.py; do not edit by hand.",
    ]
    d.comments = [c for c in d.comments if c]
    d.write(path)
    return d


# --------------------------------------------------------------------------------------------
# Example 5.2: elastic sphere on an elastic half-space (Bilder 6-9)
# --------------------------------------------------------------------------------------------
SPHERE_R = 15.0
SPHERE_E = 21000.0
SPHERE_NU = 0.3


def hertz_sphere(P, R=SPHERE_R, E=SPHERE_E, nu=SPHERE_NU):
    """Hertz (Johnson 1985, ch. 4) for two equal bodies: contact radius a, peak pressure p0, approach delta."""
    estar = 1.0 / (2.0 * (1.0 - nu * nu) / E)
    a = (3.0 * P * R / (4.0 * estar)) ** (1.0 / 3.0)
    return a, 3.0 * P / (2.0 * math.pi * a * a), a * a / R


def grow(h0, length, q):
    """Grid from 0 to `length` whose cells start at about h0 and grow by the factor q."""
    if q <= 1.0 + 1e-12:
        n = max(1, int(math.ceil(length / h0 - 1e-9)))
        return graded(0.0, length, n)
    n = max(1, int(math.ceil(math.log(1.0 + (q - 1.0) * length / h0) / math.log(q) - 1e-9)))
    return graded(0.0, length, n, ratio=q ** (n - 1)) if n > 1 else [0.0, length]


def contact_grid(h, r_fine, r_reach, q=1.12):
    """Radii of the contact nodes: uniform spacing h up to r_fine, then growing by q up to r_reach."""
    n = max(1, int(round(r_fine / h)))
    xs = [r_fine * i / n for i in range(n + 1)]
    if r_reach > r_fine:
        xs += [r_fine + x for x in grow(h * q, r_reach - r_fine, q)[1:]]
    return xs


def interp(xs, t):
    """Linear interpolation in the list xs at the fractional index t."""
    i = min(int(math.floor(t)), len(xs) - 2)
    return xs[i] + (t - i) * (xs[i + 1] - xs[i])


def ogrid(d, body, mat, s, core_x, core_y, outer2, outer1, radial, to_global, radial_far=None, blend=None):
    """A quarter disc {xi, eta >= 0, |(xi, eta)| <= rho} in local coordinates, as three
    structured blocks (an O-grid): the core square [0, s]^2 on the grid core_x x core_y;
    block 2 between the core side eta = s and the arc from 90 deg (xi = 0) to 45 deg,
    whose outer points are outer2(i) for the fractional index i of core_x; block 1
    between the core side xi = s and the arc from 0 deg to 45 deg (outer1(j), index of
    core_y).  `radial` (0 .. 1, core to arc) grades both outer blocks; to_global maps
    local to model coordinates.  With radial_far (as many entries as radial) and
    blend(i) (0 .. 1, 1 at i = n1), block 2 moves from the grading `radial` to
    `radial_far` along the arc and block 1 has `radial_far`: fine cells at the arc only
    where they are needed."""
    d.block(body, core_x, core_y, mat, mapping=lambda x, y: to_global(x, y))
    far = radial_far or radial
    w2 = blend or (lambda i: 0.0)

    def spoke(inner, outer, weight):
        def f(i, k):
            w = weight(i)
            t = (1.0 - w) * interp(radial, k) + w * interp(far, k)
            (x0, y0), (x1, y1) = inner(i), outer(i)
            return to_global((1.0 - t) * x0 + t * x1, (1.0 - t) * y0 + t * y1)
        return f

    n1, n2 = len(core_x) - 1, len(core_y) - 1
    ks = [float(k) for k in range(len(radial))]
    d.block(body, [float(i) for i in range(n1 + 1)], ks, mat,
            mapping=spoke(lambda i: (interp(core_x, i), s), outer2, w2))
    d.block(body, [float(j) for j in range(n2 + 1)], ks, mat,
            mapping=spoke(lambda j: (s, interp(core_y, j)), outer1, lambda j: 1.0 if radial_far else 0.0))


def sphere(path, P, cn=None, nnode=4, hdiv=20.0, fine=3.0, reach=5.0, q=1.12, rho_b=120.0,
           nincs=40, update="EXPLICIT", smooth="IDEAL", pen=1.0e-8, nstart=3, firstinc=None, repeats=None,
           title=None, options=()):
    """Example 5.2, axisymmetric (SPEC §6.2): hemisphere of radius 15 mm, flat face up and
    loaded by the uniform pressure P / (pi R^2); half-space = quarter disc of radius rho_b
    (a hemisphere in 3D) with its outer boundary fixed.  Node-to-node pairs at equal radii
    with the initial gaps g0(r) = R - sqrt(R^2 - r^2).  Contact nodes: spacing
    h = a_H / hdiv up to fine * a_H, then growing by q up to reach * a_H (a_H the Hertz
    radius at P).  cn = None: the smooth surface, with smooth = "IDEAL" the ideal law
    (LAW IDEAL, non-penetration by an augmented Lagrangian), with smooth = "PENALTY" the
    penalty limit of the rough law (SPEC §7: m = 1, c_n = pen mm/(N/mm2), UNITS MODEL);
    otherwise the rough law c_n [um/(kgf/cm2)^0.5], m = 0.5.  Frictionless (no tangential
    springs) in every case."""
    R = SPHERE_R
    aH, p0H, dH = hertz_sphere(P)
    h = aH / hdiv
    r_reach = min(reach * aH, 0.55 * R)
    rc = contact_grid(h, min(fine * aH, r_reach), r_reach, q)
    ideal = cn is None and smooth == "IDEAL"
    surf = ("smooth (ideal law)" if ideal else "smooth (penalty limit)") if cn is None else "rough c_n = %g" % cn
    d = Deck(title or "Example 5.2, sphere on half-space: P = %g N, %s" % (P, surf), ntype=3, nnode=nnode)

    # sphere (body A): centre (0, R); local xi = r, eta = R - z (downwards)
    c45 = R / math.sqrt(2.0)
    p45 = (c45, c45)
    s_a = 0.4 * R
    arc = rc + [rc[-1] + x for x in grow(rc[-1] - rc[-2], c45 - rc[-1], 1.25)[1:]]
    n1 = len(arc) - 1
    core_x = [s_a * i / n1 for i in range(n1 + 1)]
    n2 = 6
    core_y = [s_a * j / n2 for j in range(n2 + 1)]

    def outer2a(i):
        if i >= n1:
            return p45
        r = interp(arc, i)
        return (r, math.sqrt(R * R - r * r))

    def outer1a(j):
        if j >= n2:
            return p45
        th = 0.25 * math.pi * j / n2
        return (R * math.cos(th), R * math.sin(th))

    rad_a = [1.0 - x for x in reversed(grow(h / (R - s_a), 1.0, q))]
    # away from the contact the sphere's cells need not be thin at its surface: the radial
    # grading blends into a uniform one between r_reach and the 45 degree line
    far_a = [k / (len(rad_a) - 1.0) for k in range(len(rad_a))]

    def blend_a(i):
        r = interp(arc, min(i, n1))
        w = min(max((r - r_reach) / (c45 - r_reach), 0.0), 1.0)
        return w * w * (3.0 - 2.0 * w)
    ogrid(d, "A", 1, s_a, core_x, core_y, outer2a, outer1a, rad_a, lambda x, y: (x, R - y),
          radial_far=far_a, blend=blend_a)

    # half-space (body B): centre (0, 0); local xi = r, eta = -z
    s_b = min(max(4.0 * r_reach, 10.0 * aH), 0.3 * rho_b)
    bx = rc + [rc[-1] + x for x in grow((rc[-1] - rc[-2]) * q, s_b - rc[-1], q)[1:]]
    by = grow(h, s_b, q)
    m1, m2 = len(bx) - 1, len(by) - 1
    pb45 = (rho_b / math.sqrt(2.0), rho_b / math.sqrt(2.0))

    def outer2b(i):
        if i >= m1:
            return pb45
        th = 0.5 * math.pi - 0.25 * math.pi * i / m1
        return (rho_b * math.cos(th), rho_b * math.sin(th))

    def outer1b(j):
        if j >= m2:
            return pb45
        th = 0.25 * math.pi * j / m2
        return (rho_b * math.cos(th), rho_b * math.sin(th))

    # radial cells of the outer blocks: from about the core's last cell size, growing
    rad_b = grow((by[-1] - by[-2]) / (rho_b - s_b), 1.0, 1.2)
    ogrid(d, "B", 2, s_b, bx, by, outer2b, outer1b, rad_b, lambda x, y: (x, -y))

    # contact pairs: the sphere's arc nodes and the half-space's surface nodes at r <= r_reach
    sa = d.nodes_where("A", lambda x, y: x <= r_reach + TOL and abs(y - (R - math.sqrt(max(R * R - x * x, 0.0)))) < 1e-7)
    sb = d.nodes_where("B", lambda x, y: x <= r_reach + TOL and abs(y) < TOL)
    byr = {round(d.nodes[k - 1][0], 7): k for k in sb}
    links = [(a, byr[round(d.nodes[a - 1][0], 7)]) for a in sa]
    new = d.renumber(links)
    sa = sorted(new[k] for k in sa)
    sb = sorted(new[k] for k in sb)

    d.material(1, SPHERE_E, SPHERE_NU)
    d.material(2, SPHERE_E, SPHERE_NU)
    for n in d.nodes_where("B", lambda x, y: abs(math.hypot(x, y) - rho_b) < 1e-7):
        d.fix(n, "11")
    d.edge_pressure("A", lambda x, y: abs(y - R) < TOL, P / (math.pi * R * R))
    if ideal:
        law = ["LAW       IDEAL"]
    elif cn is None:
        law = ["UNITS     MODEL", "NORMAL    %10.3e       1.0" % pen]
    else:
        law = ["UNITS     KGF_UM", "NORMAL    %10.4f       0.5" % cn]
    d.options = list(options)
    d.contact = law + ["FRICTION  NONE", "UPDATE    " + update] + (["FIRSTINC  " + firstinc] if firstinc else []) + (
        ["REPEATS   %10d" % repeats] if repeats else []) + [
                       "START     %10s%10d" % ("", nstart),
                       "SURFACE   A"] + d.node_list_cards(sa) + ["SURFACE   B"] + d.node_list_cards(sb)
    d.increments = history(nincs)
    d.comments = [
        "Altenbach & Buczkowski, example 5.2 (Bild 6): elastic sphere on an elastic half-space.",
        "Units: N, mm, N/mm2 (= MPa), axisymmetric (x = r, y = z; forces are ring totals);",
        ("roughness constant c_n in um/(kgf/cm2)^m (UNITS KGF_UM, SPEC D2)." if cn is not None else
         "smooth surface: ideal contact (LAW IDEAL), non-penetration by an augmented Lagrangian." if ideal else
         "smooth surface: linear penalty springs, c_n in mm/(N/mm2) (UNITS MODEL, SPEC 7)."),
        "Given: sphere radius R = 15 mm, E = 21000 N/mm2, nu = 0.3 (both bodies), half-space 'A = 120 mm';",
        "rough: c_n = 0.3 or 0.8, m = 0.5, frictionless; 3 closed pairs at the start (START NSTART 3).",
        "Case: P = %g N, %s; Hertz a = %.4f mm, p0 = %.1f N/mm2, delta = %.2f um." % (
            P, "smooth, ideal contact" if ideal else "smooth, penalty c_n = %g, m = 1" % pen if cn is None
            else "c_n = %g, m = 0.5" % cn, aH, p0H, 1e3 * dH),
        "Assumed (not in the paper): a hemisphere, flat face up, loaded by the uniform pressure",
        "P/(pi R^2) = %.5f N/mm2; the half-space is a quarter disc (a hemisphere in 3D) of radius" % (P / (math.pi * R * R)),
        "%g mm, outer boundary fixed; %s elements, O-grid meshes; contact nodes at equal radii," % (
            rho_b, {3: "T3", 4: "Q4", 8: "Q8", 9: "Q9"}[nnode]),
        "node to node, spacing h = a_H/%g = %.4f mm up to r = %.3f mm, then growing to r = %.3f mm;" % (
            hdiv, h, min(fine * aH, r_reach), r_reach),
        "initial gaps g0(r) = R - sqrt(R^2 - r^2) from the node positions; load in %d increments" % nincs,
        "(5 %% first, then equal), update %s." % update,
        ("NEWTON, not the paper's explicit scheme: with 3 start pairs on a mesh this fine the explicit"
         if update == "NEWTON" and cn is not None else ""),
        ("scheme's start secant and frozen secants of newly closed pairs leave the pair forces far off"
         if update == "NEWTON" and cn is not None else ""),
        ("the normal law (docs/validation.md, example 5.2)." if update == "NEWTON" and cn is not None else ""),
        "Generated by tools/make_examples.py; do not edit by hand.",
    ]
    d.comments = [c for c in d.comments if c]
    d.write(path)
    return d


# --------------------------------------------------------------------------------------------
# Example 5.3: rigid hollow cylinder on an elastic half-space (Bilder 10-12)
# --------------------------------------------------------------------------------------------
CYL_RI = 25.0
CYL_RA = 50.0


def cylinder(path, P, cn=0.44, e_half=4.0e4, nnode=4, h=0.5, rho_b=500.0, q=1.12, nincs=20,
             update="EXPLICIT", hardening="OFF", mu=0.3, smooth=None, pen=1.0e-8, rigid="BODY", title=None,
             options=()):
    """Example 5.3, axisymmetric (SPEC §6.3): a rigid hollow cylinder (annulus 25 <= r <= 50 mm)
    pressed by the force P onto a half-space (quarter disc of radius rho_b, outer boundary
    fixed).  rigid = "BODY": the cylinder is a rigid body, a flat annular profile (RIGID FLAT)
    carried by a reference node that takes the force (in axisymmetry it moves axially only);
    rigid = "TIES": a layer of elements whose nodes all have u_r = 0 and share one u_z (TIES),
    loaded at one of them, node-to-node pairs.  Contact nodes spaced h across the annulus, no
    gaps.  Interface: m = 0.59, R = 0.67, S = 0.40 (R kept while c_n varies, as in the paper),
    Coulomb mu = 0.3; smooth = "IDEAL": the ideal law (no roughness) with Coulomb mu,
    smooth = "PENALTY": the penalty limit of the rough law (SPEC §7), frictionless."""
    body = rigid == "BODY"
    case = {None: "c_n = %g" % cn, "IDEAL": "smooth (ideal law), mu = %g" % mu,
            "PENALTY": "smooth, frictionless (penalty limit)"}[smooth]
    d = Deck(title or "Example 5.3, rigid hollow cylinder on half-space: P = %g N, %s, E = %g%s" % (
        P, case, e_half, "" if body else ", tied mesh"), ntype=3, nnode=nnode)
    n = max(1, int(round((CYL_RA - CYL_RI) / h)))
    ann = [CYL_RI + (CYL_RA - CYL_RI) * i / n for i in range(n + 1)]
    hh = ann[1] - ann[0]
    if not body:
        # the rigid cylinder: one layer of elements over the annulus
        d.block("A", ann, [0.0, 5.0], 1)
    # half-space: core [0, s] x [0, s] graded towards the annulus and the surface, then an O-grid
    s_b = 3.0 * CYL_RA
    inner = [CYL_RI - x for x in reversed(grow(hh * q, CYL_RI, q))]
    outer = [CYL_RA + x for x in grow(hh * q, s_b - CYL_RA, q)]
    bx = inner[:-1] + ann + outer[1:]
    by = grow(hh, s_b, q)
    m1, m2 = len(bx) - 1, len(by) - 1
    p45 = (rho_b / math.sqrt(2.0), rho_b / math.sqrt(2.0))

    def arc(th):
        return (rho_b * math.cos(th), rho_b * math.sin(th))

    mat_b = 1 if body else 2
    ogrid(d, "B", mat_b, s_b, bx, by,
          lambda i: p45 if i >= m1 else arc(0.5 * math.pi - 0.25 * math.pi * i / m1),
          lambda j: p45 if j >= m2 else arc(0.25 * math.pi * j / m2),
          grow((by[-1] - by[-2]) / (rho_b - s_b), 1.0, 1.2), lambda x, y: (x, -y))
    sb = d.nodes_where("B", lambda x, y: abs(y) < TOL and CYL_RI - TOL <= x <= CYL_RA + TOL)
    if body:
        new = d.renumber()
        sb = sorted(new[k] for k in sb)
        # the reference node (no element) above the middle of the annulus
        ref = d.reference_node(0.5 * (CYL_RI + CYL_RA), 5.0)
        d.point_load(ref, 0.0, -P)
    else:
        sa = d.nodes_where("A", lambda x, y: abs(y) < TOL)
        byr = {round(d.nodes[k - 1][0], 7): k for k in sb}
        new = d.renumber([(a, byr[round(d.nodes[a - 1][0], 7)]) for a in sa])
        sa = sorted(new[k] for k in sa)
        sb = sorted(new[k] for k in sb)
        d.material(1, 100.0 * e_half, 0.3)
        rigid_nodes = d.nodes_where("A", lambda x, y: True)
        for k in rigid_nodes:
            d.fix(k, "10")
        d.tie("01", rigid_nodes)
        d.point_load(rigid_nodes[0], 0.0, -P)
    d.material(mat_b, e_half, 0.3)
    for k in d.nodes_where("B", lambda x, y: abs(math.hypot(x, y) - rho_b) < 1e-7):
        d.fix(k, "11")
    friction = "FRICTION  COULOMB   %10.4f" % mu if mu > 0 else "FRICTION  NONE"
    if smooth == "IDEAL":
        law = ["LAW       IDEAL", friction]
    elif smooth == "PENALTY":
        law = ["UNITS     MODEL", "NORMAL    %10.3e       1.0" % pen, "FRICTION  NONE"]
    else:
        law = ["UNITS     KGF_UM", "NORMAL    %10.4f      0.59" % cn, "TANGENT         0.67      0.40",
               friction, "HARDENING " + hardening]
    d.options = list(options)
    if body:
        # the bottom face of the cylinder, listed with the body on its left (deck-format.md)
        surfaces = ["RIGID     FLAT      %10d%s%s%s%s" % (ref, f10(CYL_RI), f10(0.0), f10(CYL_RA), f10(0.0)),
                    "SURFACE   A"] + d.node_list_cards(sb)
    else:
        surfaces = ["SURFACE   A"] + d.node_list_cards(sa) + ["SURFACE   B"] + d.node_list_cards(sb)
    d.contact = law + ["UPDATE    " + update] + surfaces
    d.increments = history(nincs)
    pm = P / (math.pi * (CYL_RA ** 2 - CYL_RI ** 2))
    d.comments = [
        "Altenbach & Buczkowski, example 5.3 (Bild 10): rigid hollow cylinder on an elastic half-space.",
        "Units: N, mm, N/mm2 (= MPa), axisymmetric (x = r, y = z; forces are ring totals); roughness",
        "constants c_n, R in um and kgf/cm2 (UNITS KGF_UM, SPEC D2).",
        "Given: R_I = 25 mm, R_A = 50 mm, m = 0.59, R = 0.67, S = 0.40, mu_m = mu = 0.3 (constant),",
        "nu = 0.3, 'different c_n' (values lost with the figures), P = 10 kN, 100 kN, 1 MN.",
        "Case: P = %g N (p_m = P/(pi (R_A^2 - R_I^2)) = %.4g N/mm2), %s, E_half-space = %g N/mm2." % (
            P, pm, {None: "c_n = %g" % cn,
                    "IDEAL": "smooth: ideal contact (LAW IDEAL), Coulomb mu = %g" % mu,
                    "PENALTY": "smooth and frictionless (penalty limit of SPEC 7: m = 1, c_n = %g mm/(N/mm2),"
                               " UNITS MODEL)" % pen}[smooth], e_half),
        "Assumed (SPEC 6.3, D10; not in the paper): E_half-space = 4e4 N/mm2 (the printed 4e7 read as",
        "kN/m2; the printed value is a second run), the cylinder exactly rigid:",
        ("a rigid body (RIGID FLAT, its bottom face R_I..R_A moved axially by its reference node, which"
         if body else "u_r = 0 and one u_z for all nodes of one layer of elements (TIES), the force at one node;"),
        "takes the force);" if body else "",
        "c_n in {0.2, 0.44, 1.0} with R = 0.67 kept (R = 0.67 belongs to c_n = 0.44 by eq. 2.8),",
        "no hardening branch (HARDENING %s); the half-space is a quarter disc (a hemisphere in 3D)" % hardening,
        "of radius %g mm, outer boundary fixed; %s elements; %d contact pairs %.3f mm apart across" % (
            rho_b, {3: "T3", 4: "Q4", 8: "Q8", 9: "Q9"}[nnode], len(sb), hh),
        "the annulus, %s, no gaps;" % ("half-space nodes against the rigid profile" if body else "node to node"),
        "load in %d increments (5 %% first, then equal), update %s." % (nincs, update),
        "Generated by tools/make_examples.py; do not edit by hand.",
    ]
    d.comments = [c for c in d.comments if c]
    d.write(path)
    return d


# --------------------------------------------------------------------------------------------
# The decks of tools/paper_figures.py
# --------------------------------------------------------------------------------------------
SPHERE_LOADS = [50.0, 200.0, 500.0, 2000.0, 5000.0, 20000.0]
SPHERE_SURFACES = {"smooth": None, "c0.3": 0.3, "c0.8": 0.8}
CYL_LOADS = {"10kN": 1.0e4, "100kN": 1.0e5, "1MN": 1.0e6}
CYL_CN = [0.2, 0.44, 1.0]
CYL_MODULI = {"E4e4": 4.0e4, "E4e7": 4.0e7, "E2.1e5": 2.1e5}


def variants():
    """Every deck tools/paper_figures.py runs: name -> (generator, keyword arguments)."""
    v = {}
    # 5.1: Table 1 columns, Table 2 meshes, sensitivity to the assumptions, Bild 5
    # (column 5 is the paper's ideal model: punch_col5_ideal; punch_col5, the rough normal law
    # without tangential springs, was its stand-in and stays as a cross-check)
    for c in range(1, 6):
        v["punch_col%d" % c] = (punch, dict(column=c))
    v["punch_col5_ideal"] = (punch, dict(column=5, law="IDEAL"))
    v["punch_col2_t3"] = (punch, dict(column=2, nnode=3))
    v["punch_col2_q8"] = (punch, dict(column=2, nnode=8))
    v["punch_col2_q9"] = (punch, dict(column=2, nnode=9))
    for c, law, tag in ((2, "ROUGH", "col2"), (5, "IDEAL", "col5_ideal")):
        v["punch_%s_hp50" % tag] = (punch, dict(column=c, law=law, hp=50.0))
        v["punch_%s_hp190" % tag] = (punch, dict(column=c, law=law, hp=190.0))
        v["punch_%s_hf75" % tag] = (punch, dict(column=c, law=law, hf=75.0))
        v["punch_%s_hf150" % tag] = (punch, dict(column=c, law=law, hf=150.0))
        v["punch_%s_fine" % tag] = (punch, dict(column=c, law=law, refine=2))
    # the increments: the rough law only (frictionless ideal contact does not depend on them)
    v["punch_col2_n10"] = (punch, dict(column=2, nincs=10))
    v["punch_col2_n40"] = (punch, dict(column=2, nincs=40))
    v["punch_col2_newton"] = (punch, dict(column=2, update="NEWTON"))
    v["punch_col5_newton"] = (punch, dict(column=5, update="NEWTON"))
    for tag, kw in (("n40", dict(nincs=40)), ("newton", dict(update="NEWTON")), ("fine", dict(refine=2)),
                    ("gross", dict(slip="GROSS")), ("n550", dict(friction="FREDRIKSS       0.2       0.2     550.0"))):
        v["punch_col3_" + tag] = (punch, dict(column=3, **kw))
    v["punch_col1_newton"] = (punch, dict(column=1, update="NEWTON"))
    v["punch_col1_n40"] = (punch, dict(column=1, nincs=40))
    for cn2 in (0.5, 0.25):
        v["punch_fig5_cn2_%g" % cn2] = (punch, dict(column=5, cn2=cn2, unload=True))
    # 5.2: converged (NEWTON) pressures and radii for every load and surface, the paper's
    # explicit scheme beside them, and the convergence studies
    # (the smooth surface: the ideal law; its former stand-in, the penalty limit of the rough
    # law, stays as a cross-check at the loads of Bilder 7 and 8)
    for P in SPHERE_LOADS:
        for sk, cn in SPHERE_SURFACES.items():
            v["sphere_P%d_%s" % (P, sk)] = (sphere, dict(P=P, cn=cn, update="NEWTON", nincs=20))
    for P in (200.0, 20000.0):
        v["sphere_P%d_penalty" % P] = (sphere, dict(P=P, cn=None, smooth="PENALTY", update="NEWTON", nincs=20))
    for P in (200.0, 20000.0):
        for sk in ("c0.3", "c0.8"):
            v["sphere_P%d_%s_paper" % (P, sk)] = (sphere, dict(P=P, cn=SPHERE_SURFACES[sk], nincs=40))
        v["sphere_P%d_c0.8_h10" % P] = (sphere, dict(P=P, cn=0.8, update="NEWTON", nincs=20, hdiv=10.0))
        v["sphere_P%d_c0.8_h40" % P] = (sphere, dict(P=P, cn=0.8, update="NEWTON", nincs=20, hdiv=40.0))
        v["sphere_P%d_c0.8_rho60" % P] = (sphere, dict(P=P, cn=0.8, update="NEWTON", nincs=20, rho_b=60.0))
        v["sphere_P%d_c0.8_rho240" % P] = (sphere, dict(P=P, cn=0.8, update="NEWTON", nincs=20, rho_b=240.0))
        v["sphere_P%d_c0.8_q8" % P] = (sphere, dict(P=P, cn=0.8, update="NEWTON", nincs=20, nnode=8, hdiv=10.0))
        v["sphere_P%d_smooth_h40" % P] = (sphere, dict(P=P, cn=None, update="NEWTON", nincs=20, hdiv=40.0))
        v["sphere_P%d_c0.8_n5" % P] = (sphere, dict(P=P, cn=0.8, update="NEWTON", nincs=5))
    v["sphere_P200_c0.8_paper_n20"] = (sphere, dict(P=200.0, cn=0.8, nincs=20))
    v["sphere_P200_c0.8_paper_n80"] = (sphere, dict(P=200.0, cn=0.8, nincs=80))
    # (the iterated first increment needs 37 solutions, more than the default 30)
    v["sphere_P200_c0.8_paper_iterate"] = (sphere, dict(P=200.0, cn=0.8, nincs=40, firstinc="ITERATE", repeats=100))
    v["sphere_P200_c0.8_paper_nstart40"] = (sphere, dict(P=200.0, cn=0.8, nincs=40, nstart=40))
    # 5.3: three loads x three c_n with the moduli of D10, the printed and a steel half-space,
    # the smooth surface (ideal law, Coulomb 0.3; frictionless: ideal and its former stand-in,
    # the penalty limit), the converged scheme, a finer mesh; the cylinder a rigid body, and as
    # a tied layer of elements for comparison
    for lk, P in CYL_LOADS.items():
        for ek, E in CYL_MODULI.items():
            for cn in CYL_CN:
                v["cyl_%s_c%g_%s" % (lk, cn, ek)] = (cylinder, dict(P=P, cn=cn, e_half=E))
        v["cyl_%s_ideal_E4e4" % lk] = (cylinder, dict(P=P, smooth="IDEAL"))
        v["cyl_%s_ideal0_E4e4" % lk] = (cylinder, dict(P=P, smooth="IDEAL", mu=0.0))
        v["cyl_%s_penalty_E4e4" % lk] = (cylinder, dict(P=P, smooth="PENALTY"))
        v["cyl_%s_c0.2_E4e4_ties" % lk] = (cylinder, dict(P=P, cn=0.2, rigid="TIES"))
        v["cyl_%s_c0.2_E4e4_newton" % lk] = (cylinder, dict(P=P, cn=0.2, update="NEWTON"))
        v["cyl_%s_c0.2_E4e4_fine" % lk] = (cylinder, dict(P=P, cn=0.2, h=0.25))
    v["cyl_1MN_c0.2_E4e4_rho250"] = (cylinder, dict(P=1.0e6, cn=0.2, rho_b=250.0))
    v["cyl_1MN_c0.2_E4e4_rho1000"] = (cylinder, dict(P=1.0e6, cn=0.2, rho_b=1000.0))
    v["cyl_1MN_c0.2_E4e4_branch"] = (cylinder, dict(P=1.0e6, cn=0.2, hardening="ON        0.045"))
    v["cyl_1MN_c0.2_E4e4_n40"] = (cylinder, dict(P=1.0e6, cn=0.2, nincs=40))
    v["cyl_1MN_c1_E4e4_ties"] = (cylinder, dict(P=1.0e6, cn=1.0, rigid="TIES"))
    v["cyl_1MN_ideal_E4e4_ties"] = (cylinder, dict(P=1.0e6, smooth="IDEAL", rigid="TIES"))
    return v


def write_variants(outdir, names=None):
    """Write the decks of variants() (or of the given names) into outdir; returns their paths."""
    os.makedirs(outdir, exist_ok=True)
    paths = {}
    for name, (fn, kw) in variants().items():
        if names and name not in names:
            continue
        path = os.path.join(outdir, name + ".dat")
        fn(path, **kw)
        paths[name] = path
    return paths


def punch_graded(path, factor=0.25, radius=25.0, **kw):
    """punch() with the mesh graded towards the corner of the punch, (x, y) = (50, 0): the
    elements there shrink smoothly to `factor` times their size, the nodes within `radius`
    mm of the corner move towards it, those beyond stay (k2d.deck.Deck.grade_towards).  The
    pressure and u_T peak at the corner and converge slowest with a uniform refinement
    (docs/accuracy-and-stability.md, the cost study)."""
    d = punch(path, **kw)
    d.grade_towards((50.0, 0.0), radius, factor)
    d.comments = [c.replace("; contact nodes at the positions of Table 2;", ";") for c in d.comments]
    d.comments.insert(-1, "Mesh graded towards the punch corner (50, 0): the elements there shrink to %g times" % factor)
    d.comments.insert(-1, "their size, nodes within %g mm of the corner move towards it (radial map)." % radius)
    d.write(path)
    return d


# The example decks of inputs/: each the cheapest model of the cost study (tools/study.py,
# docs/accuracy-and-stability.md) that meets 1 % against its converged reference, and a
# *_fine deck beside it that stands for the reference (they run in the test suite, the fine
# ones under the label slow).  The paper's own settings (its meshes and its explicit scheme)
# are the variants punch_col2, sphere_P200_c0.8_paper and cyl_100kN_c0.44_E4e4 of --all.
# Decks with many increments write every 10th or 40th to the result file (OPTIONS RESULTS).
EXAMPLES = {
    # Q8, the paper's mesh split 2 x 2 and graded towards the punch corner, 80 Newton increments:
    # edge pressure 0.64 %, u_T at the edge 0.96 % off the reference
    "punch_5_1": (punch_graded, dict(factor=0.25, radius=25.0, column=2, nnode=8, refine=2, nincs=80,
                                     update="NEWTON", options=["RESULTS   %10d" % 10])),
    # the reference of the study: split 4 x 4, graded to 0.1, 320 increments
    "punch_5_1_fine": (punch_graded, dict(factor=0.1, radius=25.0, column=2, nnode=8, refine=4, nincs=320,
                                          update="NEWTON", options=["RESULTS   %10d" % 40])),
    # Q4, contact nodes a_H/5 apart, one Newton increment (the converged scheme is path independent
    # for this monotonic frictionless load): peak 0.87 %, contact radius 0.27 %
    "sphere_5_2": (sphere, dict(P=200.0, cn=0.8, update="NEWTON", nincs=1, hdiv=5.0)),
    # nodes a_H/20 apart: within 0.11 % of the study's reference (Q8, a_H/40)
    "sphere_5_2_fine": (sphere, dict(P=200.0, cn=0.8, update="NEWTON", nincs=5, hdiv=20.0)),
    # Q8, contact nodes 0.5 mm apart, 320 Newton increments (the tangential law is rate-type, so the
    # shear depends on the increment size): p(R_A) 0.06 %, largest shear 0.72 % off the reference
    "cylinder_5_3": (cylinder, dict(P=1.0e5, cn=0.44, nnode=8, h=1.0, nincs=320, update="NEWTON",
                                    options=["RESULTS   %10d" % 40])),
    # nodes 0.25 mm apart: p(R_A) 0.02 %, largest shear 0.28 % below the study's reference (nodes
    # 0.125 mm apart, 640 increments)
    "cylinder_5_3_fine": (cylinder, dict(P=1.0e5, cn=0.44, nnode=8, h=0.5, nincs=320, update="NEWTON",
                                         options=["RESULTS   %10d" % 40])),
}


# --------------------------------------------------------------------------------------------
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--all", metavar="DIR", help="write every variant into DIR")
    ap.add_argument("--list", action="store_true", help="list the variants")
    args = ap.parse_args(argv)
    if args.list:
        for name in variants():
            print(name)
        return
    if args.all:
        paths = write_variants(args.all)
        print("%d decks in %s" % (len(paths), args.all))
        return
    for name, (fn, kw) in EXAMPLES.items():
        fn(os.path.join(ROOT, "inputs", name + ".dat"), **kw)
        print("inputs/%s.dat" % name)


if __name__ == "__main__":
    main()
