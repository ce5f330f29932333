#!/usr/bin/python3
"""Generate the decks of this directory: ideal (smooth) contact with Coulomb
friction, rigid bodies, non-matching meshes, and the closed-form benchmarks of
SPEC §7 (V6 Hertz sphere, V8 Hertz cylinder, V10 and V11 rigid flat punches),
a frictional block and a rigid annular punch (SPEC §6.3).

Run from anywhere: tests/decks/ideal/make_decks.py.  The decks are committed;
rerun this script after changing it.  Meshes and the truncation of the
half-space are described in docs/validation-contact.md.

Units of every deck: N, mm, N/mm2.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "tools"))
from k2d import examples  # noqa: E402
from k2d.deck import Deck, fine_then_graded, f10  # noqa: E402

E_STEEL10 = 21000.0     # the paper's example 5.2 (1/10 of steel)
NU = 0.3


# ------------------------------------------------------------------ meshes

def half_space(d, body, mat, xs, ys, L, q):
    """A truncated half-space (or half-plane): the quarter disc x >= 0, y <= 0
    of radius L around the origin.  A core block on the product grid xs x ys
    (xs from 0 to c, ys from -c to 0, so the core is the square [0,c]x[-c,0])
    and two ring blocks from the core's right and bottom sides to the arc,
    graded radially by the factor q per cell from the core's cell size."""
    c = xs[-1]
    assert abs(ys[0] + c) < 1e-12 and ys[-1] == 0.0
    d.block(body, xs, ys, mat)
    h = min(xs[-1] - xs[-2], ys[1] - ys[0])
    radial = fine_then_graded(0.0, 1.0, h / (L - c), h / (L - c), q)
    depths = sorted(-y for y in ys)        # 0 .. c, down the core's right side

    def ring1(x, v):                       # right side (c, -x) -> arc from 0 to -45 degrees
        th = -(math.pi / 4) * (x / c)
        return ((1 - v) * c + v * L * math.cos(th), (1 - v) * (-x) + v * L * math.sin(th))

    def ring2(x, v):                       # bottom side (-x, -c) -> arc from -90 to -45 degrees
        th = -math.pi / 2 + (math.pi / 4) * ((-x) / c)
        return ((1 - v) * (-x) + v * L * math.cos(th), (1 - v) * (-c) + v * L * math.sin(th))

    d.block(body, depths, radial, mat, mapping=ring1)
    d.block(body, sorted(-x for x in xs), radial, mat, mapping=ring2)


def ball(d, body, mat, R, rs, ts, q):
    """The quarter disc of a sphere (axisymmetric) or cylinder (plane) of radius
    R touching y = 0 at the origin: centre (0, R), flat face y = R on top.

    It is meshed as a flat quarter disc |z| <= 2R, Im z >= 0 (a core block on
    the grid xi(rs) x ts and two graded ring blocks, as the half-space) and
    mapped by the Moebius transformation w = z / (1 - i z / (2R)), which is
    conformal, maps the real axis onto the sphere's surface, the imaginary
    axis onto the axis, the arc |z| = 2R onto the flat top face, and is the
    identity to first order at the contact point: near the contact the mesh is
    the flat one.  rs are the radii of the core's surface nodes (those of the
    half-space for node-to-node pairs), ts the core's heights."""
    def flat_of_r(r):                        # inverse of r(xi) = xi / (1 + xi^2 / 4R^2)
        return 0.0 if r == 0.0 else (2 * R * R / r) * (1.0 - math.sqrt(1.0 - (r / R) ** 2))

    def w(x, y):
        z = complex(x, y)
        m = z / (1 - 1j * z / (2 * R))
        return (m.real, m.imag)

    xs = [flat_of_r(r) for r in rs]
    c = xs[-1]
    ts = [t * c / ts[-1] for t in ts[:-1]] + [c]
    L = 2 * R
    d.block(body, xs, ts, mat, mapping=w)
    h = min(xs[-1] - xs[-2], ts[-1] - ts[-2])
    radial = fine_then_graded(0.0, 1.0, h / (L - c), h / (L - c), q)

    def ring1(x, v):                       # right side (c, -x) -> arc from 0 to 45 degrees
        th = (math.pi / 4) * ((-x) / c)
        return w((1 - v) * c + v * L * math.cos(th), (1 - v) * (-x) + v * L * math.sin(th))

    def ring2(x, v):                       # top side (x, c) -> arc from 90 to 45 degrees
        th = math.pi / 2 - (math.pi / 4) * (x / c)
        return w((1 - v) * x + v * L * math.cos(th), (1 - v) * c + v * L * math.sin(th))

    d.block(body, sorted(-t for t in ts), radial, mat, mapping=ring1)
    d.block(body, xs, radial, mat, mapping=ring2)


