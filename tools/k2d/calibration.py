"""Calibrate the rough interface's laws from measured curves (docs/calibration.md).

From pressure-closure curves (loading and unloading), tangential traction-displacement
curves at several normal pressures and friction-against-slip curves to the constants of
Kontakt2D's CONTACT cards, in the meaning the program gives them (docs/contact.md,
SPEC §2):

* normal   u = c_n p^m on the virgin curve (eq. 2.1a); unloading from the reversal point
           A = (u_A, p_A) along u = u_A - c_n2 (p_A^m2 - p^m2), reloading back along it to
           A and then on the virgin curve (SPEC D8);
* tangent  k_T^e = p_n^S / R (eq. 2.7), the hardening branch of slope kappa k_T^e between
           0.625 mu p_n and mu p_n (eqs. 2.3-2.6), gross slip at mu p_n;
* friction mu(v_e) = mu_m [1 - (1 - beta) exp(-n v_e)] (eq. 2.9 corrected, SPEC D1).

Units: a CSV column's header names its unit in brackets; the values are converted once, when
the file is read, to the unit system of the cards asked for (UNITS KGF_UM: um and kgf/cm2,
N_UM: um and N/mm2, MODEL: the model's length and pressure units, mm and N/mm2 unless told).
The fits run in those units, so the constants and their confidence intervals need no
conversion afterwards; residuals are reported back in the data's units.

Fitting uses scipy.optimize.least_squares (bounds, a reparametrisation that keeps the
unloading branch admissible); confidence intervals are 95 % intervals from the covariance
s^2 (J^T J)^-1 of the weighted residuals at the optimum, J the Jacobian with respect to the
constants themselves (central differences), with Student's t quantile.

Bad input raises DataError, whose text names the file, the line and the column.
"""
import csv
import math

import numpy as np

from k2d import laws
from k2d.laws import KGF_CM2, tangential_stiffness, unloading_closure, virgin_closure

__all__ = ["LENGTH_UNITS", "PRESSURE_UNITS", "RATIO_UNITS", "KIND_UNITS", "CARD_UNITS", "BRANCH_WORDS",
           "BRANCH_NAMES", "CONFIDENCE", "UNDETERMINED", "DataError", "Units", "unit_value", "parse_model_units",
           "Column", "Table", "read_table", "Constant", "least_squares", "jacobian", "confidence", "weights", "Fit",
           "field", "card", "card_values", "virgin", "normal_history", "normal_closure", "unloading_bound",
           "admissible_reversals", "read_normal", "fit_normal", "bilinear_return", "tangent_curve", "read_tangent",
           "fit_tangent", "fredriksson", "read_friction", "fit_friction"]

# unit name (lower case) -> value in mm, N/mm2
LENGTH_UNITS = {"um": 1.0e-3, "µm": 1.0e-3, "μm": 1.0e-3, "micron": 1.0e-3, "mm": 1.0}
PRESSURE_UNITS = {"kgf/cm2": KGF_CM2, "kgf/cm^2": KGF_CM2, "kgf/cm²": KGF_CM2, "at": KGF_CM2,
                  "n/mm2": 1.0, "n/mm^2": 1.0, "n/mm²": 1.0, "mpa": 1.0}
RATIO_UNITS = {"-": 1.0, "1": 1.0, "": 1.0}
KIND_UNITS = {"length": (LENGTH_UNITS, "um or mm"),
              "pressure": (PRESSURE_UNITS, "kgf/cm2, N/mm2 or MPa"),
              "ratio": (RATIO_UNITS, "- (dimensionless)")}
CARD_UNITS = ("KGF_UM", "N_UM", "MODEL")
BRANCH_WORDS = {"l": "L", "load": "L", "loading": "L", "u": "U", "unload": "U", "unloading": "U",
                "r": "R", "reload": "R", "reloading": "R"}
BRANCH_NAMES = {"L": "loading", "U": "unloading", "R": "reloading"}
CONFIDENCE = 0.95
UNDETERMINED = 0.10            # a 95 % half-width above 10 % of the value: "not determined"


class DataError(Exception):
    """A measured-data file that cannot be used: the text names file, line and column."""

    def __init__(self, path, line, text, column=None):
        where = "%s:%d:" % (path, line) if line else "%s:" % path
        col = " column %d \"%s\":" % (column.index, column.header) if column is not None else ""
        super().__init__("%s error:%s %s" % (where, col, text))


# ---------------------------------------------------------------------------- units
class Units:
    """The unit system of the cards: length and pressure in mm and N/mm2, by name.

    KGF_UM and N_UM constants belong to a model in mm and N/mm2 (the program converts them);
    MODEL constants are in the model's own units, `model` = (length, pressure) names."""

    def __init__(self, card="KGF_UM", model=("mm", "N/mm2")):
        card = card.upper()
        if card not in CARD_UNITS:
            raise ValueError("units %r: expected one of %s" % (card, ", ".join(CARD_UNITS)))
        self.card = card
        if card == "KGF_UM":
            self.length_name, self.pressure_name = "um", "kgf/cm2"
            self.model = ("mm", "N/mm2")
        elif card == "N_UM":
            self.length_name, self.pressure_name = "um", "N/mm2"
            self.model = ("mm", "N/mm2")
        else:
            self.length_name, self.pressure_name = model
            self.model = tuple(model)
        self.length = unit_value("length", self.length_name)       # in mm
        self.pressure = unit_value("pressure", self.pressure_name)  # in N/mm2
        self.model_length = unit_value("length", self.model[0])
        self.model_pressure = unit_value("pressure", self.model[1])

    def describe(self):
        return "UNITS %s (lengths in %s, pressures in %s; model in %s and %s)" % (
            self.card, self.length_name, self.pressure_name, self.model[0], self.model[1])


def unit_value(kind, name):
    table, expected = KIND_UNITS[kind]
    key = name.strip().lower()
    if key not in table:
        raise ValueError("unknown %s unit %r: expected %s" % (kind, name, expected))
    return table[key]


def parse_model_units(text):
    """'mm,N/mm2' -> ('mm', 'N/mm2'), each checked."""
    parts = [s.strip() for s in text.split(",")]
    if len(parts) != 2:
        raise ValueError("model units %r: expected LENGTH,PRESSURE such as mm,N/mm2" % text)
    unit_value("length", parts[0])
    unit_value("pressure", parts[1])
    return tuple(parts)


# ---------------------------------------------------------------------------- CSV
class Column:
    def __init__(self, index, header, name, unit):
        self.index = index            # 1-based field number
        self.header = header
        self.name = name
        self.unit = unit              # as written, None without brackets
        self.kind = None
        self.scale = 1.0              # value of one data unit in mm or N/mm2


