"""Generated scenes: valid decks a new user could write, run and checked.

A *scene* is two rectangular bodies, A on top of B, touching along y = 0 through one contact
interface, built from a seeded random draw over what the deck format offers:

* bodies: E from 1e3 to 1e9 N/mm2 (log-uniform), nu from 0 to 0.45, the same material in both
  bodies or two different ones; plane stress, plane strain or axisymmetric (the bodies on the
  axis or an annulus off it); T3, Q4, Q8 or Q9 elements; meshes that match node for node
  (MATCHING NODE) or not (MATCHING SEGMENT, A the finer);
* the interface: the rough law (c_n from the literature's range in kgf/cm2 and um, m from 0.15,
  the exponent of measured steel surfaces (tools/calibrate.py topography), to the literature's 0.8; c_n2 <= c_n
  with m2 = m, admissible at every pressure, or m2 > m with c_n2 such that the unloading branch is
  admissible to twice the largest pressure of the history), Coulomb, Fredriksson or no friction, the hardening
  branch on or off, or ideal contact (frictionless or Coulomb);
* the history: a pressure p0 on A's top (load case 1) loaded and unloaded to exactly zero,
  reloaded, partly unloaded, or held while A's top is moved tangentially (load case 2) forward,
  back past zero (a reversal) and home again; 5 to 200 increments per stroke.

Every scene's deck is written by k2d.deck and run by the program.  A scene passes when the run
completes (exit code 0) and its results are on the law and, where the scene has one, on the
closed form at every increment end:

* the law, every rough scene: each closed pair's closure against the law at the pair's own
  pressure, u = c_n p^m while its pressure exceeds every earlier one, u = u_A - c_n2 (p_A^m2 -
  p^m2) below its largest pressure so far p_A (docs/contact.md), at most u_res = u_A - c_n2 p_A^m2
  at zero force; to 1e-8 of the run's largest closure: the program returns every pair to its law
  exactly and its Newton iterations end at 1e-10 of the out-of-balance force, and 1e-8 is the
  accuracy asked of every increment end;
* the *uniform* scenes (one material in both bodies, a pressure load only, matching meshes or
  frictionless ones): the exact solution is the uniform uniaxial stress sigma_y = -lambda p0
  (plane and axisymmetric alike, represented exactly by every element: a patch test), so every
  pair carries the pressure lambda p0, to 1e-8 of p0.  (With MATCHING SEGMENT and friction a
  uniform state is not exact: the averaged partner point of an end node, or of any node in
  axisymmetry, is not where the node is, so a linear radial displacement makes a tangential
  relative displacement of 1e-7 of the closure and shear of that order.)  Ideal contact
  converges on its penetration instead (AUGMENTED TOL x the element length): its penetration
  is checked against that, its pressures to the stress such a penetration can cause,
  E/(1 - nu^2) x TOL.

    from k2d.scenes import draw, run_scene
    sc = draw(seed=7)                     # a Scene
    out = run_scene(sc, exe, workdir)     # a dict: exit code, checks, messages
"""
import math
import os
import random
import subprocess
import time

from k2d import laws
from k2d.deck import Deck, f10

__all__ = ["KGF", "ELEMENTS", "HISTORIES", "Scene", "draw", "deck_constants", "model_constants",
           "tangential_stroke", "build_deck", "branch_closure", "check_law", "check_uniform", "check_result",
           "run_scene"]

KGF = laws.KGF_CM2            # N/mm2 per kgf/cm2

ELEMENTS = (3, 4, 8, 9)
HISTORIES = ("unload", "reload", "partial", "tangential")