def surface_cards(d, body, pred, side):
    return ["SURFACE   " + side] + d.node_list_cards(d.nodes_where(body, pred))


def near_links(d, a_nodes, b_nodes):
    """Pairs (a, nearest b in x) for the renumbering: contact couples them."""
    bx = sorted((d.nodes[k - 1][0], k) for k in b_nodes)
    out = []
    j = 0
    for k in sorted(a_nodes, key=lambda k: d.nodes[k - 1][0]):
        x = d.nodes[k - 1][0]
        while j + 1 < len(bx) and abs(bx[j + 1][0] - x) <= abs(bx[j][0] - x):
            j += 1
        out.append((k, bx[j][1]))
    return out


def fix_far_boundary(d, body, L):
    """The truncation of the half-space: zero displacement on the arc of radius L."""
    for n in d.nodes_where(body, lambda x, y: abs(math.hypot(x, y) - L) < 1e-6 * L):
        d.fix(n, "11")


# ------------------------------------------------------------------ V6 / V8 Hertz

def hertz(name, ntype, P, R, a_h, law_cards, title, comments, h_frac=20.0, fine=2.0, core_fine=1.2, q_core=1.12,
          q_far=1.12, L_frac=None, segment_mesh=False, incs=None):
    """Elastic ball (sphere in axisymmetry, cylinder in plane strain) of radius R
    on an elastic half-space of the same material, loaded by a uniform
    pressure on its flat top face.  Contact surfaces meshed with h = a_h/h_frac
    up to fine a_h, graded beyond.  segment_mesh: the ball's surface grid is
    offset and 0.7 times as fine (non-matching) and the pairs use MATCHING SEGMENT."""
    d = Deck(title, ntype=ntype, nnode=4)
    d.comments = comments + ["Generated by make_decks.py."]
    h = a_h / h_frac
    L = L_frac * a_h if L_frac else 120.0
    c = fine * a_h
    xs = fine_then_graded(0.0, c, h, core_fine * a_h, q_core)
    half_space(d, "HS", 2, xs, [-x for x in reversed(xs)], L, q_far)
    if segment_mesh:
        hb = globals().get("SEG_RATIO", 0.7) * h
        rs = [0.0] + [0.5 * hb + k * hb for k in range(int(core_fine * a_h / hb))]
        rs += fine_then_graded(rs[-1], c, hb, 0.0, q_core)[1:]
    else:
        rs = xs
    ball(d, "BALL", 1, R, rs, fine_then_graded(0.0, c, h, core_fine * a_h, q_core), q_far)
    d.material(1, E_STEEL10, NU, 1.0)
    d.material(2, E_STEEL10, NU, 1.0)
    on_ball = lambda x, y: y < 1e-9 + R - math.sqrt(max(R * R - x * x, 0.0)) and x <= c * (1 + 1e-9)  # noqa: E731
    on_hs = lambda x, y: abs(y) < 1e-12 and x <= c * (1 + 1e-9) + (2 * h if segment_mesh else 0.0)  # noqa: E731
    sa = d.nodes_where("BALL", on_ball)
    sb = d.nodes_where("HS", on_hs)
    d.renumber(near_links(d, sa, sb))
    fix_far_boundary(d, "HS", L)
    if ntype != 3:
        for n in d.nodes_where("HS", lambda x, y: abs(x) < 1e-12):
            d.fix(n, "10")
        for n in d.nodes_where("BALL", lambda x, y: abs(x) < 1e-12):
            d.fix(n, "10")
    # load: uniform pressure on the flat top face (total P; per unit length P/2 on the half model in plane)
    ptop = P / (math.pi * R * R) if ntype == 3 else P / (2.0 * R)
    d.edge_pressure("BALL", lambda x, y: abs(y - R) < 1e-9, ptop)
    # the ball is held by contact alone: close the pair of smallest gap at the
    # start (the paper's "start nodes"; with averaged segment gaps none is exactly 0)
    d.contact = law_cards + ["START               %10d" % 1] + (["MATCHING  SEGMENT"] if segment_mesh else []) + \
        surface_cards(d, "BALL", on_ball, "A") + surface_cards(d, "HS", on_hs, "B")
    d.increments = incs or [(1, [1.0])]
    d.write(os.path.join(HERE, name + ".dat"))
    return d