class Table:
    """A CSV file of measured data: named columns with units, rows with their line numbers."""

    def __init__(self, path):
        self.path = str(path)
        self.columns = {}             # canonical name -> Column
        self.found = []               # every header cell, for messages
        self.lines = None             # line number of each row
        self.values = {}              # canonical name -> numpy array in the column's unit
        self.text = {}                # canonical name -> list of str (text columns)
        self.header_line = 0

    def __len__(self):
        return 0 if self.lines is None else len(self.lines)

    def has(self, name):
        return name in self.columns

    def column(self, name):
        return self.columns[name]

    def get(self, name, unit_scale=1.0):
        """Values of a numeric column in the unit whose value (mm, N/mm2) is unit_scale."""
        return self.values[name] * (self.columns[name].scale / unit_scale)

    def error(self, row, text, name=None):
        """A DataError at data row `row` (0-based; None: the header), column `name`."""
        line = self.header_line if row is None else int(self.lines[row])
        return DataError(self.path, line, text, self.columns.get(name) if name else None)


def _split_header(cell):
    """'p [kgf/cm2]' -> ('p', 'kgf/cm2'); 'branch' -> ('branch', None); None if malformed."""
    s = cell.strip()
    if "[" in s:
        i = s.index("[")
        if not s.endswith("]") or s.count("[") != 1 or s.count("]") != 1:
            return None
        return s[:i].strip(), s[i + 1:-1].strip()
    return s, None


def read_table(path, spec):
    """Read a CSV file.  `spec`: list of (name, kind, aliases, required) with kind one of
    'length', 'pressure', 'ratio', 'text'.  Lines starting with '#' and blank lines are
    skipped; the first other line is the header.  Raises DataError."""
    t = Table(path)
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:      # a spreadsheet's BOM is no column
            raw = f.read().splitlines()
    except OSError as e:
        raise DataError(path, 0, "cannot read the file: %s" % e.strerror)
    except UnicodeDecodeError:
        raise DataError(path, 0, "not a text file (UTF-8 expected)")
    rows = [(k + 1, line) for k, line in enumerate(raw) if line.strip() and not line.lstrip().startswith("#")]
    if not rows:
        raise DataError(path, 0, "no header line: expected column names with units, e.g. \"p [kgf/cm2], u [um]\"")
    t.header_line, header = rows[0]
    cells = next(csv.reader([header], skipinitialspace=True))
    alias = {}
    for name, kind, aliases, required in spec:
        for a in (name,) + tuple(aliases):
            alias[a.lower()] = (name, kind)
    for k, cell in enumerate(cells, 1):
        split = _split_header(cell)
        t.found.append(cell.strip())
        if split is None:
            raise DataError(path, t.header_line, "column %d \"%s\": expected a name with its unit in brackets, "
                            "e.g. \"p [kgf/cm2]\"" % (k, cell.strip()))
        name, unit = split
        if name.lower() not in alias:
            continue                               # a column the fit does not use
        canon, kind = alias[name.lower()]
        col = Column(k, cell.strip(), canon, unit)
        col.kind = kind
        if canon in t.columns:
            raise DataError(path, t.header_line, "column %d \"%s\" repeats column %d \"%s\""
                            % (k, cell.strip(), t.columns[canon].index, t.columns[canon].header))
        if kind != "text":
            table, expected = KIND_UNITS[kind]
            if unit is None and kind != "ratio":
                raise DataError(path, t.header_line, "column %d \"%s\": expected its unit in brackets, e.g. "
                                "\"%s [%s]\" (%s)" % (k, cell.strip(), name, expected.split(",")[0].split(" ")[0],
                                                      expected))
            key = (unit or "").lower()
            if key not in table:
                raise DataError(path, t.header_line, "column %d \"%s\": unknown %s unit \"%s\"; expected %s"
                                % (k, cell.strip(), kind, unit, expected))
            col.scale = table[key]
        t.columns[canon] = col
    for name, kind, aliases, required in spec:
        if required and name not in t.columns:
            example = {"length": "um", "pressure": "kgf/cm2", "ratio": "-", "text": None}[kind]
            want = "\"%s [%s]\"" % (name, example) if example else "\"%s\"" % name
            raise DataError(path, t.header_line, "missing column %s (%s); the header has: %s"
                            % (want, _describe(name), ", ".join(t.found) or "nothing"))
    ncell = len(cells)
    lines, data = [], {n: [] for n in t.columns}
    for line, text in rows[1:]:
        fields = next(csv.reader([text], skipinitialspace=True))
        if len(fields) != ncell:
            raise DataError(path, line, "expected %d fields as the header has, found %d" % (ncell, len(fields)))
        for name, col in t.columns.items():
            s = fields[col.index - 1].strip()
            if col.kind == "text":
                data[name].append(s)
                continue
            try:
                v = float(s)
            except ValueError:
                v = None
            if v is None or s.lower().lstrip("+-") in ("nan", "inf", "infinity") or not math.isfinite(v):
                what = "an empty field" if not s else "\"%s\"" % s
                raise DataError(path, line, "expected a finite number, found %s" % what, col)
            data[name].append(v)
        lines.append(line)
    t.lines = np.array(lines, dtype=int)
    for name, col in t.columns.items():
        if col.kind == "text":
            t.text[name] = data[name]
        else:
            t.values[name] = np.array(data[name], dtype=float)
    return t


def _describe(name):
    return {"p": "the normal pressure", "u": "the closure", "pn": "the normal pressure",
            "ut": "the tangential displacement", "pt": "the tangential traction", "slip": "the effective slip",
            "mu": "the friction coefficient", "branch": "the branch", "curve": "the curve"}.get(name, name)


# ---------------------------------------------------------------------------- statistics
class Constant:
    """A fitted constant with its 95 % confidence half-width (None: not from the fit)."""

    def __init__(self, name, value, half=None, fixed=False, note=""):
        self.name = name
        self.value = float(value)
        self.half = half
        self.fixed = fixed
        self.note = note

    @property
    def relative(self):
        if self.half is None or self.value == 0.0:
            return None
        return self.half / abs(self.value)

    def determined(self):
        return self.fixed or (self.half is not None and math.isfinite(self.half) and
                              (self.relative is not None and self.relative <= UNDETERMINED))

    def __repr__(self):
        return "%s = %.6g ± %s" % (self.name, self.value, "?" if self.half is None else "%.2g" % self.half)


def least_squares(*args, **kw):
    """scipy.optimize.least_squares, imported when a fit runs (a bad file is reported fast)."""
    from scipy import optimize
    return optimize.least_squares(*args, **kw)


def jacobian(fun, x, rel=1.0e-6):
    """Central-difference Jacobian of the vector function fun at x."""
    x = np.asarray(x, dtype=float)
    f0 = np.asarray(fun(x))
    J = np.empty((f0.size, x.size))
    for j in range(x.size):
        h = rel * max(abs(x[j]), 1.0e-3)
        xp, xm = x.copy(), x.copy()
        xp[j] += h
        xm[j] -= h
        J[:, j] = (np.asarray(fun(xp)) - np.asarray(fun(xm))) / (2.0 * h)
    return J


