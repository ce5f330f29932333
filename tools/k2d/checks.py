"""Expected values of a regression deck, kept beside it in `<deck>.check`, compared with its
result file.  The format is documented in docs/DEVELOPERS.md ("Expected values of a good
deck"); tests/decks/check_deck.py is the command line that ctest runs.

    from k2d.checks import parse, check_result
    checks = parse("inputs/lame_cylinder.check")           # CheckFormatError on a malformed file
    for c, ok, message in check_result("lame_cylinder.h5", checks):
        print(("PASS" if ok else "FAIL"), c.where, message)

One line holds one check:

    QUANTITY [SELECTOR ...] OP EXPECTED [tol=A] [rtol=R]   # why this value and this tolerance

e.g. `u_x node=17 = 9.5333e-3 rtol=2e-4  # Lame: u(a) = ...`.  The comment is required.
Results are read through k2d.results only.
"""
import ast
import math
import operator
import re

import numpy as np

from .results import Result

__all__ = ["NODE_FIELDS", "RUN_QUANTITIES", "NODE_SETS", "PAIR_SETS", "REDUCTIONS", "OPERATORS", "CheckFormatError",
           "Check", "parse", "evaluate", "check_result"]

# nodal quantities: (field of an increment, column)
NODE_FIELDS = {"u_x": ("displacement", 0), "u_y": ("displacement", 1),
               "stress_xx": ("stress_nodal", 0), "stress_yy": ("stress_nodal", 1),
               "stress_xy": ("stress_nodal", 2), "stress_zz": ("stress_nodal", 3),
               "reaction_x": ("reaction", 0), "reaction_y": ("reaction", 1)}
RUN_QUANTITIES = ("status", "increments_completed", "steps")
NODE_SETS = ("all",)
PAIR_SETS = ("all", "closed", "open", "slipping", "sticking")
REDUCTIONS = ("sum", "max", "min", "maxabs")
OPERATORS = ("=", "<=", ">=")


class CheckFormatError(Exception):
    """A malformed check file: the message names file and line."""


class Check:
    """One line of a check file."""

    def __init__(self, path, line, text):
        self.path, self.line, self.text = path, line, text.rstrip("\n")
        self.where = "%s:%d" % (path, line)
        body, _, why = text.partition("#")
        self.why = why.strip()
        if not self.why:
            self.fail("every check needs a comment (# ...) saying why the value and the tolerance hold")
        tok = body.split()
        ops = [i for i, t in enumerate(tok) if t in OPERATORS]
        if len(ops) != 1:
            self.fail("expected one operator (=, <= or >=) between the quantity and the expected value, "
                      "found %d" % len(ops))
        k = ops[0]
        if k == 0:
            self.fail("a quantity must come before the operator")
        self.quantity = tok[0]
        self.op = tok[k]
        self.options = {}
        self.flags = []
        for t in tok[1:k]:
            if "=" in t:
                key, _, val = t.partition("=")
                if key not in ("node", "at", "on", "pair", "x", "increment", "case", "interface"):
                    self.fail("unknown selector %r (node=, at=, on=, pair=, x=, increment=, case=, "
                              "interface=)" % key)
                self.options[key] = val
            elif t in NODE_SETS + PAIR_SETS + REDUCTIONS:
                self.flags.append(t)
            else:
                self.fail("unknown selector %r" % t)
        rest = tok[k + 1:]
        self.tol = self.rtol = None
        while rest and re.match(r"^r?tol=", rest[-1]):
            key, _, val = rest.pop().partition("=")
            try:
                v = float(val)
            except ValueError:
                self.fail("%s= expects a number, found %r" % (key, val))
            if not v >= 0.0:
                self.fail("%s= must not be negative" % key)
            setattr(self, key, v)
        if not rest:
            self.fail("no expected value after %r" % self.op)
        self.expected = " ".join(rest)
        self.exact = self.quantity == "status" or bool(re.match(r"^[+-]?\d+$", self.expected))
        if self.quantity == "status":
            if self.op != "=" or self.tol is not None or self.rtol is not None:
                self.fail("status takes '= WORD' only")
        else:
            try:
                _compile(self.expected)
            except ValueError as e:
                self.fail("expected value %r: %s" % (self.expected, e))
        if self.op == "=" and not self.exact and self.tol is None and self.rtol is None:
            self.fail("a real expected value needs a tolerance (tol= absolute, rtol= relative)")

    def fail(self, msg):
        raise CheckFormatError("%s: %s\n  %s" % (self.where, msg, self.text.strip()))

    @property
    def label(self):
        return self.text.partition("#")[0].strip()