def hertz_sphere(name, P, law_cards, segment_mesh=False, incs=None, extra=(), fine=2.0):
    R = 15.0
    estar = 1.0 / (2 * (1 - NU ** 2) / E_STEEL10)
    a = (3 * P * R / (4 * estar)) ** (1.0 / 3.0)
    p0 = 3 * P / (2 * math.pi * a * a)
    comments = ["V6 (SPEC 7, 6.2): elastic sphere R = 15 on an elastic half-space, E = 21000, nu = 0.3 for",
                "both (E* = 11538.5), axisymmetric, P = %g N: Hertz a = %.4f mm, p0 = %.1f N/mm2." % (P, a, p0),
                "Sphere: the hemisphere with its flat face on top, loaded by a uniform pressure P/(pi R^2).",
                "Half-space: the quarter disc of radius 120 mm about the contact point, fixed on the arc.",
                "Q4 elements, h = a/20 on both surfaces up to 1.2a, growing by 12 % per element beyond."] + list(extra)
    return hertz(name, 3, P, R, a, law_cards, "V6 Hertz: elastic sphere on elastic half-space, P = %g N" % P,
                 comments + ["Contact surfaces (and the core of both meshes) up to %g a." % fine],
                 segment_mesh=segment_mesh, incs=incs, fine=fine)


# ------------------------------------------------------------------ punches

def rigid_flat_punch(name, ntype, b, load_cards, title, comments, L_frac=400.0, h_frac=40.0, friction="NONE",
                     law="IDEAL", extra_contact=()):
    """A rigid flat punch of half width (radius) b on a half-space (quarter disc of
    radius L_frac b), the punch face from x = 0 to b; its reference node above.
    Uniform elements h = b/h_frac in the core [0, 1.25b] x [-1.25b, 0], growing by
    12 % per element beyond."""
    d = Deck(title, ntype=ntype, nnode=4)
    d.comments = comments + ["Generated by make_decks.py."]
    h = b / h_frac
    c = 1.25 * b
    xs = fine_then_graded(0.0, c, h, c, 1.0)
    L = L_frac * b
    half_space(d, "HS", 1, xs, [-x for x in reversed(xs)], L, 1.12)
    d.material(1, E_STEEL10, NU, 1.0)
    d.renumber()
    ref = d.reference_node(0.5 * b, 0.5 * b)
    fix_far_boundary(d, "HS", L)
    if ntype != 3:
        for n in d.nodes_where("HS", lambda x, y: abs(x) < 1e-12):
            d.fix(n, "10")
    load_cards(d, ref)
    d.contact = ["LAW       " + law, "FRICTION  " + friction, "RIGID     FLAT      %10d%s%s%s%s" %
                 (ref, f10(0.0), f10(0.0), f10(b), f10(0.0))] + list(extra_contact) + \
        surface_cards(d, "HS", lambda x, y: abs(y) < 1e-12 and x <= b + 1e-9, "A")
    d.write(os.path.join(HERE, name + ".dat"))
    return d, ref