def confidence(fun, x, names):
    """95 % half-widths of the constants x of the weighted residual function fun:
    s^2 (J^T J)^-1 with s^2 = |r|^2 / (n - p).  Infinite where J^T J is singular."""
    r = np.asarray(fun(x))
    n, p = r.size, len(x)
    dof = n - p
    if dof <= 0:
        return [math.inf] * p
    J = jacobian(fun, x)
    s2 = float(r @ r) / dof
    JTJ = J.T @ J
    from scipy import stats                        # here: a bad file is reported without it
    q = stats.t.ppf(0.5 + CONFIDENCE / 2.0, dof)
    # scaled inverse: singular (a constant the residuals do not depend on) -> infinite
    d = np.sqrt(np.diag(JTJ))
    if np.any(d == 0.0):
        out = []
        for j in range(p):
            out.append(math.inf if d[j] == 0.0 else None)
        keep = [j for j in range(p) if d[j] > 0.0]
        if keep:
            sub = JTJ[np.ix_(keep, keep)] / np.outer(d[keep], d[keep])
            cov = np.linalg.pinv(sub) / np.outer(d[keep], d[keep]) * s2
            for i, j in enumerate(keep):
                out[j] = q * math.sqrt(max(cov[i, i], 0.0))
        return out
    scaled = JTJ / np.outer(d, d)
    if np.linalg.cond(scaled) > 1.0e12:
        cov = np.linalg.pinv(scaled) / np.outer(d, d) * s2
        half = [q * math.sqrt(max(cov[j, j], 0.0)) for j in range(p)]
        return [h if h > 0 else math.inf for h in half]
    cov = np.linalg.inv(scaled) / np.outer(d, d) * s2
    return [q * math.sqrt(max(cov[j, j], 0.0)) for j in range(p)]


def weights(y, mode):
    """Standard deviation model of the measured response: 'relative' (proportional to the
    value, floored at 1 % of the largest) or 'absolute' (uniform)."""
    y = np.abs(np.asarray(y, dtype=float))
    top = float(np.max(y)) if y.size else 1.0
    if top == 0.0:
        top = 1.0
    if mode == "absolute":
        return np.full(y.shape, top)
    return np.maximum(y, 0.01 * top)


class Fit:
    """The outcome of one fit: constants, cards, residuals, warnings."""

    def __init__(self, kind, path, units):
        self.kind = kind
        self.path = path
        self.units = units
        self.constants = []
        self.warnings = []
        self.notes = []
        self.cards = []
        self.rms = self.worst = 0.0
        self.worst_line = 0
        self.residual_unit = ""

    def constant(self, name):
        for c in self.constants:
            if c.name == name:
                return c
        raise KeyError(name)

    def value(self, name):
        return self.constant(name).value

    def set_residuals(self, resid, lines, unit_name):
        resid = np.asarray(resid, dtype=float)
        self.residuals = resid
        self.residual_unit = unit_name
        self.rms = float(np.sqrt(np.mean(resid ** 2))) if resid.size else 0.0
        k = int(np.argmax(np.abs(resid))) if resid.size else 0
        self.worst = float(resid[k]) if resid.size else 0.0
        self.worst_line = int(lines[k]) if resid.size else 0

    def check_determined(self):
        for c in self.constants:
            if c.fixed or c.determined():
                continue
            if c.half is None or not math.isfinite(c.half):
                how = "the data does not constrain it"
            else:
                how = "95 %% interval ±%.3g is %.0f %% of the value" % (c.half, 100.0 * c.relative)
            self.warnings.append("%s = %.6g is not determined by the data (%s)%s"
                                 % (c.name, c.value, how, (": " + c.note) if c.note else ""))

    def report(self):
        u = self.units
        L = ["%s law from %s" % (self.kind, self.path)]
        L += ["  " + n for n in self.notes]
        L.append("constants in %s, 95 %% confidence intervals:" % u.describe())
        for c in self.constants:
            if c.fixed:
                L.append("  %-6s = %-12.7g (fixed%s)" % (c.name, c.value, ": " + c.note if c.note else ""))
            elif c.half is None or not math.isfinite(c.half):
                L.append("  %-6s = %-12.7g ± undetermined" % (c.name, c.value))
            else:
                L.append("  %-6s = %-12.7g ± %-10.3g (%.2g %%)"
                         % (c.name, c.value, c.half, 100.0 * (c.relative or 0.0)))
        unit = (" " + self.residual_unit) if self.residual_unit else ""
        L.append("residual (fit - data): RMS %.4g%s, worst %.4g%s (line %d)"
                 % (self.rms, unit, self.worst, unit, self.worst_line))
        for w in self.warnings:
            L.append("warning: " + w)
        L.append("cards (CONTACT block):")
        L += self.cards
        return "\n".join(L)


def _compact(s):
    """'1.5e-03' -> '1.5e-3', '2e+05' -> '2e5'."""
    if "e" not in s:
        return s
    a, b = s.split("e")
    return a + "e" + str(int(b))


def field(x):
    """A real for a ten-column F10 field, right-justified: the shortest form that is exact,
    else the most precise of at most 9 characters if within 5e-7 (seven significant digits,
    with a blank before the number), else the most precise of 10."""
    x = float(x)
    if x == 0.0:
        return "%10s" % "0.0"
    cands = [_compact("%.*g" % (k, x)) for k in range(1, 17)] + ["%.*f" % (k, x) for k in range(0, 10)]
    cands = [s if any(ch in s for ch in ".e") else s + "." for s in cands]
    exact = [s for s in cands if len(s) <= 9 and float(s) == x]
    if exact:
        return "%10s" % min(exact, key=len)

    def err(s):
        return abs(float(s) - x) / abs(x)
    nine = min((s for s in cands if len(s) <= 9), key=err, default=None)
    if nine is not None and err(nine) <= 5e-7:
        return "%10s" % nine
    return "%10s" % min((s for s in cands if len(s) <= 10), key=err)


def card(keyword, *fields):
    """A CONTACT card: keyword in columns 1-10, then ten-column fields (words left-aligned)."""
    s = "%-10s" % keyword
    for v in fields:
        if v is None:
            s += " " * 10
        elif isinstance(v, str):
            s += "%-10s" % v
        else:
            s += field(v)
    return s.rstrip()


def card_values(line):
    """The numbers of a card written by card(), as the deck reader sees them (F10 fields)."""
    out = []
    for a in range(10, len(line), 10):
        s = line[a:a + 10].strip()
        try:
            out.append(float(s))
        except ValueError:
            out.append(s)
    return out


# ---------------------------------------------------------------------------- normal law
virgin = virgin_closure        # u = c_n p^m (k2d.laws)