class Scene:
    """The drawn parameters of one scene (plain attributes; `describe()` says them in a line)."""

    def __init__(self, **kw):
        self.__dict__.update(kw)

    def describe(self):
        law = ("ideal" if self.law == "IDEAL" else
               "rough c_n=%.3g m=%.2f c_n2=%.3g m2=%.2f" % (self.cn, self.m, self.cn2, self.m2))
        fr = self.friction if self.friction == "NONE" else "%s mu=%.2f" % (self.friction, self.mu)
        if self.law == "ROUGH" and self.friction != "NONE":
            fr += " hardening " + ("ON" if self.hardening else "OFF")
        mats = ("E=%.3g nu=%.2f" % (self.EA, self.nuA) if self.uniform_material else
                "E_A=%.3g nu_A=%.2f E_B=%.3g nu_B=%.2f" % (self.EA, self.nuA, self.EB, self.nuB))
        return ("%s %s T%d/Q%d %s %s; %s; %s; p0=%.3g N/mm2, %s, %d incr/stroke" %
                (self.name, ("plane stress", "plane strain", "axisymmetric")[self.ntype - 1],
                 self.nnode, self.nnode, self.matching, mats, law, fr, self.p0, self.history,
                 self.nstroke)).replace("T3/Q3", "T3").replace("T4/", "").replace("T8/", "").replace("T9/", "")

    @property
    def uniform(self):
        """The scene has the closed form of a uniform uniaxial stress (see the module doc)."""
        return (self.uniform_material and self.history != "tangential" and
                (self.matching == "NODE" or self.friction == "NONE"))


def _log_uniform(rng, a, b):
    return _q(math.exp(rng.uniform(math.log(a), math.log(b))))


def _q(x):
    """x as the deck's ten columns write it (the checks must use the constants the program reads)."""
    return float(f10(x))


def draw(seed):
    """The scene of one seed (the same seed gives the same scene)."""
    rng = random.Random(seed)
    ntype = rng.choice((1, 2, 3))
    nnode = rng.choice(ELEMENTS)
    law = "IDEAL" if rng.random() < 0.25 else "ROUGH"
    friction = rng.choice(("COULOMB", "COULOMB", "FREDRIKSSON", "NONE")) if law == "ROUGH" else \
        rng.choice(("COULOMB", "NONE"))
    history = rng.choice(HISTORIES)
    if friction == "NONE" and history == "tangential":
        history = rng.choice(HISTORIES[:3])
    uniform_material = rng.random() < 0.5
    EA = _log_uniform(rng, 1e3, 1e9)
    nuA = _q(rng.uniform(0.0, 0.45))
    if uniform_material:
        EB, nuB = EA, nuA
    else:
        EB = _log_uniform(rng, 1e3, 1e9)
        nuB = _q(rng.uniform(0.0, 0.45))
    # the rough law: c_n from the machine-tool literature's range (kgf/cm2, um), m from the
    # exponents of measured surfaces (0.15-0.22, docs/calibration.md) to the literature's 0.8;
    # admissible at any pressure
    m = _q(rng.uniform(0.15, 0.8))
    cn = _log_uniform(rng, 0.2, 3.0)
    cn2 = _q(cn * rng.uniform(0.3, 1.0))
    m2 = m
    p0 = _log_uniform(rng, 0.1, 10.0)
    if rng.random() < 0.3:
        # an unloading exponent above m: admissible for reversal pressures up to
        # p* = min[(cn/cn2)^(1/(m2-m)), (cn m/(cn2 m2))^(1/(m2-m))] (docs/deck-format.md NORMAL);
        # cn2 is chosen so that p* is at least twice the largest pressure of any history (1.2 p0)
        m2 = _q(m * rng.uniform(1.05, 1.3))
        pmax_kgf = 2.4 * p0 / KGF
        cn2 = _q(cn * (m / m2) * pmax_kgf ** (-(m2 - m)) * rng.uniform(0.5, 1.0))
    nx_b = rng.choice((2, 3, 4, 6, 8))
    matching = "NODE"
    nx_a = nx_b
    if rng.random() < 0.3:
        matching = "SEGMENT"
        nx_a = nx_b + rng.choice((1, 2, 3))
    width = rng.choice((10.0, 20.0, 40.0))
    x0 = 0.0
    if ntype == 3 and rng.random() < 0.5:
        x0 = rng.choice((5.0, 20.0))
    return Scene(
        name="scene_%05d" % seed, seed=seed, ntype=ntype, nnode=nnode, law=law, friction=friction,
        mu=_q(rng.uniform(0.1, 0.5)), beta=_q(rng.uniform(0.3, 1.0)), nfred=_log_uniform(rng, 10.0, 1e4),
        hardening=rng.random() < 0.6, history=history, uniform_material=uniform_material,
        EA=EA, nuA=nuA, EB=EB, nuB=nuB, m=m, cn=cn, cn2=cn2, m2=m2,
        units=rng.choice(("KGF_UM", "N_UM")),
        p0=p0, nstroke=rng.choice((5, 10, 20, 50, 200)),
        tangential_factor=rng.uniform(0.3, 3.0),
        nx_a=nx_a, nx_b=nx_b, ny_a=rng.choice((1, 2, 3)), ny_b=rng.choice((1, 2, 3)),
        width=width, height_a=width * rng.choice((0.25, 0.5, 1.0)),
        height_b=width * rng.choice((0.25, 0.5, 1.0)), x0=x0, matching=matching)