def v10(name="v10_punch"):
    a, delta = 1.0, 1.0e-3
    estar = E_STEEL10 / (1 - NU ** 2)

    def load(d, ref):
        d.fix(ref, "01", uy=-delta)
    rigid_flat_punch(name, 3, a, load, "V10 rigid flat circular punch on an elastic half-space",
                     ["V10 (SPEC 7, Boussinesq/Sneddon): rigid flat circular punch of radius a = 1 mm pressed",
                      "by delta = %g mm into a half-space E = 21000, nu = 0.3 (axisymmetric):" % delta,
                      "P = 2 a E* delta = %.4f N, K = 2 a E* = %.1f N/mm," % (2 * a * estar * delta, 2 * a * estar),
                      "p(r) = P / (2 pi a sqrt(a^2 - r^2)).  Punch: RIGID FLAT, its reference node driven",
                      "down (prescribed u_z); the half-space: quarter disc of radius 400 a, fixed on the arc,",
                      "Q4 with h = a/40 in the core [0, 1.25a] x [-1.25a, 0], growing by 12 % per element beyond."])


def v11(name="v11_punch"):
    b, P = 1.0, 100.0

    def load(d, ref):
        d.fix(ref, "10")
        d.point_load(ref, 0.0, -P / 2)
    rigid_flat_punch(name, 2, b, load, "V11 rigid flat punch on an elastic half-plane (Sadowsky)",
                     ["V11 (SPEC 7, Sadowsky): rigid flat punch of half width b = 1 mm, P' = %g N/mm," % P,
                      "plane strain, E = 21000, nu = 0.3: p(x) = P' / (pi sqrt(b^2 - x^2)).",
                      "Half model (u_x = 0 on x = 0): the reference node carries P'/2 and is held in x.",
                      "Half-plane: quarter disc of radius 400 b, fixed on the arc; Q4, h = b/40 up to 1.25b."])


# ------------------------------------------------------------------ V8 rigid cylinder

def v8_rigid(name="v8_hertz_rigid"):
    R, P, E = 50.0, 100.0, 2.1e5
    estar = E / (1 - NU ** 2)
    a = math.sqrt(4 * P * R / (math.pi * estar))
    d = Deck("V8 Hertz: rigid cylinder on an elastic half-plane, plane strain", ntype=2, nnode=4)
    d.comments = ["V8 (SPEC 7): rigid cylinder R = 50 mm, P' = 100 N/mm, on E = 2.1e5, nu = 0.3 (plane strain):",
                  "a = %.4f mm, p0 = %.1f N/mm2.  Cylinder: RIGID CIRCLE; half model (u_x = 0 on x = 0)," %
                  (a, 2 * P / (math.pi * a)),
                  "the reference node carries P'/2.  Half-plane: quarter disc of radius 200 a, fixed on the arc;",
                  "Q4 with h = a/20 up to 1.2a, growing by 12 % per element beyond.", "Generated by make_decks.py."]
    h = a / 20.0
    c = 2.0 * a
    xs = fine_then_graded(0.0, c, h, 1.2 * a, 1.12)
    L = 200.0 * a
    half_space(d, "HS", 1, xs, [-x for x in reversed(xs)], L, 1.12)
    d.material(1, E, NU, 1.0)
    d.renumber()
    ref = d.reference_node(0.0, R)
    fix_far_boundary(d, "HS", L)
    for n in d.nodes_where("HS", lambda x, y: abs(x) < 1e-12):
        d.fix(n, "10")
    d.fix(ref, "10")
    d.point_load(ref, 0.0, -P / 2)
    d.contact = ["LAW       IDEAL", "FRICTION  NONE",
                 "RIGID     CIRCLE    %10d%s%s%s" % (ref, f10(0.0), f10(R), f10(R))] + \
        surface_cards(d, "HS", lambda x, y: abs(y) < 1e-12 and x <= c + 1e-9, "A")
    d.write(os.path.join(HERE, name + ".dat"))