def normal_history(p):
    """Branch of every point of a pressure history under the law's rules (docs/contact.md):
    'L' virgin loading, 'U' unloading, 'R' reloading; and the index of the reversal point
    of each point on the unloading branch (-1 on the virgin curve).  A reversal is the last
    point before the pressure falls from the virgin curve; reloading rejoins the virgin
    curve at the reversal pressure.  A hold (equal pressure) keeps the branch."""
    n = len(p)
    code = np.empty(n, dtype="<U1")
    rev = np.full(n, -1, dtype=int)
    on_unl, a, prev, last = False, -1, 0.0, "L"
    for k in range(n):
        if p[k] < prev and not on_unl:
            on_unl, a = True, k - 1
        if on_unl and p[k] >= p[a]:
            on_unl = False
        if not on_unl:
            code[k] = "L"
        elif p[k] < prev:
            code[k] = "U"
        elif p[k] > prev:
            code[k] = "R"
        else:
            code[k] = last
        rev[k] = a if on_unl else -1
        last, prev = code[k], p[k]
    return code, rev


def normal_closure(p, rev, c, m, c2, m2):
    """Closure of the law over a pressure history whose reversal indices are `rev`."""
    u = virgin(p, c, m)
    on = rev >= 0
    if np.any(on):
        pa = p[rev[on]]
        # the bare branch (clamp=False): the fit holds (c2, m2) admissible by its parametrization,
        # and the unloading-only fit (unloading_free) reports what the data say, admissible or not
        u[on] = unloading_closure(p[on], virgin_closure(pa, c, m), pa, c2, m2, clamp=False)
    return u


def unloading_bound(pa, m, m2):
    """g(m, m2): the largest c_n2 / c_n that the law admits at every reversal pressure pa:
    residual closure >= 0 (c_n2 p_A^m2 <= c_n p_A^m) and unloading at least as stiff as
    loading at A (c_n2 m2 p_A^m2 <= c_n m p_A^m) (SPEC §2.1)."""
    pa = np.asarray(pa, dtype=float)
    return float(np.min(pa ** (m - m2))) * min(1.0, m / m2)


def admissible_reversals(c, m, c2, m2, lo, hi):
    """The reversal pressures in [lo, hi] at which (c2, m2) is admissible after (c, m)."""
    ps = np.geomspace(lo, hi, 400)
    p_lo, p_hi = laws.admissible_reversals(c, m, c2, m2)      # p* of docs/contact.md for m2 > m
    ok = (ps >= p_lo * (1 - 1e-12)) & (ps <= p_hi * (1 + 1e-12))
    return ps, ok


def read_normal(path, units):
    """The normal-law data: pressure and closure (in the card units), rows' lines, branches."""
    t = read_table(path, [("p", "pressure", ("pn", "pressure"), True),
                          ("u", "length", ("un", "closure"), True),
                          ("branch", "text", (), False)])
    if len(t) == 0:
        raise DataError(path, t.header_line, "no data rows after the header")
    p = t.get("p", units.pressure)
    u = t.get("u", units.length)
    for k in range(len(t)):
        if p[k] < 0.0:
            raise t.error(k, "expected a pressure >= 0 (compressive positive), found %s" % _fmt(t.values["p"][k]), "p")
    code, rev = normal_history(p)
    if t.has("branch"):
        _check_branch_column(t, p, code, rev)
    return t, p, u, code, rev


def _fmt(v):
    return "%.6g" % v


def _lines(lines):
    """[3, 4, 5] -> 'lines 3-5'; [7] -> 'line 7'; [3, 5, 9] -> 'lines 3, 5, 9'."""
    lines = [int(x) for x in lines]
    if not lines:
        return "no line"
    if len(lines) == 1:
        return "line %d" % lines[0]
    if lines == list(range(lines[0], lines[-1] + 1)):
        return "lines %d-%d" % (lines[0], lines[-1])
    return "lines " + ", ".join(str(x) for x in lines[:12]) + (", ..." if len(lines) > 12 else "")


def _check_branch_column(t, p, code, rev):
    """A branch column must agree with the pressure history (the law decides the branch)."""
    words = t.text["branch"]
    for k, w in enumerate(words):
        lab = BRANCH_WORDS.get(w.strip().lower())
        if lab is None:
            raise t.error(k, "expected a branch L, U or R (loading, unloading, reloading), found \"%s\"" % w,
                          "branch")
        if lab == code[k]:
            continue
        prev = "%s (line %d)" % (_fmt(t.values["p"][k - 1]), t.lines[k - 1]) if k > 0 else "0 (the start)"
        here = "%s (marked %s in column %d)" % (_fmt(t.values["p"][k]), w.strip(), t.column("branch").index)
        if lab == "L" and code[k] == "U":
            msg = "non-monotonic loading: the pressure falls from %s to %s" % (prev, here)
        elif lab == "L":
            msg = ("the pressure %s lies below the reversal pressure %s (line %d): the law reloads along "
                   "the unloading branch up to it; mark the row R (reloading)"
                   % (here, _fmt(t.values["p"][rev[k]]), t.lines[rev[k]]))
        elif lab == "U":
            msg = "non-monotonic unloading: the pressure rises from %s to %s" % (prev, here)
        elif code[k] == "L":
            msg = ("the pressure %s is not below the last reversal pressure: the row is back on the loading "
                   "curve (L), not reloading" % here)
        else:
            msg = "non-monotonic reloading: the pressure falls from %s to %s" % (prev, here)
        raise t.error(k, msg, "p")


def fit_normal(path, units, loading_only=False, same_exponent=False, noise="relative"):
    """Fit the normal law to the data of `path`.  Returns a Fit with .constants c_n, m
    (and c_n2, m2), .cards, and the data (.p, .u, .code, .rev, .lines, .model)."""
    t, p, u, code, rev = read_normal(path, units)
    fit = Fit("normal", path, units)
    fit.table, fit.p, fit.u, fit.code, fit.rev, fit.lines = t, p, u, code, rev, t.lines
    load = (code == "L") & (p > 0.0)
    unl = code != "L"
    nL, nU, nR = int(np.sum(code == "L")), int(np.sum(code == "U")), int(np.sum(code == "R"))
    reversals = sorted(set(int(a) for a in rev[rev >= 0]))
    fit.notes.append("%d rows: %d loading, %d unloading, %d reloading; %d reversal point(s)%s"
                     % (len(t), nL, nU, nR, len(reversals),
                        (" at p = " + ", ".join(_fmt(t.values["p"][a]) for a in reversals)) if reversals else ""))
    # closure must grow with pressure on the loading curve: flag rows where it does not (noise?)
    bad = [k for k in range(1, len(t)) if code[k] == "L" and code[k - 1] == "L" and p[k] > p[k - 1] and u[k] < u[k - 1]]
    if bad:
        fit.warnings.append("the closure decreases while the pressure rises on the loading curve at line(s) %s"
                            % ", ".join(str(t.lines[k]) for k in bad[:8]) + (" ..." if len(bad) > 8 else ""))
    if int(np.sum(load)) < 3:
        raise t.error(len(t) - 1, "too few points: %d loading point(s) with p > 0 (%s), at least 3 needed to fit "
                      "c_n and m with a confidence interval" % (int(np.sum(load)), _lines(t.lines[load])), "p")
    for k in np.nonzero(load)[0]:
        if not u[k] > 0.0:
            raise t.error(k, "expected a closure > 0 on the loading curve at p > 0, found %s" % _fmt(t.values["u"][k]),
                          "u")
    # 1. the loading curve in log space: log u = log c + m log p
    A = np.column_stack([np.ones(int(np.sum(load))), np.log(p[load])])
    coef = np.linalg.lstsq(A, np.log(u[load]), rcond=None)[0]
    c0, m0 = math.exp(coef[0]), float(coef[1])
    if not m0 > 0.0:
        raise DataError(path, t.header_line, "the loading curve does not rise (fitted m = %.3g): check the "
                        "columns p and u" % m0)
    sig = weights(u, noise)
    if loading_only or not np.any(unl):
        if not loading_only:
            raise t.error(len(t) - 1, "no unloading branch: the pressure never falls (%s), so c_n2 and m2 "
                          "cannot be fitted; add the unloading measurements or use --loading-only (the NORMAL card "
                          "then leaves CN2, M2 to the program's defaults c_n/2, m)" % _lines(t.lines), "p")
        _fit_loading(fit, p, u, load, sig, c0, m0)
    else:
        nunl = int(np.sum(unl))
        need = 2 if same_exponent else 3
        if nunl < need:
            raise t.error(len(t) - 1, "too few points: %d unloading/reloading point(s) (%s), at least %d needed "
                          "to fit %s with a confidence interval"
                          % (nunl, _lines(t.lines[unl]), need, "c_n2" if same_exponent else "c_n2 and m2"), "p")
        _fit_cycles(fit, p, u, rev, sig, c0, m0, same_exponent)
    fit.check_determined()
    _normal_cards(fit)
    return fit


