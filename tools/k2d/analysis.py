"""What the example analyses measure on a result: the contact pairs along the surface, values
at a position, relative differences, the contact radius.

    from k2d.results import Result
    from k2d.analysis import Pairs, at, rel, contact_radius
    p = Pairs(Result("punch.h5"))      # the pairs in the order of their x (r) position
    p.x, p.last("pressure")            # positions and a contact quantity of the last increment
    p.of_step(p.steps[3], "closure")   # ... of another increment, in the same order
    at(p.x, p.last("slip"), 25.0)      # the value at the pair at x = 25 (NaN if there is none)
    contact_radius(p.x, p.last("closure"), p.last("normal_state"))
"""
import math

import numpy as np

__all__ = ["Pairs", "at", "rel", "contact_radius", "radius_ideal"]


class Pairs:
    """The contact pairs of a Result in the order of their position along x (r in
    axisymmetry), the view of a contact profile that the example analyses take."""

    def __init__(self, result):
        if result.contact is None:
            raise KeyError("%s holds no contact definition" % result.path)
        self.result = result
        self.position = result.contact.position
        self.order = np.argsort(self.position[:, 0])
        self.x = self.position[self.order, 0]
        self._last = None

    @property
    def steps(self):
        return self.result.steps

    def last(self, key):
        """A contact quantity of the last increment, in the order of the positions."""
        if self._last is None:
            self._last = self.result.last.contact_all()
        return self._last[key][self.order]

    def of_step(self, step, key):
        """A contact quantity of the increment `step` (a Step of the result), in the same order."""
        return step.contact(key)[self.order]


def at(xs, values, x, tol=1e-6):
    """The value at the position x (within tol), NaN if no position is there."""
    k = np.where(np.abs(xs - x) < tol)[0]
    return float(values[k[0]]) if len(k) else float("nan")


def rel(a, b):
    """The difference of a from b in per cent (NaN for b = 0 or a = NaN)."""
    return 100.0 * (a / b - 1.0) if b not in (0.0,) and not math.isnan(a) else float("nan")


def contact_radius(x, closure, state):
    """Rough law: where the closure of the outermost closed pair, interpolated linearly to the
    next pair, falls to zero (docs/validation.md, example 5.2).  x, closure and the normal
    state in the order of x; NaN when no pair is closed or the last pair is (the paired zone
    is then too small)."""
    k = np.where(state > 0)[0]
    if not len(k) or k.max() + 1 >= len(x):
        return float("nan")
    k = k.max()
    u0, u1 = closure[k], closure[k + 1]
    return float(x[k] + (x[k + 1] - x[k]) * u0 / (u0 - u1)) if u0 > u1 else float(x[k])


def radius_ideal(x, closure, state):
    """Ideal law: the closure of a closed pair is zero (to the tolerance), so interpolating it
    says nothing.  Outside a smooth frictionless contact the gap grows like (r - a)^(3/2)
    (the pressure falls like (a - r)^(1/2)); the gaps g1, g2 of the first two open pairs
    r1 < r2 then give a = (r1 - q r2)/(1 - q), q = (g1/g2)^(2/3), kept between the last but
    one closed pair and the first open one (the last closed pair's force stands for its
    whole tributary zone, so the edge may lie before it)."""
    k = np.where(state > 0)[0]
    if not len(k) or k.max() + 2 >= len(x):
        return float("nan")
    k = k.max()
    g1, g2 = -closure[k + 1], -closure[k + 2]
    lo, hi = float(x[max(k - 1, 0)]), float(x[k + 1])
    if not (0.0 < g1 < g2):
        return 0.5 * float(x[k] + x[k + 1])
    q = (g1 / g2) ** (2.0 / 3.0)
    a = (x[k + 1] - q * x[k + 2]) / (1.0 - q)
    return float(min(max(a, lo), hi))
