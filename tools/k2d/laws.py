"""The rough interface's laws, once for the Python tools (docs/contact.md, SPEC §2.1, §2.4, D8).

The same functions as the program's `src/contact/contact_laws.f90`, elementwise over numpy arrays
(scalars in, floats out):

* loading (the virgin curve) u = c_n p^m, its tangent dp/du = p^(1-m) / (c_n m);
* unloading from the reversal point A = (u_A, p_A) along u = u_A - c_n2 (p_A^m2 - p^m2), down to
  the residual closure u_res = max(u_A - c_n2 p_A^m2, 0).  Where c_n2 p_A^m2 > u_A (a reversal
  beyond p*, below) the program takes the branch through A and the origin, u = u_A (p/p_A)^m2
  (c_n2 replaced by u_A / p_A^m2: `unloading_constant`);
* the admissible reversal pressures: with m2 > m both u_res >= 0 and unloading at least as stiff
  as loading at A hold up to p* = min[(c_n/c_n2)^(1/(m2-m)), (c_n m/(c_n2 m2))^(1/(m2-m))];
* the tangential law's elastic stiffness k_T = p^S / R, R = 2 c_n m (1 + nu) by default (eq. 2.8),
  and its integration over an increment at a fixed normal force (Masing's rule, linear kinematic
  hardening: `masing_return`, the program's `bilinear_return`, docs/contact.md);
* the units (docs/contact.md "Units"): constants given in um and kgf/cm2 (UNITS KGF_UM) or um and
  N/mm2 (N_UM) become model constants (mm, N/mm2) as c_model = 1e-3 c f^e, f = 1/0.0980665
  kgf/cm2 per N/mm2 for KGF_UM (1 for N_UM), e the constant's pressure exponent (m for c_n, m2 for
  c_n2, 1 - S for R); UNITS MODEL takes them as given.
"""
import math

import numpy as np

__all__ = ["KGF_CM2", "KGF_PER_NMM2", "UNITS", "length_scale", "pressure_scale", "model_constant",
           "virgin_closure", "virgin_pressure", "virgin_tangent", "admissible_reversals", "reversal_limit",
           "unloading_constant", "residual_closure", "unloading_closure", "unloading_pressure",
           "unloading_tangent", "r_literature", "tangential_stiffness", "masing_return", "normal_law_pressure"]

KGF_CM2 = 0.0980665                 # N/mm2 per kgf/cm2 (SPEC §1)
KGF_PER_NMM2 = 1.0 / KGF_CM2        # kgf/cm2 per N/mm2, the program's KGF_PER_NMM2
UNITS = ("KGF_UM", "N_UM", "MODEL")


def _out(x):
    """A float for a scalar result, the array otherwise."""
    return float(x) if np.ndim(x) == 0 else x


def _units(units):
    u = str(units).upper()
    if u not in UNITS:
        raise ValueError("unknown UNITS %r: expected one of %s" % (units, ", ".join(UNITS)))
    return u


def length_scale(units):
    """Model length per unit of the constants' closure: 1e-3 (um -> mm) unless UNITS MODEL."""
    return 1.0 if _units(units) == "MODEL" else 1.0e-3


def pressure_scale(units):
    """The constants' pressure unit per model pressure unit (N/mm2): 1/0.0980665 for KGF_UM, else 1."""
    return KGF_PER_NMM2 if _units(units) == "KGF_UM" else 1.0


def model_constant(value, exponent, units):
    """A constant of the deck in model units: 1e-3 value f^exponent (see the module's text); the
    exponent is m for c_n, m2 for c_n2, 1 - S for R."""
    return length_scale(units) * value * pressure_scale(units) ** exponent


# ---- the normal law
def virgin_closure(p, cn, m):
    """u = c_n p^m (eq. 2.1a), zero pressure below zero."""
    return _out(cn * np.maximum(p, 0.0) ** m)


def virgin_pressure(u, cn, m):
    """The inverse of the virgin curve, p = (u/c_n)^(1/m), zero for u <= 0."""
    u = np.asarray(u, dtype=float)
    return _out(np.where(u > 0.0, (np.maximum(u, 0.0) / cn) ** (1.0 / m), 0.0))


def virgin_tangent(p, cn, m):
    """dp/du of the virgin curve at pressure p: p^(1-m) / (c_n m) (corrected eq. 3.27)."""
    return _out(np.maximum(p, 0.0) ** (1.0 - m) / (cn * m))


def _power_root(x, e):
    """x^(1/e) for x > 0, e > 0, inf where it would overflow."""
    lr = math.log(x) / e
    return math.inf if lr >= math.log(np.finfo(float).max) else math.exp(lr)