def _fit_loading(fit, p, u, load, sig, c0, m0):
    def res(x):
        return (virgin(p[load], x[0], x[1]) - u[load]) / sig[load]

    def res_log(y):
        return res([math.exp(y[0]), y[1]])

    sol = least_squares(res_log, [math.log(c0), m0], bounds=([-np.inf, 1e-6], [np.inf, 20.0]),
                        x_scale="jac", xtol=1e-14, ftol=1e-14, gtol=1e-14)
    x = np.array([math.exp(sol.x[0]), sol.x[1]])
    half = confidence(res, x, ["c_n", "m"])
    fit.constants = [Constant("c_n", x[0], half[0]), Constant("m", x[1], half[1])]
    fit.model = virgin(fit.p, x[0], x[1])
    fit.model[~load & (fit.code != "L")] = np.nan
    resid = fit.model[load] - u[load]
    fit.set_residuals(resid * fit.units.length / fit.table.column("u").scale, fit.lines[load],
                      fit.table.column("u").unit)
    fit.fitted = load
    fit.loading_only = True
    fit.notes.append("loading curve only: %d points from p = %s to %s"
                     % (int(np.sum(load)), _fmt(np.min(p[load])), _fmt(np.max(p[load]))))


def _fit_cycles(fit, p, u, rev, sig, c0, m0, same_exponent):
    pa = p[sorted(set(int(a) for a in rev[rev >= 0]))]
    used = (p > 0.0) | (rev >= 0)          # rows at p = 0 on the virgin curve carry no information

    # m2 = m + y[3] with y[3] >= 0: the program rejects M2 < M (its residual closure is
    # negative at small reversal pressures, docs/contact.md), so the fit never proposes it
    def natural(y):
        c, m = math.exp(y[0]), y[1]
        m2 = m if same_exponent else m + y[3]
        return c, m, y[2] * unloading_bound(pa, m, m2) * c, m2

    def res_nat(x):
        c, m, c2, m2 = x
        return (normal_closure(p, rev, c, m, c2, m2)[used] - u[used]) / sig[used]

    def res_y(y):
        return res_nat(natural(y))

    # start: c2 from a linear fit of the unloading points at m2 = m0 and (c0, m0)
    on = rev >= 0
    d = p[rev[on]] ** m0 - p[on] ** m0
    ua = virgin(p[rev[on]], c0, m0)
    c2 = float(np.sum(d * (ua - u[on])) / max(np.sum(d * d), 1e-300))
    best = None
    for m2s in ([m0] if same_exponent else [m0, 1.2 * m0, 1.4 * m0]):
        t0 = min(max(c2 / (unloading_bound(pa, m0, m2s) * c0), 0.05), 0.98)
        y0 = [math.log(c0), m0, t0] + ([] if same_exponent else [m2s - m0])
        lo = [-np.inf, 1e-6, 1e-9] + ([] if same_exponent else [0.0])
        hi = [np.inf, 20.0, 1.0] + ([] if same_exponent else [20.0])
        sol = least_squares(res_y, y0, bounds=(lo, hi), x_scale="jac", xtol=1e-14, ftol=1e-14, gtol=1e-14)
        if best is None or sol.cost < best.cost:
            best = sol
    c, m, c2, m2 = natural(best.x)
    if same_exponent:
        half = confidence(lambda x: res_nat([x[0], x[1], x[2], x[1]]), [c, m, c2], ["c_n", "m", "c_n2"])
        half.append(half[1])
    else:
        half = confidence(res_nat, [c, m, c2, m2], ["c_n", "m", "c_n2", "m2"])
    fit.constants = [Constant("c_n", c, half[0]), Constant("m", m, half[1]),
                     Constant("c_n2", c2, half[2]),
                     Constant("m2", m2, half[3], fixed=same_exponent, note="m2 = m" if same_exponent else "")]
    if best.x[2] > 1.0 - 1e-6:
        fit.warnings.append("the fit lies on the admissibility bound of the unloading branch (residual closure "
                            "zero or unloading as stiff as loading at a reversal point); the intervals of c_n2, m2 "
                            "are those of the unconstrained local fit")
    free = _free_unloading(p, u, rev, sig, c, m, c2, m2, same_exponent)
    if free is not None and free[0] > unloading_bound(pa, m, free[1]) * c * (1.0 + 1e-6):
        fit.warnings.append("the measured unloading is softer than the law admits: alone, the unloading rows "
                            "fit c_n2 = %.4g, m2 = %.4g, which would make the residual closure negative or the "
                            "unloading softer than loading at a reversal point; the law cannot follow them and "
                            "the fit is the nearest admissible compromise (check the rows, or the reversal points)"
                            % free)
    fit.model = normal_closure(p, rev, c, m, c2, m2)
    fit.model[~used] = np.nan
    resid = fit.model[used] - u[used]
    fit.set_residuals(resid * fit.units.length / fit.table.column("u").scale, fit.lines[used],
                      fit.table.column("u").unit)
    fit.fitted = used
    fit.loading_only = False
    fit.reversal_pressures = pa
    for a in sorted(set(int(a) for a in rev[rev >= 0])):
        ures = virgin_closure(p[a], c, m) - c2 * p[a] ** m2     # the fit's bare u_res (may be < 0)
        fit.notes.append("reversal at p_A = %s %s (line %d): residual closure after unloading %.4g %s"
                         % (_fmt(p[a]), fit.units.pressure_name, fit.lines[a], ures, fit.units.length_name))
    if abs(m2 - m) > 1e-9 * m:
        top = max(float(np.max(p)), float(np.max(pa)))
        ps, ok = admissible_reversals(c, m, c2, m2, top * 1e-3, top * 10.0)
        if not np.all(ok):
            good = ps[ok]
            rng = "none"
            if good.size:
                rng = "%s to %s %s" % (_fmt(good.min()), _fmt(good.max()), fit.units.pressure_name)
            fit.warnings.append("with m2 != m the unloading branch is admissible (residual closure >= 0, unloading "
                                "at least as stiff as loading) only for reversal pressures from %s (checked from "
                                "1e-3 to 10 times the largest pressure); the program does not check this" % rng)