def v8_segment(name="v8_hertz_segment"):
    """Elastic cylinder R = 15 on an elastic block, non-matching meshes."""
    R, P = 15.0, 200.0
    estar = 1.0 / (2 * (1 - NU ** 2) / E_STEEL10)
    a = math.sqrt(4 * P * R / (math.pi * estar))
    p0 = 2 * P / (math.pi * a)
    hertz(name, 2, P, R, a, ["LAW       IDEAL", "FRICTION  NONE"],
          "V8 Hertz: elastic cylinder on elastic half-plane, non-matching meshes",
          ["V8 (SPEC 7): elastic cylinder R = 15 on an elastic half-plane, both E = 21000, nu = 0.3,",
           "plane strain, P' = %g N/mm: a = %.4f mm, p0 = %.1f N/mm2.  Half model." % (P, a, p0),
           "The cylinder's surface nodes are 0.7 times as dense as the half-plane's and offset:",
           "MATCHING SEGMENT pairs every cylinder node with a point of a half-plane edge."],
          segment_mesh=True)


# ------------------------------------------------------------------ friction block

def friction_block(name="friction_block", law="IDEAL"):
    """An elastic block (nu = 0) on a RIGID FLAT base with Coulomb friction mu = 0.3:
    normal force N on the tied top, then the top is driven sideways beyond full
    slip and back."""
    W, H, N, mu = 10.0, 10.0, 100.0, 0.3
    d = Deck("Frictional block on a rigid base: tangential force saturates at mu N", ntype=2, nnode=4)
    d.comments = ["Block 10 x 10 (E = 1000, nu = 0), plane strain, on a rigid flat base (RIGID FLAT, its",
                  "reference node fixed), Coulomb mu = 0.3.  Case 1: N = 100 N on the tied top.",
                  "Case 2: the top's x displacement (factor 1 = 0.1 mm): out to 0.2 mm, back to 0.16 mm.",
                  "Expected: F_T = k U (stick) up to mu N = 30 N, then F_T = mu N (slip everywhere); on",
                  "reversal F_T falls with the stick stiffness k (elastic unloading) until -mu N.",
                  "Generated by make_decks.py."]
    xs = [W * i / 10 for i in range(11)]
    ys = [H * j / 10 for j in range(11)]
    d.block("A", xs, ys, 1)
    d.material(1, 1000.0, 0.0, 1.0)
    ref = d.reference_node(5.0, -1.0)      # the base lies below y = 0: its face is listed right to left
    top = d.nodes_where("A", lambda x, y: abs(y - H) < 1e-12)
    d.tie("01", top)
    for n in top:
        d.fix(n, "10", ux=0.1, case=2)
    d.fix(ref, "11")
    d.point_load(top[0], 0.0, -N, case=1)
    d.contact = ["LAW       " + law, "NORMAL           1.0       0.5", "FRICTION  COULOMB  %10s" % mu,
                 "HARDENING OFF", "RIGID     FLAT      %10d%s%s%s%s" % (ref, f10(W + 1.0), f10(0.0), f10(-1.0), f10(0.0))] + \
        surface_cards(d, "A", lambda x, y: abs(y) < 1e-12, "A")
    d.increments = [(1, [1.0, None]), (40, [None, 2.0]), (10, [None, 1.6])]
    d.write(os.path.join(HERE, name + ".dat"))


# ------------------------------------------------------------------ patch test, non-matching meshes

