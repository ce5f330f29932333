"""Synthetic measurements for the calibration tools: curves generated from known constants,
written as CSV files in the format k2d.calibration reads (docs/calibration.md).

Each generator evaluates the law in closed form along an explicit history (it does not use
the fitting code's model), optionally with seeded Gaussian noise proportional to the measured
response (`noise` = its relative standard deviation, e.g. 0.005).  Constants are in um and
kgf/cm2 (UNITS KGF_UM) and the slip in mm for n; `lunit`, `punit` choose the units written.
"""
import numpy as np

from k2d.calibration import LENGTH_UNITS, PRESSURE_UNITS
from k2d.laws import KGF_CM2, tangential_stiffness, unloading_closure, virgin_closure

__all__ = ["SPEC_TABLE", "TABLE_PMAX", "normal_cycles", "loading_curve", "tangent_curves", "friction_curve",
           "write_csv", "write_normal", "write_tangent", "write_friction"]

# SPEC §2.4, Ito 2008 Table 6-2 (after Back et al.): cast-iron joints, C in um/(kgf/cm2)^m;
# the ranges of the table are taken at both ends.
SPEC_TABLE = [
    ("hand-scraped/hand-scraped, 20-25 points per in2, 3-5 um", 0.3, 0.5),
    ("hand-scraped/hand-scraped, 20-25 points per in2, 6-8 um", 0.5, 0.5),
    ("hand-scraped, 15-18 points per in2 (low)", 0.8, 0.5),
    ("hand-scraped, 15-18 points per in2 (high)", 1.0, 0.5),
    ("hand-scraped, 10-12 points per in2 (low)", 1.3, 0.5),
    ("hand-scraped, 10-12 points per in2 (high)", 1.5, 0.5),
    ("hand-scraped, 5-12 points per in2 (high)", 2.0, 0.5),
    ("hand-scraped/ground, 1.0 um R_CLA (low)", 0.8, 0.4),
    ("hand-scraped/ground, 1.0 um R_CLA (high)", 1.0, 0.4),
    ("peripheral ground/peripheral ground (low)", 0.6, 0.4),
    ("peripheral ground/peripheral ground (high)", 0.7, 0.5),
]
TABLE_PMAX = 25.0              # kgf/cm2: the table's range of validity (SPEC §2.4)


def _noisy(y, noise, rng):
    y = np.asarray(y, dtype=float)
    if not noise:
        return y
    return y * (1.0 + noise * rng.standard_normal(y.shape))


def _convert(values, kind, unit):
    """Values in um (length) or kgf/cm2 (pressure) expressed in `unit`."""
    if kind == "length":
        return np.asarray(values) * (LENGTH_UNITS["um"] / LENGTH_UNITS[unit.lower()])
    return np.asarray(values) * (KGF_CM2 / PRESSURE_UNITS[unit.lower()])


def normal_cycles(c, m, c2, m2, peaks=(1.0, 3.0, 8.0, 25.0), low=0.0, npts=40, noise=0.0, seed=1):
    """Load to peaks[0], unload to `low`, reload to peaks[1] (along the unloading branch up
    to the previous peak, then on the virgin curve), unload, ...: pressures in kgf/cm2,
    closures in um, `npts` points per segment.  Returns (p, u, branch)."""
    P, U, B = [], [], []

    def add(ps, us, b):
        P.extend(ps)
        U.extend(us)
        B.extend(b)

    ps = np.linspace(0.0, peaks[0], npts + 1)[1:]
    add(ps, virgin_closure(ps, c, m), ["L"] * npts)
    for i, pa in enumerate(peaks):
        ua = virgin_closure(pa, c, m)
        ps = np.linspace(pa, low, npts + 1)[1:]
        # measurements may lie beyond the program's admissible range: the bare formula, no clamp
        add(ps, unloading_closure(ps, ua, pa, c2, m2, clamp=False), ["U"] * npts)
        if i + 1 < len(peaks):
            ps = np.linspace(low, peaks[i + 1], npts + 1)[1:]
            us = np.where(ps <= pa, unloading_closure(ps, ua, pa, c2, m2, clamp=False), virgin_closure(ps, c, m))
            add(ps, us, ["R" if q < pa else "L" for q in ps])
    rng = np.random.default_rng(seed)
    return np.array(P), _noisy(U, noise, rng), B