def deck_constants(sc):
    """c_n and c_n2 as the deck writes them (ten columns), in the scene's UNITS: drawn in kgf/cm2
    and um, converted for N_UM."""
    if sc.units == "KGF_UM":
        return _q(sc.cn), _q(sc.cn2)
    f = laws.pressure_scale("KGF_UM")
    return _q(sc.cn * f ** sc.m), _q(sc.cn2 * f ** sc.m2)


def model_constants(sc):
    """c_n and c_n2 in model units (mm, N/mm2), converted from the deck's values as the program
    converts them (docs/contact.md, SPEC 2.4)."""
    cn, cn2 = deck_constants(sc)
    return laws.model_constant(cn, sc.m, sc.units), laws.model_constant(cn2, sc.m2, sc.units)


def tangential_stroke(sc):
    """The tangential displacement of A's top [mm]: tangential_factor times an estimate of the
    slip onset, mu p0 / k_T of the interface plus the bodies' shear compliance."""
    if sc.law == "IDEAL":
        return sc.tangential_factor * sc.mu * sc.p0 * (sc.height_a + sc.height_b) / min(sc.EA, sc.EB) * 3.0
    cnm, _ = model_constants(sc)
    # k_T = p^S / R with R = 2 c_n m (1 + nu), S = 1 - m (model units), per unit area
    R = laws.r_literature(cnm, sc.m, 0.5 * (sc.nuA + sc.nuB))
    kt = laws.tangential_stiffness(sc.p0, 1.0 - sc.m, R)
    u_slip = sc.mu * sc.p0 / kt
    shear = sc.mu * sc.p0 * (sc.height_a / sc.EA + sc.height_b / sc.EB) * 2.6
    return sc.tangential_factor * (u_slip + shear)