def patch_nonmatching(name, ntype, nnode, law, na=5, nb=7):
    """Contact patch test across non-matching meshes: block A (na elements across)
    pressed by a uniform pressure p0 = 1 onto block B (nb elements across, graded),
    nu = 0, B's bottom held in y (and one node in x).  Every pair must carry p0
    exactly (MATCHING SEGMENT transfers a uniform pressure exactly)."""
    W, H = 10.0, 5.0
    d = Deck("Patch test of contact across non-matching meshes (%d against %d elements), %s law" % (na, nb, law),
             ntype=ntype, nnode=nnode)
    d.comments = ["Uniform pressure p0 = 1 N/mm2 on block A [0,10]x[0,5] (%d elements across) resting on" % na,
                  "block B [0,10]x[-5,0] (%d graded elements across), E = 1000, nu = 0; B's bottom held in y." % nb,
                  "MATCHING SEGMENT: p_n = p0 at every pair (exact, to round-off).", "Generated by make_decks.py."]
    xa = [W * i / na for i in range(na + 1)]
    xb = [W * (i / nb) ** 1.3 for i in range(nb + 1)]
    d.block("A", xa, [0.0, H / 2, H], 1)
    d.block("B", xb, [-H, -H / 2, 0.0], 2)
    d.material(1, 1000.0, 0.0, 1.0)
    d.material(2, 1000.0, 0.0, 1.0)
    for n in d.nodes_where("B", lambda x, y: abs(y + H) < 1e-12):
        d.fix(n, "01")
    if ntype != 3:
        d.fix(d.nodes_where("B", lambda x, y: abs(y + H) < 1e-12)[0], "11")
        d.fix(d.nodes_where("A", lambda x, y: abs(x) < 1e-12)[0], "10")
    d.edge_pressure("A", lambda x, y: abs(y - H) < 1e-12, 1.0)
    rough = ["LAW       ROUGH", "UNITS     KGF_UM", "NORMAL           1.0       0.5", "UPDATE    RETURN"]
    d.contact = (rough if law == "ROUGH" else ["LAW       IDEAL"]) + ["FRICTION  NONE", "MATCHING  SEGMENT"] + \
        surface_cards(d, "A", lambda x, y: abs(y) < 1e-12, "A") + surface_cards(d, "B", lambda x, y: abs(y) < 1e-12, "B")
    d.increments = [(1, [0.05]), (3, [1.0])]
    d.write(os.path.join(HERE, name + ".dat"))


def polyline_patch(name="polyline_patch"):
    """A block under a uniform pressure on a rigid base given as a POLYLINE of
    collinear segments: p_n = p0 at every pair (nu = 0)."""
    W, H = 10.0, 5.0
    d = Deck("Patch test on a rigid polyline base (collinear segments)", ntype=2, nnode=4)
    d.comments = ["Block [0,10]x[0,5] (E = 1000, nu = 0, plane strain) under p0 = 1 N/mm2 on a rigid base whose",
                  "profile is a POLYLINE of three collinear segments, listed right to left (the body below",
                  "y = 0 on the left of the walk); ideal frictionless contact: p_n = p0 at every pair.",
                  "Generated by make_decks.py."]
    d.block("A", [W * i / 5 for i in range(6)], [0.0, H / 2, H], 1)
    d.material(1, 1000.0, 0.0, 1.0)
    ref = d.reference_node(5.0, -2.0)
    d.fix(ref, "11")
    d.fix(d.nodes_where("A", lambda x, y: abs(x) < 1e-12 and abs(y) < 1e-12)[0], "10")
    d.edge_pressure("A", lambda x, y: abs(y - H) < 1e-12, 1.0)
    d.contact = ["LAW       IDEAL", "FRICTION  NONE", "RIGID     POLYLINE  %10d" % ref,
                 f10(W + 1.0) + f10(0.0), f10(4.3) + f10(0.0), f10(2.0) + f10(0.0), f10(-1.0) + f10(0.0)] + \
        surface_cards(d, "A", lambda x, y: abs(y) < 1e-12, "A")
    d.write(os.path.join(HERE, name + ".dat"))


# ------------------------------------------------------------------ rigid annulus (SPEC 6.3)