def admissible_reversals(cn, m, cn2, m2):
    """(p_lo, p_hi): the reversal pressures p_A at which the unloading branch leaves u_res >= 0 and
    is at least as stiff as loading at A (SPEC §2.1), in the pressure unit of the constants (the
    unit conversion moves both sides alike).  m2 > m: (0, p*); m2 < m: (p_lo, inf); m2 = m:
    (0, inf) if c_n2 <= c_n, else (inf, 0) (no reversal is admissible)."""
    q_res, q_stiff = cn2 / cn, (cn2 * m2) / (cn * m)
    if m2 > m:
        return 0.0, _power_root(1.0 / max(q_res, q_stiff), m2 - m)
    if m2 < m:
        return _power_root(max(q_res, q_stiff), m - m2), math.inf
    return (0.0, math.inf) if q_res <= 1.0 else (math.inf, 0.0)


def reversal_limit(cn, m, cn2, m2):
    """p*: the largest admissible reversal pressure (inf: no bound; see admissible_reversals)."""
    return admissible_reversals(cn, m, cn2, m2)[1]


def unloading_constant(ua, pa, cn2, m2):
    """The constant of the unloading branch from A = (u_A, p_A): c_n2, or u_A / p_A^m2 where
    c_n2 p_A^m2 > u_A (the residual closure would be negative: the branch through A and the origin)."""
    ua, pa = np.asarray(ua, dtype=float), np.asarray(pa, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        beyond = (pa > 0.0) & (ua > 0.0) & (cn2 * np.maximum(pa, 0.0) ** m2 > ua)
        c = np.where(beyond, ua / np.where(beyond, pa, 1.0) ** m2, cn2)
    return _out(c + 0.0 * ua + 0.0 * pa)


def residual_closure(ua, pa, cn2, m2):
    """u_res = max(u_A - c_n2 p_A^m2, 0) (SPEC D8, the clamp of docs/contact.md)."""
    return _out(np.maximum(ua - cn2 * np.maximum(pa, 0.0) ** m2, 0.0))


def unloading_closure(p, ua, pa, cn2, m2, clamp=True):
    """The closure on the unloading branch through A at pressure p <= p_A:
    u = u_A - c (p_A^m2 - p^m2), c = unloading_constant (the program's law); with clamp=False
    c = c_n2 as given, the bare formula (a curve fitted to measurements, not yet held to p*)."""
    c = unloading_constant(ua, pa, cn2, m2) if clamp else cn2
    return _out(ua - c * (np.maximum(pa, 0.0) ** m2 - np.maximum(p, 0.0) ** m2))


def unloading_pressure(u, ua, pa, cn2, m2):
    """The pressure on the unloading branch through A at closure u, zero below u_res."""
    c = np.asarray(unloading_constant(ua, pa, cn2, m2))
    u, ua, pa = (np.asarray(x, dtype=float) for x in (u, ua, pa))
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.maximum(pa, 0.0) ** m2 - (ua - u) / c
        p = np.where(q > 0.0, np.maximum(q, 0.0) ** (1.0 / m2), 0.0)
    return _out(p)


def unloading_tangent(p, c, m2):
    """dp/du on an unloading branch of constant c (unloading_constant of its A) at pressure p."""
    return _out(np.maximum(p, 0.0) ** (1.0 - m2) / (c * m2))


# ---- the tangential law
def r_literature(cn, m, nu):
    """R = 2 c_n m (1 + nu) (eq. 2.8), in the units of the given c_n."""
    return 2.0 * cn * m * (1.0 + nu)


def tangential_stiffness(p, s, r):
    """The elastic tangential stiffness per unit area k_T = p^S / R (eq. 2.7)."""
    return _out(np.maximum(p, 0.0) ** s / r)


def masing_return(f0, du, ke, kappa, limit, x0, hardening=True):
    """The tangential force after the displacement increment du from the force f0 with the back
    force x0 (Masing's rule, docs/contact.md "The tangential law after a reversal"; the program's
    `bilinear_return` in contact_laws.f90): elastic band |F - X| <= r_y = 0.625 limit (limit =
    mu F_n; r_y = limit without the hardening branch), slope ke inside it, kappa ke at its edge
    (the band dragged along), gross slip at |F| = limit.  Returns (force, back force, state:
    0 stick, 1 hardening branch, 2 slip)."""
    ry = 0.625 * limit if hardening else limit
    xcap = max(limit - ry, 0.0)
    x = min(max(x0, -xcap), xcap)
    trial = f0 + ke * du
    if abs(trial - x) <= ry:
        return trial, x, 0
    s = 1.0 if trial - x >= 0.0 else -1.0
    if hardening:
        f = x + s * ry + kappa * (trial - x - s * ry)
        if abs(f) <= limit:
            return f, f - s * ry, 1
    return s * limit, s * xcap, 2


def normal_law_pressure(u, cn, m, cn2, m2, reversal=None):
    """The normal law's pressure at closure u: the virgin curve, or with a reversal point
    A = (u_A, p_A) the unloading branch through A up to u_A (zero below u_res) and the virgin
    curve beyond it (reloading retraces the branch up to A, then follows the virgin curve)."""
    u = np.asarray(u, dtype=float)
    if reversal is None:
        return virgin_pressure(u, cn, m)
    ua, pa = reversal
    return _out(np.where(u <= ua, unloading_pressure(u, ua, pa, cn2, m2), virgin_pressure(u, cn, m)))
