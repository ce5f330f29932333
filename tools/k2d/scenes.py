"""Generated scenes: valid decks a new user could write, run and checked.

A *scene* is two rectangular bodies, A on top of B, touching along y = 0 through one contact
interface, built from a seeded random draw over what the deck format offers:

* bodies: E from 1e3 to 1e9 N/mm2 (log-uniform), nu from 0 to 0.45, the same material in both
  bodies or two different ones; plane stress, plane strain or axisymmetric (the bodies on the
  axis or an annulus off it); T3, Q4, Q8 or Q9 elements; meshes that match node for node
  (MATCHING NODE) or not (MATCHING SEGMENT, A the finer);
* the interface: the rough law (c_n, m from the literature's range in kgf/cm2 and um, c_n2 <= c_n
  with m2 = m: admissible at every pressure), Coulomb, Fredriksson or no friction, the hardening
  branch on or off, or ideal contact (frictionless or Coulomb);
* the history: a pressure p0 on A's top (load case 1) loaded and unloaded to exactly zero,
  reloaded, partly unloaded, or held while A's top is moved tangentially (load case 2) forward,
  back past zero (a reversal) and home again; 5 to 200 increments per stroke.

Every scene's deck is written by k2d.deck and run by the program.  A scene passes when the run
completes (exit code 0) and, where the scene has a closed form, its results are on it at every
increment end:

* the *uniform* scenes (one material in both bodies, matching or not, a pressure load only):
  the exact solution is the uniform uniaxial stress sigma_y = -lambda p0 (plane and
  axisymmetric alike, represented exactly by every element: a patch test), so every pair
  carries the pressure lambda p0 and, for the rough law, the closure the law gives at that
  pressure on its branch: u = c_n p^m while loading, u = u_A - c_n2 (p_A^m2 - p^m2) after the
  reversal point A = (u_A, p_A) (docs/contact.md), u_res = u_A - c_n2 p_A^m2 at zero load.
  Both to 1e-8 of their scale (p0; the closure at p0): the program's Newton iterations end
  at 1e-10 of the out-of-balance force, the pressures of a linear-elastic patch are exact to
  round-off, and 1e-8 is the accuracy the issue asks of every increment end.

    from k2d.scenes import draw, run_scene
    sc = draw(seed=7)                     # a Scene
    out = run_scene(sc, exe, workdir)     # a dict: exit code, checks, messages
"""
import math
import os
import random
import subprocess
import time

from k2d.deck import Deck, f10

KGF = 0.0980665            # N/mm2 per kgf/cm2

ELEMENTS = (3, 4, 8, 9)
HISTORIES = ("unload", "reload", "partial", "tangential")


class Scene:
    """The drawn parameters of one scene (plain attributes; `describe()` says them in a line)."""

    def __init__(self, **kw):
        self.__dict__.update(kw)

    def describe(self):
        law = ("ideal" if self.law == "IDEAL" else
               "rough c_n=%.3g m=%.2f c_n2=%.3g" % (self.cn, self.m, self.cn2))
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
        return self.uniform_material and self.history != "tangential"


def _log_uniform(rng, a, b):
    return math.exp(rng.uniform(math.log(a), math.log(b)))


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
    nuA = rng.uniform(0.0, 0.45)
    if uniform_material:
        EB, nuB = EA, nuA
    else:
        EB = _log_uniform(rng, 1e3, 1e9)
        nuB = rng.uniform(0.0, 0.45)
    # the rough law: the machine-tool literature's range (kgf/cm2, um), admissible at any pressure
    m = rng.uniform(0.3, 0.8)
    cn = _log_uniform(rng, 0.2, 3.0)
    cn2 = cn * rng.uniform(0.3, 1.0)
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
        mu=rng.uniform(0.1, 0.5), beta=rng.uniform(0.3, 1.0), nfred=_log_uniform(rng, 10.0, 1e4),
        hardening=rng.random() < 0.6, history=history, uniform_material=uniform_material,
        EA=EA, nuA=nuA, EB=EB, nuB=nuB, m=m, cn=cn, cn2=cn2, m2=m,
        units=rng.choice(("KGF_UM", "N_UM")),
        p0=_log_uniform(rng, 0.1, 10.0), nstroke=rng.choice((5, 10, 20, 50, 200)),
        tangential_factor=rng.uniform(0.3, 3.0),
        nx_a=nx_a, nx_b=nx_b, ny_a=rng.choice((1, 2, 3)), ny_b=rng.choice((1, 2, 3)),
        width=width, height_a=width * rng.choice((0.25, 0.5, 1.0)),
        height_b=width * rng.choice((0.25, 0.5, 1.0)), x0=x0, matching=matching)