def loading_curve(c, m, pmax=TABLE_PMAX, step=0.5):
    """The virgin curve sampled at round pressures step, 2 step, ..., pmax (kgf/cm2)."""
    ps = np.arange(1, int(round(pmax / step)) + 1) * step
    return ps, virgin_closure(ps, c, m)


def tangent_curves(R, S, mu, kappa, levels=(5.0, 10.0, 20.0), npts=100, reach=2.0, noise=0.0, seed=2,
                   hardening=True):
    """Monotonic tangential curves at the normal pressures `levels` (kgf/cm2), each from the
    unloaded state: u_T geometric from 0.05 u_1 to `reach` u_2 (u_1 the end of the elastic
    range at 0.625 mu p_n, u_2 the start of gross slip).  Returns (pn, ut, pt) in kgf/cm2
    and um."""
    PN, UT, PT = [], [], []
    for pn in levels:
        ke = tangential_stiffness(pn, S, R)
        lim = mu * pn
        if hardening:
            u1 = 0.625 * lim / ke
            u2 = u1 + 0.375 * lim / (kappa * ke)
        else:
            u1 = u2 = lim / ke
        ut = np.geomspace(0.05 * u1, reach * u2, npts)
        pt = np.where(ut <= u1, ke * ut, np.minimum(0.625 * lim + kappa * ke * (ut - u1), lim))
        if not hardening:
            pt = np.minimum(ke * ut, lim)
        PN.extend([pn] * npts)
        UT.extend(ut)
        PT.extend(pt)
    rng = np.random.default_rng(seed)
    return np.array(PN), np.array(UT), _noisy(PT, noise, rng)


def friction_curve(mu_m, beta, n, reach=5.0, npts=160, noise=0.0, seed=3):
    """mu against the effective slip v (mm) from 0 to reach / n."""
    v = np.linspace(0.0, reach / n, npts)
    mu = mu_m * (1.0 - (1.0 - beta) * np.exp(-n * v))
    rng = np.random.default_rng(seed)
    return v, _noisy(mu, noise, rng)


def write_csv(path, header, columns, comments=(), digits=17):
    """Columns of numbers (or strings) under a header such as ['p [kgf/cm2]', 'u [um]'],
    numbers with `digits` significant digits (17: exactly)."""
    with open(path, "w") as f:
        for c in comments:
            f.write("# %s\n" % c)
        f.write(", ".join(header) + "\n")
        for row in zip(*columns):
            f.write(", ".join(v if isinstance(v, str) else "%.*g" % (digits, v) for v in row) + "\n")


def write_normal(path, p, u, branch=None, punit="kgf/cm2", lunit="um", comments=(), digits=17):
    cols = [_convert(p, "pressure", punit), _convert(u, "length", lunit)]
    header = ["p [%s]" % punit, "u [%s]" % lunit]
    if branch is not None:
        cols.append(list(branch))
        header.append("branch")
    write_csv(path, header, cols, comments, digits)


def write_tangent(path, pn, ut, pt, punit="kgf/cm2", lunit="um", comments=(), digits=17):
    write_csv(path, ["pn [%s]" % punit, "ut [%s]" % lunit, "pt [%s]" % punit],
              [_convert(pn, "pressure", punit), _convert(ut, "length", lunit), _convert(pt, "pressure", punit)],
              comments, digits)


def write_friction(path, v_mm, mu, lunit="um", comments=(), digits=17):
    write_csv(path, ["slip [%s]" % lunit, "mu [-]"], [np.asarray(v_mm) / LENGTH_UNITS[lunit.lower()], mu], comments,
              digits)