def parse(path):
    """The checks of a check file (comment and blank lines skipped); CheckFormatError when a
    line is malformed or the file holds no check."""
    checks = []
    with open(path) as f:
        for n, text in enumerate(f, 1):
            if not text.strip() or text.lstrip().startswith("#"):
                continue
            checks.append(Check(path, n, text))
    if not checks:
        raise CheckFormatError("%s: no check in the file" % path)
    return checks


# ------------------------------------------------------------------ expressions
_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
           ast.Pow: operator.pow}
_FUNCTIONS = {"sqrt": np.sqrt, "exp": np.exp, "log": np.log, "sin": np.sin, "cos": np.cos, "tan": np.tan,
              "atan": np.arctan, "abs": np.abs}
_CONSTANTS = {"pi": math.pi}
_VARIABLES = ("x", "y", "r", "z", "lf", "p")


def _compile(text):
    """Check that `text` is an arithmetic expression of numbers, pi, the variables x, y, r, z,
    lf, p and sqrt, exp, log, sin, cos, tan, atan, abs; returns its syntax tree."""
    try:
        tree = ast.parse(text, mode="eval").body
    except SyntaxError:
        raise ValueError("not an arithmetic expression") from None

    def walk(n):
        if isinstance(n, ast.Constant) and isinstance(n.value, (int, float)):
            return
        if isinstance(n, ast.Name) and (n.id in _CONSTANTS or n.id in _VARIABLES):
            return
        if isinstance(n, ast.BinOp) and type(n.op) in _BINARY:
            walk(n.left)
            walk(n.right)
            return
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, (ast.USub, ast.UAdd)):
            walk(n.operand)
            return
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in _FUNCTIONS \
                and len(n.args) == 1 and not n.keywords:
            walk(n.args[0])
            return
        raise ValueError("only numbers, + - * / **, pi, sqrt, exp, log, sin, cos, tan, atan, abs and "
                         "the variables x, y (r, z), lf and p may appear")
    walk(tree)
    return tree


def evaluate(text, **variables):
    """The value of an expression (see _compile) for the given variables (arrays allowed)."""
    def ev(n):
        if isinstance(n, ast.Constant):
            return float(n.value)
        if isinstance(n, ast.Name):
            if n.id in _CONSTANTS:
                return _CONSTANTS[n.id]
            if n.id not in variables:
                raise ValueError("the variable %s means nothing for this quantity" % n.id)
            return variables[n.id]
        if isinstance(n, ast.BinOp):
            return _BINARY[type(n.op)](ev(n.left), ev(n.right))
        if isinstance(n, ast.UnaryOp):
            return -ev(n.operand) if isinstance(n.op, ast.USub) else ev(n.operand)
        return _FUNCTIONS[n.func.id](ev(n.args[0]))
    return ev(_compile(text))


# ------------------------------------------------------------------ values
def _steps(c, res):
    inc = c.options.get("increment", "last")
    if not res.steps:
        raise LookupError("the result file holds no increment")
    if inc == "last":
        return [res.last]
    if inc == "all":
        return list(res.steps)
    try:
        return [res.step(int(inc))]
    except (ValueError, KeyError):
        raise LookupError("no increment %s in the result file (kept: %s)" % (
            inc, ", ".join(str(s.number) for s in res.steps))) from None


def _reduce(c, values, labels, expected_of):
    """(values, expected values, labels) of a selection, or of its reduction when the check
    names one.  expected_of(each): the expected value of the reduction (each False) or of
    every entity (each True)."""
    red = [f for f in c.flags if f in REDUCTIONS]
    if len(red) > 1:
        raise LookupError("one reduction at most (sum, max, min, maxabs)")
    if not len(values):
        raise LookupError("the selection is empty: nothing to check")
    if red:
        v = {"sum": np.sum, "max": np.max, "min": np.min, "maxabs": lambda a: np.max(np.abs(a))}[red[0]](values)
        return [v], [expected_of(False)], [red[0]]
    return list(values), list(expected_of(True)), labels