def model_constants(sc):
    """c_n and c_n2 in model units (mm, N/mm2), as the program converts them (docs/contact.md)."""
    if sc.units == "KGF_UM":
        f = 1.0 / KGF
        return 1e-3 * sc.cn * f ** sc.m, 1e-3 * sc.cn2 * f ** sc.m2
    # N_UM: the constants drawn in kgf/cm2 and um, written in N/mm2 and um
    return 1e-3 * sc.cn * (1.0 / KGF) ** sc.m, 1e-3 * sc.cn2 * (1.0 / KGF) ** sc.m2


def deck_constants(sc):
    """c_n and c_n2 as the deck writes them, in the scene's UNITS."""
    if sc.units == "KGF_UM":
        return sc.cn, sc.cn2
    return sc.cn * (1.0 / KGF) ** sc.m, sc.cn2 * (1.0 / KGF) ** sc.m2


def tangential_stroke(sc):
    """The tangential displacement of A's top [mm]: tangential_factor times an estimate of the
    slip onset, mu p0 / k_T of the interface plus the bodies' shear compliance."""
    if sc.law == "IDEAL":
        return sc.tangential_factor * sc.mu * sc.p0 * (sc.height_a + sc.height_b) / min(sc.EA, sc.EB) * 3.0
    cnm, _ = model_constants(sc)
    # k_T = p^S / R with R = 2 c_n m (1 + nu), S = 1 - m (model units), per unit area
    R = 2.0 * cnm * sc.m * (1.0 + 0.5 * (sc.nuA + sc.nuB))
    kt = sc.p0 ** (1.0 - sc.m) / R
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


def expected_closure(sc, history_p):
    """The closure of the rough law along a history of pressures (model units), one per entry:
    the virgin curve while the pressure exceeds every earlier one, else the unloading branch
    through the reversal point (docs/contact.md)."""
    cnm, cn2m = model_constants(sc)
    out = []
    pa = 0.0
    for p in history_p:
        if p >= pa:
            pa = p
            out.append(cnm * p ** sc.m)
        else:
            ua = cnm * pa ** sc.m
            out.append(ua - cn2m * (pa ** sc.m2 - p ** sc.m2))
    return out


def check_uniform(sc, h5):
    """Messages for every increment end off the closed form (empty: on it)."""
    from k2d.results import Result
    r = Result(h5)
    msgs = []
    if not r.steps:
        return ["no increment in the result file"]
    lam = [float(s.load_factor[0]) for s in r.steps]
    ps = [max(l, 0.0) * sc.p0 for l in lam]
    uexp = expected_closure(sc, ps) if sc.law == "ROUGH" else None
    cnm, _ = model_constants(sc)
    uscale = cnm * sc.p0 ** sc.m
    npairs = 0
    area = r.contact.area
    for k, s in enumerate(r.steps):
        p = s.contact("pressure")
        keep = [j for j in range(len(p)) if area[j] > 0.0]
        npairs += len(keep)
        dp = max(abs(p[j] - ps[k]) for j in keep)
        if dp > 1e-8 * sc.p0:
            msgs.append("increment %d (lambda %.6g): pressure off lambda p0 by %.3e of p0"
                        % (s.number, lam[k], dp / sc.p0))
        if uexp is not None:
            u = s.contact("closure")
            du = max(abs(u[j] - uexp[k]) for j in keep)
            if du > 1e-8 * uscale:
                msgs.append("increment %d (lambda %.6g): closure off the law by %.3e of the closure at p0"
                            % (s.number, lam[k], du / uscale))
    if npairs == 0:
        msgs.append("no pair with an area was checked")
    return msgs[:5]


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
            lines = [ln.strip() for ln in f if "error" in ln or "warning" in ln or "doubtful" in ln]
        out["message"] = lines[-1] if lines else ""
    if rc in (0, 4) and sc.uniform and os.path.exists(h5):
        try:
            out["checks"] = check_uniform(sc, h5)
        except (KeyError, OSError, ValueError) as e:
            out["checks"] = ["the result file could not be checked: %s" % e]
    out["passed"] = rc == 0 and not out["checks"]
    return out