def _free_unloading(p, u, rev, sig, c, m, c2, m2, same_exponent):
    """c_n2, m2 fitted to the unloading rows alone, with (c, m) held and no admissibility
    bound: a diagnostic for data the law cannot follow.  None if the fit fails."""
    on = rev >= 0

    def res(y):
        k2 = math.exp(y[0])
        e2 = m if same_exponent else y[1]
        return (normal_closure(p, rev, c, m, k2, e2)[on] - u[on]) / sig[on]

    y0 = [math.log(c2)] + ([] if same_exponent else [m2])
    lo = [-np.inf] + ([] if same_exponent else [1e-6])
    hi = [np.inf] + ([] if same_exponent else [20.0])
    try:
        sol = least_squares(res, y0, bounds=(lo, hi), x_scale="jac")
    except (ValueError, FloatingPointError):
        return None
    return math.exp(sol.x[0]), (m if same_exponent else float(sol.x[1]))


def _normal_cards(fit):
    u = fit.units
    c, m = fit.value("c_n"), fit.value("m")
    if fit.loading_only:
        line = card("NORMAL", c, m)
    else:
        c2, m2 = fit.value("c_n2"), fit.value("m2")
        line = card("NORMAL", c, m, c2, m2)
        v = card_values(line)
        # the deck reader's rule (SPEC 2.1): with M2 = M, CN2 <= CN; keep it after rounding
        if abs(v[3] - v[1]) <= 1e-12 * v[1] and v[2] > v[0]:
            line = line[:30] + line[10:20] + line[40:]
    fit.cards = ["UNITS     %s" % u.card, line]
    fit.normal_card = line


# ---------------------------------------------------------------------------- tangential law
def bilinear_return(f0, du, ke, kappa, limit, fy, hardening):
    """The program's integration of the bilinear law over one increment at fixed normal
    force (src/contact/contact_laws.f90, bilinear_return): returns (force, state) with
    state 0 stick, 1 hardening branch, 2 slip."""
    trial = f0 + ke * du
    fb = min(max(0.625 * limit, fy), limit)
    if not hardening:
        fb = limit
    if abs(trial) <= fb:
        return trial, 0
    s = 1.0 if trial >= 0.0 else -1.0
    if hardening and fb < limit:
        if f0 * s >= fb:
            f = f0 + kappa * ke * du
        else:
            du_el = (fb * s - f0) / ke
            f = fb * s + kappa * ke * (du - du_el)
        if abs(f) <= limit:
            return f, 1
    return limit * s, 2


def tangent_curve(ut, pn, R, S, mu, kappa, hardening):
    """Traction p_T of the tangential law along a displacement history ut at normal
    pressure pn, from the unloaded state (u_T = 0, p_T = 0); and the states."""
    ke = tangential_stiffness(pn, S, R)
    limit = mu * pn if mu is not None else math.inf
    f, fy, prev = 0.0, 0.0, 0.0
    out = np.empty(len(ut))
    st = np.zeros(len(ut), dtype=int)
    for k, u in enumerate(ut):
        f, s = bilinear_return(f, u - prev, ke, kappa, limit, fy, hardening)
        if s != 0:
            fy = max(fy, abs(f))
        out[k], st[k], prev = f, s, u
    return out, st


def read_tangent(path, units):
    t = read_table(path, [("pn", "pressure", ("p",), True), ("ut", "length", ("u_t",), True),
                          ("pt", "pressure", ("p_t", "tau"), True), ("curve", "text", (), False)])
    if len(t) == 0:
        raise DataError(path, t.header_line, "no data rows after the header")
    pn = t.get("pn", units.pressure)
    ut = t.get("ut", units.length)
    pt = t.get("pt", units.pressure)
    for k in range(len(t)):
        if not pn[k] > 0.0:
            raise t.error(k, "expected a normal pressure > 0 (a tangential curve is measured under a normal "
                          "load), found %s" % _fmt(t.values["pn"][k]), "pn")
    # curves: a curve column, or runs of equal normal pressure
    ident = t.text["curve"] if t.has("curve") else list(t.values["pn"])
    curves, start = [], 0
    for k in range(1, len(t) + 1):
        if k == len(t) or ident[k] != ident[k - 1]:
            curves.append(np.arange(start, k))
            start = k
    seen = set()
    for idx in curves:
        key = ident[idx[0]]
        if t.has("curve") and key in seen:
            raise t.error(idx[0], "curve \"%s\" appears again after other curves: give each curve's rows together"
                          % key, "curve")
        seen.add(key)
        if t.has("curve"):
            spread = np.ptp(pn[idx]) / np.mean(pn[idx])
            if spread > 0.01:
                k = idx[int(np.argmax(np.abs(pn[idx] - np.mean(pn[idx]))))]
                raise t.error(k, "the normal pressure of curve \"%s\" varies by %.1f %%: a tangential curve is "
                              "measured at one normal pressure" % (key, 100 * spread), "pn")
        if len(idx) < 3:
            raise t.error(idx[-1], "too few points: the curve at p_n = %s has %d point(s) (%s), at least 3 "
                          "needed" % (_fmt(t.values["pn"][idx[0]]), len(idx), _lines(t.lines[idx])), "ut")
    return t, pn, ut, pt, curves