def _node_values(c, res, step):
    field, col = NODE_FIELDS[c.quantity]
    data = step.field(field)[:, col]
    xy = res.mesh.coordinates
    lf = float(step.load_factor[0])
    if "node" in c.options:
        n = int(c.options["node"])
        if not 1 <= n <= len(data):
            raise LookupError("node %d does not exist (1..%d)" % (n, len(data)))
        sel = np.array([n - 1])
    elif "at" in c.options:
        try:
            px, py = (float(v) for v in c.options["at"].split(","))
        except ValueError:
            raise LookupError("at= expects X,Y") from None
        size = max(float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1])), 1.0)
        sel = np.where(np.hypot(xy[:, 0] - px, xy[:, 1] - py) <= 1e-9 * size)[0]
        if len(sel) == 0:
            raise LookupError("no node at (%g, %g)" % (px, py))
        sel = sel[:1]
    elif "on" in c.options:
        axis, _, val = c.options["on"].partition(":")
        if axis not in ("x", "y", "r", "z"):
            raise LookupError("on= expects x:X or y:Y (r:R, z:Z), found %r" % c.options["on"])
        try:
            v0 = float(val)
        except ValueError:
            raise LookupError("on= expects x:X or y:Y (r:R, z:Z), found %r" % c.options["on"]) from None
        col = 0 if axis in ("x", "r") else 1
        size = max(float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1])), 1.0)
        sel = np.where(np.abs(xy[:, col] - v0) <= 1e-9 * size)[0]
        if len(sel) == 0:
            raise LookupError("no node on %s = %g" % (axis, v0))
    elif "all" in c.flags or any(f in REDUCTIONS for f in c.flags):
        sel = np.arange(len(data))
    else:
        raise LookupError("say which nodes: node=N, at=X,Y, on=x:X, all, or a reduction (sum, max, min, maxabs)")
    x, y = xy[sel, 0], xy[sel, 1]

    def expected_of(each):
        if not each:
            return evaluate(c.expected, lf=lf)
        return np.broadcast_to(evaluate(c.expected, x=x, y=y, r=x, z=y, lf=lf), x.shape)
    return _reduce(c, data[sel], ["node %d" % (k + 1) for k in sel], expected_of)


def _pair_data(c, res, step):
    name = c.quantity
    if name == "shear_ratio":
        p, t = step.contact("pressure"), step.contact("shear")
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(p > 0.0, np.abs(t) / np.where(p > 0.0, p, 1.0), np.nan)
    if name == "pairs":
        return np.ones(res.contact.npair)
    if name == "position_x":
        return np.asarray(res.contact.position[:, 0], dtype=float)
    if name in res.contact.names:
        return np.asarray(getattr(res.contact, name), dtype=float)
    return step.contact(name)


def _pair_values(c, res, step):
    if res.contact is None:
        raise LookupError("the deck has no contact")
    data = _pair_data(c, res, step)
    if data.ndim != 1:
        raise LookupError("%s is not one value per pair" % c.quantity)
    pos = res.contact.position
    lf = float(step.load_factor[0])
    sets = [f for f in c.flags if f in PAIR_SETS]
    # interface=K: the pairs of the deck's K-th interface only (a model of several interfaces)
    of_iface = np.ones(len(data), dtype=bool)
    if "interface" in c.options:
        k_if = int(c.options["interface"])
        of_iface = np.asarray(res.contact.interface) == k_if
        if not of_iface.any():
            raise LookupError("interface %d has no pairs" % k_if)
        if "pair" in c.options:
            raise LookupError("interface= selects a set of pairs; pair=J names one already")
    if "pair" in c.options:
        j = int(c.options["pair"])
        if not 1 <= j <= len(data):
            raise LookupError("pair %d does not exist (1..%d)" % (j, len(data)))
        sel = np.array([j - 1])
    elif "x" in c.options:
        x0 = float(c.options["x"])
        o = np.argsort(pos[:, 0])
        o = o[of_iface[o]]
        xs = pos[o, 0]
        if not xs[0] - 1e-9 <= x0 <= xs[-1] + 1e-9:
            raise LookupError("x = %g lies outside the pairs (%g .. %g)" % (x0, xs[0], xs[-1]))
        v = float(np.interp(x0, xs, data[o]))
        p = float(np.interp(x0, xs, step.contact("pressure")[o]))
        return [v], [evaluate(c.expected, x=x0, r=x0, lf=lf, p=p)], ["x = %g" % x0]
    else:
        if len(sets) > 1:
            raise LookupError("one pair set at most (all, closed, open, slipping, sticking)")
        which = sets[0] if sets else ("all" if any(f in REDUCTIONS for f in c.flags) else None)
        if which is None:
            raise LookupError("say which pairs: pair=J, x=X, all, closed, open, slipping, sticking, "
                              "or a reduction (sum, max, min, maxabs)")
        if which == "all":
            mask = np.ones(len(data), dtype=bool)
        else:
            ns = step.contact("normal_state")
            ts = step.contact("tangential_state")
            mask = {"closed": ns > 0, "open": ns == 0, "slipping": (ns > 0) & (ts == 2),
                    "sticking": (ns > 0) & (ts == 0)}[which]
        sel = np.where(mask & of_iface)[0]
        if c.quantity == "pairs":
            # a count: how many pairs are in the set
            return [float(len(sel))], [evaluate(c.expected, lf=lf)], ["%s pairs" % which]
        if len(sel) == 0:
            raise LookupError("no %s pair: a check over pairs needs pairs to check" % which)
    x, y = pos[sel, 0], pos[sel, 1]
    p = step.contact("pressure")[sel]

    def expected_of(each):
        if not each:
            return evaluate(c.expected, lf=lf)
        return np.broadcast_to(evaluate(c.expected, x=x, y=y, r=x, z=y, lf=lf, p=p), x.shape)
    return _reduce(c, data[sel], ["pair %d" % (k + 1) for k in sel], expected_of)