def annulus(name="annulus_rigid"):
    """The paper's third example as a rigid annular punch: R_I = 25, R_A = 50 mm on a
    half-space E = 4e4 (SPEC D10), rough interface m = 0.59, R = 0.67, S = 0.40, mu = 0.3,
    P = 10 kN on the punch's reference node (coarse mesh: a regression deck, not a study)."""
    d = Deck("Rigid annular punch (SPEC 6.3) on a rough interface", ntype=3, nnode=4)
    d.comments = ["SPEC 6.3 / D10: rigid hollow cylinder R_I = 25, R_A = 50 mm as a RIGID FLAT annulus,",
                  "half-space E = 4e4 N/mm2, nu = 0.3 (a cylinder r <= 500, depth 500, bottom fixed).",
                  "Rough interface c_n = 0.44, m = 0.59, R = 0.67, S = 0.40, Coulomb mu = 0.3; P = 10 kN.",
                  "p_m = P / (pi (R_A^2 - R_I^2)) = 1.698 N/mm2.", "Generated by make_decks.py."]
    xs = fine_then_graded(0.0, 25.0, 5.0, 25.0, 1.0) + [25.0 + 1.25 * k for k in range(1, 21)] + \
        fine_then_graded(50.0, 500.0, 1.25, 0.0, 1.25)[1:]
    ys = [-y for y in reversed(fine_then_graded(0.0, 500.0, 1.25, 5.0, 1.25))]
    d.block("HS", xs, ys, 1)
    d.material(1, 4.0e4, 0.3, 1.0)
    d.renumber()
    ref = d.reference_node(37.5, 10.0)
    for n in d.nodes_where("HS", lambda x, y: abs(y + 500.0) < 1e-9):
        d.fix(n, "11")
    d.point_load(ref, 0.0, -1.0e4)
    d.contact = ["LAW       ROUGH", "UNITS     KGF_UM", "NORMAL          0.44      0.59",
                 "TANGENT         0.67      0.40", "FRICTION  COULOMB         0.3", "HARDENING OFF",
                 "RIGID     FLAT      %10d%s%s%s%s" % (ref, f10(25.0), f10(0.0), f10(50.0), f10(0.0))] + \
        surface_cards(d, "HS", lambda x, y: abs(y) < 1e-12 and 25.0 - 1e-9 <= x <= 50.0 + 1e-9, "A")
    d.increments = [(1, [0.05]), (9, [1.0])]
    d.write(os.path.join(HERE, name + ".dat"))


def v6_quadratic_start(name="v6_hertz_q8_start3"):
    """Example 5.2's smooth sphere (k2d.examples.sphere) with Q8 elements, a coarse
    contact mesh and the paper's 3 start pairs, 5 % first increment: two of the
    start pairs lie across open gaps, and a quadratic edge loaded at its midside
    lifts its corner on the axis, so a first solution that ignored the gaps found
    every start pair open (a singular system, or under condensation a body out of
    equilibrium by 14 % of the load)."""
    d = examples.sphere(os.path.join(HERE, name + ".dat"), P=200.0, cn=None, nnode=8, hdiv=2.5, nincs=5,
                        update="NEWTON", rho_b=20.0, q=1.5, fine=2.0, reach=3.0)
    d.comments.insert(0, "Ideal law, Q8, start pairs across gaps (tests/decks/ideal/make_decks.py, v6_quadratic_start).")
    d.write(os.path.join(HERE, name + ".dat"))


if __name__ == "__main__":
    ideal = ["LAW       IDEAL", "NORMAL           0.3       0.5", "FRICTION  NONE"]
    hertz_sphere("v6_hertz_p200", 200.0, ideal, fine=2.5)
    hertz_sphere("v6_hertz_p20000", 20000.0, ideal)
    hertz_sphere("v6_hertz_p200_segment", 200.0, ideal, segment_mesh=True,
                 extra=["Non-matching: the sphere's surface nodes are 0.7 times as dense and offset;",
                        "MATCHING SEGMENT pairs each of them with a point of a half-space edge."])
    v8_rigid()
    v8_segment()
    v10()
    v11()
    friction_block()
    annulus()
    patch_nonmatching("patch_segment_plane_q4_rough", 2, 4, "ROUGH")
    patch_nonmatching("patch_segment_axi_q8_rough", 3, 8, "ROUGH", na=6, nb=4)
    patch_nonmatching("patch_segment_plane_q8_ideal", 2, 8, "IDEAL", na=6, nb=4)
    patch_nonmatching("patch_segment_axi_q4_ideal", 3, 4, "IDEAL")
    polyline_patch()
    v6_quadratic_start()