class _TangentProblem:
    """The tangential curves of a data set and the law's traction along them, for a choice
    of the constants that are fitted: R and S (unless S is given) always, mu unless the
    mode is 'elastic', kappa in mode 'hardening' (modes: elastic, slip, hardening)."""

    def __init__(self, t, ut, pt, curves, levels, sig, s_fixed):
        self.t, self.ut, self.pt, self.curves, self.levels = t, ut, pt, curves, levels
        self.sig, self.s_fixed = sig, s_fixed

    def model(self, R, S, mu, kappa, hard):
        out = np.empty(len(self.t))
        st = np.zeros(len(self.t), dtype=int)
        for idx, lv in zip(self.curves, self.levels):
            out[idx], st[idx] = tangent_curve(self.ut[idx], lv, R, S, mu, kappa, hard)
        return out, st

    def names(self, mode):
        return ["R"] + ([] if self.s_fixed is not None else ["S"]) + ([] if mode == "elastic" else ["mu"]) + \
            (["kappa"] if mode == "hardening" else [])

    def constants(self, x, mode):
        """(R, S, mu, kappa) from the fitted constants x (in the order of names())."""
        x = list(x)
        R = x.pop(0)
        S = self.s_fixed if self.s_fixed is not None else x.pop(0)
        mu = x.pop(0) if mode != "elastic" else None
        kappa = x.pop(0) if mode == "hardening" else 1.0
        return R, S, mu, kappa

    def residuals(self, x, mode):
        R, S, mu, kappa = self.constants(x, mode)
        return (self.model(R, S, mu, kappa, mode == "hardening")[0] - self.pt) / self.sig

    def initial(self):
        """R0, S0 from the initial slopes (through-origin fit of each curve's points below
        half its peak), mu0 from the largest traction ratio."""
        t, k0 = self.t, []
        for idx, lv in zip(self.curves, self.levels):
            a, b = self.ut[idx], self.pt[idx]
            top = int(np.argmax(np.abs(b)))
            sel = [j for j in range(top + 1) if abs(b[j]) <= 0.5 * abs(b[top]) and a[j] != 0.0]
            if not sel:
                sel = [j for j in range(top + 1) if a[j] != 0.0][:1]
            if not sel:
                raise t.error(idx[0], "the curve at p_n = %s never moves (u_T = 0 throughout)" % _fmt(lv), "ut")
            sel = np.array(sel)
            k0.append(float(np.sum(a[sel] * b[sel]) / np.sum(a[sel] ** 2)))
            if not k0[-1] > 0.0:
                raise t.error(idx[0], "the curve at p_n = %s does not rise: the traction must follow the "
                              "displacement" % _fmt(lv), "pt")
        logp, logk = np.log(self.levels), np.log(k0)
        S0 = float(np.polyfit(logp, logk, 1)[0]) if self.s_fixed is None else self.s_fixed
        R0 = float(np.exp(np.mean(S0 * logp - logk)))
        mu0 = max(float(np.max(np.abs(self.pt[idx]))) / lv for idx, lv in zip(self.curves, self.levels))
        return R0, S0, mu0

    def fit(self, mode, starts):
        """Least squares in (log R, S, log mu, kappa) from each start (R, S, mu, kappa);
        returns the best (R, S, mu, kappa)."""
        hard, free_s = mode == "hardening", self.s_fixed is None
        lo = [-np.inf] + ([0.0] if free_s else []) + ([] if mode == "elastic" else [-np.inf]) + ([1e-4] if hard else [])
        hi = [np.inf] + ([5.0] if free_s else []) + ([] if mode == "elastic" else [np.inf]) + ([1.0] if hard else [])

        def natural(y):
            y = list(y)
            x = [math.exp(y.pop(0))] + ([y.pop(0)] if free_s else [])
            if mode != "elastic":
                x.append(math.exp(y.pop(0)))
            if hard:
                x.append(y.pop(0))
            return x

        best = None
        for R, S, mu, kappa in starts:
            y0 = [math.log(R)] + ([S] if free_s else []) + ([] if mode == "elastic" else [math.log(mu)]) + \
                ([kappa] if hard else [])
            y0 = np.clip(y0, np.array(lo) + 1e-9, np.array(hi) - 1e-9)
            sol = least_squares(lambda y: self.residuals(natural(y), mode), y0, bounds=(lo, hi), x_scale="jac",
                                xtol=1e-14, ftol=1e-14, gtol=1e-14, diff_step=1e-7)
            if best is None or sol.cost < best.cost:
                best = sol
        return self.constants(natural(best.x), mode)


def fit_tangent(path, units, hardening="auto", s_fixed=None, noise="relative"):
    """Fit R, S (and mu, kappa where the data shows the kink and the slip) to tangential
    traction-displacement curves at several normal pressures.  hardening: 'auto' (the
    branch if the data shows a kink), 'on', 'off'."""
    t, pn, ut, pt, curves = read_tangent(path, units)
    fit = Fit("tangential", path, units)
    fit.table, fit.pn, fit.ut, fit.pt, fit.curves, fit.lines = t, pn, ut, pt, curves, t.lines
    fit.levels = levels = [float(np.mean(pn[idx])) for idx in curves]
    fit.notes.append("%d curve(s) at p_n = %s %s, %d points" % (
        len(curves), ", ".join(_fmt(v) for v in levels), units.pressure_name, len(t)))
    if s_fixed is None and len(set(round(math.log(v), 6) for v in levels)) < 2:
        s_fixed = 0.5
        fit.warnings.append("S is not determined by one normal pressure level: fixed at S = 0.5 (give --S, e.g. "
                            "1 - m from the normal fit, or measure at two or more pressures)")
    sig = np.empty(len(t))
    for idx in curves:
        sig[idx] = weights(pt[idx], noise)
    prob = _TangentProblem(t, ut, pt, curves, levels, sig, s_fixed)
    R0, S0, mu0 = prob.initial()

    # the mode: hardening unless told otherwise, then what the states of the points show
    if hardening == "off":
        mode = "slip"
        R, S, mu, kappa = prob.fit(mode, [(R0, S0, mu0, 1.0), (R0, S0, 1.2 * mu0, 1.0)])
    else:
        mode = "hardening"
        R, S, mu, kappa = prob.fit(mode, [(R0, S0, mu0, 0.045), (R0, S0, 1.05 * mu0, 0.2),
                                          (R0, S0, mu0 / 0.8, 0.045), (R0, S0, mu0, 0.6)])
    st = prob.model(R, S, mu, kappa, mode == "hardening")[1]
    nbranch, nslip = int(np.sum(st == 1)), int(np.sum(st == 2))
    if nbranch + nslip == 0:
        mode = "elastic"
        R, S, mu, kappa = prob.fit(mode, [(R0, S0, None, 1.0)])
        fit.warnings.append("the data stays elastic (no kink, no slip): mu and kappa are not determined; only "
                            "TANGENT is written (FRICTION and HARDENING from other data)")
    elif mode == "hardening" and hardening == "auto" and (nbranch < 2 or kappa > 0.999):
        mode = "slip"
        R, S, mu, kappa = prob.fit(mode, [(R0, S0, mu0, 1.0), (R, S, mu, 1.0)])
        fit.warnings.append("no kink in the data (%d point(s) on a hardening branch): kappa is not determined; the "
                            "data fits the law without the branch, HARDENING OFF" % nbranch)
    elif mode == "hardening" and nbranch < 2:
        fit.warnings.append("only %d point(s) on the hardening branch: kappa is not determined" % nbranch)
    hard = mode == "hardening"
    fit.mode, fit.R, fit.S, fit.mu, fit.kappa, fit.hardening = mode, R, S, mu, kappa, hard
    fit.model, fit.states = prob.model(R, S, mu, kappa, hard)
    nst = [int(np.sum(fit.states == s)) for s in (0, 1, 2)]

    # intervals with respect to the constants themselves
    names = prob.names(mode)
    x = [v for v, n in zip((R, S, mu, kappa), ("R", "S", "mu", "kappa")) if n in names]
    half = dict(zip(names, confidence(lambda x_: prob.residuals(x_, mode), x, names)))
    fit.constants = [Constant("R", R, half["R"]),
                     Constant("S", S, half.get("S"), fixed=s_fixed is not None,
                              note="given" if s_fixed is not None else "")]
    if mode != "elastic":
        fit.constants.append(Constant("mu", mu, half["mu"], note="from the %s" % (
            "kink and the slip limit" if nst[1] and nst[2] else "slip limit" if nst[2] else "kink")))
    if hard:
        fit.constants.append(Constant("kappa", kappa, half["kappa"]))
    fit.notes.append("points: %d elastic, %d on the hardening branch, %d slipping" % tuple(nst))
    if mode != "elastic" and nst[2] == 0:
        fit.notes.append("no point reaches gross slip: mu comes from the kink at 0.625 mu p_n alone")
    fit.check_determined()
    fit.set_residuals((fit.model - pt) * units.pressure / t.column("pt").scale, t.lines, t.column("pt").unit)
    fit.cards = ["UNITS     %s" % units.card, card("TANGENT", R, S)]
    if mode != "elastic":
        fit.cards.append(card("FRICTION", "COULOMB", mu))
        fit.cards.append(card("HARDENING", "ON", kappa) if hard else card("HARDENING", "OFF"))
    return fit