def _attr_values(c, res, step):
    if c.quantity not in step.attrs:
        raise LookupError("increment %d has no value %s" % (step.number, c.quantity))
    v = np.atleast_1d(np.asarray(step.attrs[c.quantity], dtype=float))
    k = int(c.options.get("case", "1"))
    if not 1 <= k <= len(v):
        raise LookupError("case %d does not exist (1..%d)" % (k, len(v)))
    return [v[k - 1]], [evaluate(c.expected, lf=float(step.load_factor[0]))], ["increment %d" % step.number]


def _measure(c, res):
    """[(step label, values, expected values, labels)] of a check."""
    q = c.quantity
    if q in RUN_QUANTITIES:
        if c.options or c.flags:
            raise LookupError("%s takes no selector" % q)
        v = {"status": res.status, "increments_completed": res.completed, "steps": len(res.steps)}[q]
        return [("run", [v], [c.expected if q == "status" else evaluate(c.expected)], [q])]
    out = []
    for step in _steps(c, res):
        if q in NODE_FIELDS:
            vals = _node_values(c, res, step)
        elif q in ("shear_ratio", "pairs", "position_x") or (res.contact is not None and
                                               (q in res.contact.names or q in step.contact_all())):
            vals = _pair_values(c, res, step)
        elif q in step.attrs:
            vals = _attr_values(c, res, step)
        elif res.contact is None:
            raise LookupError("unknown quantity %r, or a contact quantity of a deck without contact" % q)
        else:
            raise LookupError("unknown quantity %r (docs/DEVELOPERS.md lists them)" % q)
        out.append(("increment %d" % step.number,) + tuple(vals))
    return out


def _judge(c, v, e, scale):
    """(passes, deviation, allowed deviation) of the value v against the expected e; `scale`
    is what rtol is relative to."""
    if c.quantity == "status":
        good = str(v).strip() == str(e).strip()
        return good, 0.0 if good else 1.0, 0.0
    v, e = float(v), float(e)
    allow = (c.tol or 0.0) + (c.rtol or 0.0) * scale
    dev = abs(v - e) if c.op == "=" else (v - e if c.op == "<=" else e - v)
    if math.isnan(dev):
        return False, math.inf, allow
    return dev <= allow, dev, allow


def check_result(h5, checks):
    """Compare the result file h5 with the checks; yields (check, passes, message).  A check
    over several entities (nodes, pairs, increments) passes when every one does; the message
    names the worst."""
    res = Result(h5)
    for c in checks:
        try:
            measured = _measure(c, res)
        except (LookupError, ValueError) as err:
            yield c, False, "cannot measure: %s" % err
            continue
        ok, worst, count = True, None, 0
        for inc, values, expected, labels in measured:
            # rtol is relative to the expected value, or for a field over several entities to
            # the largest expected magnitude of the selection (its scale)
            scale = max(abs(float(e)) for e in expected) if c.quantity != "status" else 0.0
            for v, e, lab in zip(values, expected, labels):
                if c.quantity != "status" and len(expected) == 1:
                    scale = abs(float(e))
                good, dev, allow = _judge(c, v, e, scale)
                count += 1
                if worst is None or (worst[0] and not good) or (good == worst[0] and dev > worst[1]):
                    worst = (good, dev, v, e, allow, lab if len(measured) == 1 or lab == inc else "%s, %s" % (lab, inc))
                ok = ok and good
        good, dev, v, e, allow, where = worst
        if c.quantity == "status":
            msg = "status %r" % v
        else:
            msg = "%s%s: %.10g %s %.10g (deviation %.3g, allowed %.3g%s)" % (
                "worst of %d at " % count if count > 1 else "", where, float(v),
                {"=": "vs", "<=": "<=", ">=": ">="}[c.op], float(e), max(dev, 0.0), allow,
                "" if c.op == "=" else " beyond the bound")
        yield c, ok, msg