def build_deck(sc, path):
    """Write the scene's deck to `path`; returns the Deck."""
    d = Deck("generated scene %d: %s" % (sc.seed, sc.history), ntype=sc.ntype, nnode=sc.nnode)
    d.comments.append(sc.describe())
    d.comments.append("units: N, mm, N/mm2; written by tools/scenes.py (k2d.scenes)")
    x0, W = sc.x0, sc.width
    xa = [x0 + W * k / sc.nx_a for k in range(sc.nx_a + 1)]
    xb = [x0 + W * k / sc.nx_b for k in range(sc.nx_b + 1)]
    ya = [sc.height_a * k / sc.ny_a for k in range(sc.ny_a + 1)]
    yb = [-sc.height_b + sc.height_b * k / sc.ny_b for k in range(sc.ny_b + 1)]
    d.block("A", xa, ya, 1)
    d.block("B", xb, yb, 2)
    d.material(1, sc.EA, sc.nuA)
    d.material(2, sc.EB, sc.nuB)
    top = d.nodes_where("A", lambda x, y: abs(y - sc.height_a) < 1e-9)
    bottom = d.nodes_where("B", lambda x, y: abs(y + sc.height_b) < 1e-9)
    for n in bottom:
        d.fix(n, "01")
    if sc.ntype == 3 and x0 == 0.0:
        for body in ("A", "B"):
            for n in d.nodes_where(body, lambda x, y: abs(x) < 1e-12):
                d.fix(n, "10")
    elif sc.ntype != 3:
        # plane: one node of each body holds it in x (the uniform solution has no reaction there)
        d.fix(bottom[0], "11")
        if sc.history != "tangential":
            d.fix(top[0], "10")
    if sc.history == "tangential":
        u = tangential_stroke(sc)
        for n in top:
            d.fix(n, "10", ux=u, case=2)
    d.edge_pressure("A", lambda x, y: abs(y - sc.height_a) < 1e-9, sc.p0, case=1)
    surf_a = d.nodes_where("A", lambda x, y: abs(y) < 1e-9)
    surf_b = d.nodes_where("B", lambda x, y: abs(y) < 1e-9)
    c = ["LAW       " + sc.law]
    if sc.law == "ROUGH":
        cn, cn2 = deck_constants(sc)
        c.append("UNITS     " + sc.units)
        c.append("NORMAL    " + f10(cn) + f10(sc.m) + f10(cn2) + f10(sc.m2))
    if sc.friction == "NONE":
        c.append("FRICTION  NONE")
    elif sc.friction == "COULOMB":
        c.append("FRICTION  COULOMB   " + f10(sc.mu))
    else:
        c.append("FRICTION  FREDRIKSS " + f10(sc.mu) + f10(sc.beta) + f10(sc.nfred))
    if sc.law == "ROUGH" and sc.friction != "NONE":
        c.append("HARDENING " + ("ON" if sc.hardening else "OFF"))
    if sc.matching == "SEGMENT":
        c.append("MATCHING  SEGMENT")
    c.append("SURFACE   A")
    c += d.node_list_cards(surf_a)
    c.append("SURFACE   B")
    c += d.node_list_cards(surf_b)
    d.contact = c
    n = sc.nstroke
    ncase = 2 if sc.history == "tangential" else 1
    inc = []

    def step(k, l1, l2=None):
        inc.append((k, [l1] if ncase == 1 else [l1, l2]))

    if sc.history == "unload":
        step(n, 1.0)
        step(n, 0.0)
    elif sc.history == "reload":
        step(n, 1.0)
        step(n, 0.0)
        step(n, 1.0)
    elif sc.history == "partial":
        step(n, 1.0)
        step(max(1, n // 2), 0.3)
        step(n, 1.2)
        step(n, 0.0)
    else:
        step(max(1, n // 2), 1.0, None)
        step(n, None, 1.0)
        step(2 * n, None, -1.0)
        step(n, None, 0.0)
        step(max(1, n // 2), 0.0, None)
    d.increments = inc
    d.write(path)
    return d


def branch_closure(sc, p, pa):
    """The rough law's closure at pressure p on the branch of a pair whose largest pressure so far
    (its reversal point A) is pa, in model units: the virgin curve u = c_n p^m at p >= pa, else
    the unloading branch u = u_A - c_n2 (p_A^m2 - p^m2) (docs/contact.md)."""
    cnm, cn2m = model_constants(sc)
    if p >= pa:
        return laws.virgin_closure(p, cnm, sc.m)
    return laws.unloading_closure(p, laws.virgin_closure(pa, cnm, sc.m), pa, cn2m, sc.m2)


def check_law(sc, r):
    """Every closed pair of a rough scene on its normal law at every increment end: its closure
    against the law at its own pressure, on the branch through the largest pressure it carried so
    far (the reversal point of a pair is its committed state at an increment end), to 1e-8 of the
    largest closure of the run.  Any scene, any history."""
    msgs = []
    area = r.contact.area
    pmax = [0.0] * len(area)
    hist = [(s, s.contact("pressure"), s.contact("closure"), s.contact("normal_state")) for s in r.steps]
    uscale = max([float(max(u)) for _, _, u, _ in hist] + [0.0])
    checked = 0
    for s, p, u, ns in hist:
        worst, jw = 0.0, -1
        for j in range(len(area)):
            if area[j] <= 0.0:
                continue
            if ns[j] != 0:
                checked += 1
                ulaw = branch_closure(sc, max(p[j], 0.0), pmax[j])
                # at zero force the law holds every closure up to its zero-force point
                # (a pair resting there, or below it and about to open)
                d = max(u[j] - ulaw, 0.0) if p[j] <= 0.0 else abs(u[j] - ulaw)
                if d > worst:
                    worst, jw = d, j
            pmax[j] = max(pmax[j], p[j])
        if uscale > 0.0 and worst > 1e-8 * uscale:
            msgs.append("increment %d: closure of pair %d off its law by %.3e of the largest closure"
                        % (s.number, jw + 1, worst / uscale))
    if checked == 0:
        msgs.append("no closed pair was checked against the law")
    return msgs


def check_uniform(sc, r):
    """The uniform scenes: every pair at the pressure lambda p0 (and, ideal, within the
    penetration tolerance) at every increment end."""
    msgs = []
    lam = [float(s.load_factor[0]) for s in r.steps]
    area = r.contact.area
    ptol = 1e-8 * sc.p0
    if sc.law == "IDEAL":
        # ideal contact converges on the penetration, to AUGMENTED TOL (1e-6) x the contact element
        # length h; pressures differ from the exact ones by the stress of a penetration varying by
        # that much over an element, at most E/(1 - nu^2) x TOL (docs/contact.md)
        ptol = max(ptol, sc.EA / (1.0 - sc.nuA ** 2) * 1e-6)
        h = sc.width / max(sc.nx_a, sc.nx_b)
    npairs = 0
    for k, s in enumerate(r.steps):
        p = s.contact("pressure")
        keep = [j for j in range(len(p)) if area[j] > 0.0]
        npairs += len(keep)
        dp = max([abs(p[j] - max(lam[k], 0.0) * sc.p0) for j in keep] + [0.0])
        if dp > ptol:
            msgs.append("increment %d (lambda %.6g): pressure off lambda p0 by %.3e of p0 (tolerance %.3e)"
                        % (s.number, lam[k], dp / sc.p0, ptol / sc.p0))
        if sc.law == "IDEAL" and float(s.attrs.get("penetration", 0.0)) > 1e-6 * h * (1.0 + 1e-9):
            msgs.append("increment %d: penetration %.3e > 1e-6 of the contact element length %.3g"
                        % (s.number, float(s.attrs["penetration"]), h))
    if npairs == 0:
        msgs.append("no pair with an area was checked")
    return msgs


def check_result(sc, h5):
    """Messages for every increment end off the law or the closed form (empty: on them)."""
    from k2d.results import Result
    r = Result(h5)
    if not r.steps:
        return ["no increment in the result file"]
    msgs = []
    if sc.law == "ROUGH":
        msgs += check_law(sc, r)
    if sc.uniform:
        msgs += check_uniform(sc, r)
    return msgs[:6]


def run_scene(sc, exe, workdir, timeout=300):
    """Write, run and check one scene in `workdir`; a dict of the outcome."""
    os.makedirs(workdir, exist_ok=True)
    deck = os.path.join(workdir, sc.name + ".dat")
    h5 = os.path.join(workdir, sc.name + ".h5")
    log = os.path.join(workdir, sc.name + ".log")
    build_deck(sc, deck)
    t0 = time.time()
    try:
        with open(log, "w") as f:
            rc = subprocess.call([exe, deck, "-o", h5, "-l", os.path.join(workdir, sc.name + ".lis"), "-q"],
                                 stdout=f, stderr=subprocess.STDOUT, timeout=timeout)
    except subprocess.TimeoutExpired:
        rc = "timeout"
    wall = time.time() - t0
    out = {"scene": sc, "exit": rc, "wall": wall, "checks": [], "message": ""}
    if rc != 0:
        with open(log) as f:
            lines = [ln.strip() for ln in f if any(w in ln for w in ("error", "failed:", "doubtful", "warning"))]
        failed = [ln for ln in lines if "failed:" in ln]
        out["message"] = (failed or lines or [""])[0]
    if rc in (0, 4) and os.path.exists(h5):
        try:
            out["checks"] = check_result(sc, h5)
        except (KeyError, OSError, ValueError) as e:
            out["checks"] = ["the result file could not be checked: %s" % e]
    out["passed"] = rc == 0 and not out["checks"]
    return out