# ---------------------------------------------------------------------------- friction law
def fredriksson(v, mu_m, beta, n):
    return mu_m * (1.0 - (1.0 - beta) * np.exp(-n * np.asarray(v, dtype=float)))


def read_friction(path, units):
    t = read_table(path, [("slip", "length", ("ve", "v_e", "v"), True), ("mu", "ratio", ("μ",), False),
                          ("pt", "pressure", ("p_t", "tau"), False), ("pn", "pressure", ("p",), False)])
    if len(t) == 0:
        raise DataError(path, t.header_line, "no data rows after the header")
    if not t.has("mu") and not (t.has("pt") and t.has("pn")):
        raise DataError(path, t.header_line, "missing column \"mu [-]\" (the friction coefficient), or the pair "
                        "\"pt [kgf/cm2]\" and \"pn [kgf/cm2]\" (tangential and normal pressure); the header has: %s"
                        % ", ".join(t.found))
    v = t.get("slip", units.model_length)          # n is in 1/model length
    if t.has("mu"):
        mu = t.get("mu")
    else:
        pn = t.get("pn")
        for k in range(len(t)):
            if not pn[k] > 0.0:
                raise t.error(k, "expected a normal pressure > 0, found %s" % _fmt(t.values["pn"][k]), "pn")
        mu = np.abs(t.get("pt")) / pn
    for k in range(len(t)):
        if v[k] < 0.0:
            raise t.error(k, "expected an effective slip >= 0, found %s" % _fmt(t.values["slip"][k]), "slip")
        if k and v[k] < v[k - 1]:
            raise t.error(k, "the effective slip decreases from %s (line %d) to %s: it is the path length of the "
                          "slip and never decreases" % (_fmt(t.values["slip"][k - 1]), t.lines[k - 1],
                                                        _fmt(t.values["slip"][k])), "slip")
        if not mu[k] >= 0.0:
            raise t.error(k, "expected a friction coefficient >= 0, found %s" % _fmt(mu[k]),
                          "mu" if t.has("mu") else "pt")
    if len(t) < 4:
        raise t.error(len(t) - 1, "too few points: %d (%s), at least 4 needed to fit mu_m, beta and n with a "
                      "confidence interval" % (len(t), _lines(t.lines)), "slip")
    return t, v, mu


def fit_friction(path, units, noise="relative"):
    """Fit Fredriksson's mu_m, beta, n to friction-against-effective-slip data."""
    t, v, mu = read_friction(path, units)
    fit = Fit("friction", path, units)
    fit.table, fit.v, fit.mu, fit.lines = t, v, mu, t.lines
    sig = weights(mu, noise)
    fit.notes.append("%d points, effective slip from %s to %s %s (n in 1/%s)"
                     % (len(t), _fmt(t.values["slip"][0]), _fmt(t.values["slip"][-1]), t.column("slip").unit,
                        units.model[0]))

    def res(x):
        return (fredriksson(v, *x) - mu) / sig

    mu_m0 = float(np.max(mu))
    beta0 = min(max(float(mu[0]) / mu_m0, 0.05), 0.95)
    target = mu[0] + 0.632 * (mu_m0 - mu[0])
    j = int(np.argmax(mu >= target))
    vspan = float(v[-1] - v[0]) or 1.0
    n0 = 1.0 / max(float(v[j]), 0.05 * vspan)
    best = None
    for scale in (1.0, 0.3, 3.0):
        sol = least_squares(res, [mu_m0, beta0, n0 * scale], bounds=([1e-9, 1e-6, 0.0], [np.inf, 1.0, np.inf]),
                            x_scale="jac", xtol=1e-14, ftol=1e-14, gtol=1e-14)
        if best is None or sol.cost < best.cost:
            best = sol
    mu_m, beta, n = (float(x) for x in best.x)
    half = confidence(res, [mu_m, beta, n], ["mu_m", "beta", "n"])
    fit.constants = [Constant("mu_m", mu_m, half[0]), Constant("beta", beta, half[1]), Constant("n", n, half[2])]
    fit.model = fredriksson(v, mu_m, beta, n)
    coulomb = beta > 1.0 - 1e-6 or (math.isfinite(half[1]) and beta + half[1] >= 1.0 and half[1] > 0
                                    and (1.0 - beta) < half[1])
    if coulomb:
        fit.warnings.append("no slip hardening in the data (beta = %.4g reaches 1 within its interval): n is not "
                            "determined; the data is Coulomb friction mu = %.4g" % (beta, mu_m))
        fit.constants[2].note = "no hardening to fix it"
        fit.cards = [card("FRICTION", "COULOMB", mu_m)]
    else:
        reach = n * (float(v[-1]) - 0.0)
        if reach < 3.0:
            fit.warnings.append("the data ends at n v_e = %.2g (%.0f %% of the hardening): mu_m is extrapolated"
                                % (reach, 100.0 * (1.0 - math.exp(-reach))))
        if n * float(v[0]) > 1.0:
            fit.warnings.append("the first point lies at n v_e = %.2g: the initial coefficient beta mu_m is "
                                "extrapolated" % (n * float(v[0])))
        fit.cards = [card("FRICTION", "FREDRIKSS", mu_m, beta, n)]
        fit.check_determined()
    fit.set_residuals(fit.model - mu, t.lines, "")
    return fit
