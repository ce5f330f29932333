"""The normal law from measured surfaces: the rough contact solved by FFT boundary elements
(docs/calibration.md, "From a measured surface").

One or two height maps (any format SurfaceTopography reads: .x3p, .sur, .opd, .plu, .datx,
.nc, ...) are levelled (their mean plane removed) and, for two, added into the composite
roughness h = h1 + h2 (the two surfaces face each other).  ContactMechanics presses a rigid
flat on an elastic half-space of contact modulus E* (1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2)
carrying that roughness, the sample being one period of a periodic surface, by constrained
conjugate gradients (Polonsky & Keer 1999), with a penetration hardness H capping the
pressure where it is given (plastic asperities, their flattening kept for the unloading).

The closure is the approach of the flat from first touch: u = ubar_0 - ubar(p), ubar the mean
separation between the flat and the surface's original mean plane, ubar_0 = max h - mean h.
The curve -- loading from PMIN to PMAX and, with a hardness, unloading back to exactly zero
-- is written as a CSV in the format of the `normal` mode and fitted by
k2d.calibration.fit_normal: one home for the fit, its confidence intervals, the cards and the
units.

What is checked: the grid (at least MIN_GRID points a side), the contact at PMIN (at least
MIN_CONTACT_POINTS grid points in MIN_SPOTS separate spots: otherwise the closure rests on a
few pixels or a few asperities and the sample is refused, DataError, exit 2), the power law
over the range (the widest sub-range where it holds to POWER_LAW_TOL is reported; beyond it
the report says so, and the calibration is doubtful), and the BEM's own convergence (the
constants again on the half-resolution grid and on the four quarters of the sample).
"""
import math
import os

import numpy as np

from k2d import calibration as cal

__all__ = ["MIN_GRID", "MIN_CONTACT_POINTS", "MIN_SPOTS", "POWER_LAW_TOL", "HEIGHT_UNITS", "Surface",
           "read_surface", "composite", "contact_modulus", "level", "BEMCurve", "solve", "check_resolution",
           "write_curve", "power_law_range", "log_law", "TopographyFit", "calibrate", "convergence"]

MIN_GRID = 32                # grid points a side
MIN_CONTACT_POINTS = 100     # grid points in contact at PMIN: the contact area to ~10 %
MIN_SPOTS = 10               # separate contact spots at PMIN: more than a handful of asperities
POWER_LAW_TOL = 0.03         # the power law "holds" where it follows the BEM closure to 3 %
# height units SurfaceTopography reports -> mm
HEIGHT_UNITS = {"m": 1.0e3, "mm": 1.0, "um": 1.0e-3, "µm": 1.0e-3, "μm": 1.0e-3, "nm": 1.0e-6, "pm": 1.0e-9,
                "A": 1.0e-7, "Å": 1.0e-7}


class Surface:
    """A levelled height map in mm on a uniform grid: heights (nx, ny) or (n,), sizes in mm."""

    def __init__(self, heights, sizes, name, periodic=True):
        self.heights = np.asarray(heights, dtype=float)
        self.sizes = tuple(float(s) for s in sizes)
        self.name = name
        self.periodic = periodic

    @property
    def shape(self):
        return self.heights.shape

    @property
    def spacing(self):
        return tuple(s / n for s, n in zip(self.sizes, self.shape))

    def rms_height(self):
        return float(np.sqrt(np.mean((self.heights - self.heights.mean()) ** 2)))

    def rms_gradient(self):
        """sqrt(<|grad h|^2>) from the Fourier series of the periodic sample (the h'_rms of
        Persson's and Bush-Gibson-Thomas' contact-area laws)."""
        h = self.heights - self.heights.mean()
        hq = np.fft.fftn(h) / h.size
        qs = np.meshgrid(*[2.0 * np.pi * np.fft.fftfreq(n, d=s / n) for n, s in zip(self.shape, self.sizes)],
                         indexing="ij")
        q2 = sum(q ** 2 for q in qs)
        return float(np.sqrt(np.sum(q2 * np.abs(hq) ** 2)))

    def topography(self):
        from SurfaceTopography import Topography, UniformLineScan
        if self.heights.ndim == 1:
            return UniformLineScan(self.heights, self.sizes[0], periodic=True, unit="mm")
        return Topography(self.heights, self.sizes, periodic=True, unit="mm")

    def coarsened(self):
        """Every second grid point: the same sample at half the resolution."""
        sl = tuple(slice(0, None, 2) for _ in self.shape)
        return Surface(self.heights[sl], self.sizes, self.name + " (half resolution)")

    def quarters(self):
        """The four quarters of the sample (each levelled anew)."""
        nx, ny = self.shape
        out = []
        for i in range(2):
            for j in range(2):
                h = self.heights[i * nx // 2:(i + 1) * nx // 2, j * ny // 2:(j + 1) * ny // 2]
                out.append(Surface(level(h), (self.sizes[0] / 2, self.sizes[1] / 2),
                                   "%s (quarter %d)" % (self.name, 2 * i + j + 1)))
        return out


def level(h):
    """Remove the mean plane (least squares) of a height map."""
    h = np.asarray(h, dtype=float)
    if h.ndim == 1:
        x = np.arange(h.size, dtype=float)
        A = np.column_stack([np.ones(h.size), x])
    else:
        ix, iy = np.meshgrid(np.arange(h.shape[0], dtype=float), np.arange(h.shape[1], dtype=float), indexing="ij")
        A = np.column_stack([np.ones(h.size), ix.ravel(), iy.ravel()])
    coef = np.linalg.lstsq(A, h.ravel(), rcond=None)[0]
    return h - (A @ coef).reshape(h.shape)


def _unreadable(path, e):
    if type(e).__name__ == "CannotDetectFileFormat":
        why = "the file is damaged, or not in a format SurfaceTopography reads"
    else:
        why = "%s (%s)" % (str(e).strip().splitlines()[0] if str(e).strip() else "no message", type(e).__name__)
    raise cal.DataError(path, 0, "cannot read the surface: %s; expected a height map such as .x3p, .sur, "
                        ".opd, .plu, .datx, .nc, or a matrix of heights as text with --size and --length-unit"
                        % why)


def _metadata(reader, path, size, length_unit):
    """The keywords that give a file its physical size and length unit where it carries none
    (a plain-text or .npy height matrix): from --size and --length-unit; a file that carries
    them keeps its own, and giving them again is refused (DataError) rather than ignored."""
    ch = reader.default_channel
    has_size = ch.physical_sizes is not None
    has_unit = ch.unit is not None
    kw = {}
    if size is not None:
        if has_size:
            raise cal.DataError(path, 0, "the file gives its physical size (%s %s); expected no --size"
                                % (" x ".join("%g" % float(s) for s in ch.physical_sizes), ch.unit or ""))
        if len(size) not in (1, 2) or not all(math.isfinite(s) and s > 0.0 for s in size):
            raise cal.DataError(path, 0, "--size %s: expected one or two positive lengths (LX [LY])"
                                % " ".join("%g" % s for s in size))
        n = tuple(ch.nb_grid_pts)
        if len(n) == 1 or len(size) == 2:
            kw["physical_sizes"] = tuple(size[:len(n)])
        else:                                  # LY from LX, the pixel square
            kw["physical_sizes"] = (size[0], size[0] * n[1] / n[0])
    elif not has_size:
        raise cal.DataError(path, 0, "the file does not give the sample's physical size (a height matrix of "
                            "%s grid points); expected --size LX [LY] (in --length-unit)"
                            % " x ".join(str(n) for n in ch.nb_grid_pts))
    if length_unit is not None:
        if has_unit:
            raise cal.DataError(path, 0, "the file gives its length unit (%s); expected no --length-unit" % ch.unit)
        if length_unit not in HEIGHT_UNITS:
            raise cal.DataError(path, 0, "--length-unit %s: expected one of %s"
                                % (length_unit, ", ".join(sorted(HEIGHT_UNITS))))
        kw["unit"] = length_unit
    elif not has_unit:
        raise cal.DataError(path, 0, "the file does not give the unit of its heights and size; expected "
                            "--length-unit (one of %s)" % ", ".join(sorted(HEIGHT_UNITS)))
    return kw


def read_surface(path, size=None, length_unit=None):
    """Read a measured height map with SurfaceTopography; DataError (exit 2) where it cannot be
    used: unreadable or unknown format, no physical size or unit (and none given by size, in
    length_unit), missing points, a line scan, too few grid points, no roughness."""
    try:
        from SurfaceTopography import open_topography
    except ImportError as e:                                           # pragma: no cover
        raise RuntimeError("SurfaceTopography is not installed: run tools/setup_topography.sh (%s)" % e)
    if not os.path.isfile(path):
        raise cal.DataError(path, 0, "cannot read the file: No such file or directory")
    try:
        reader = open_topography(path)
        ch = reader.default_channel
    except Exception as e:                                             # the readers raise many kinds
        _unreadable(path, e)
    kw = _metadata(reader, path, size, length_unit)
    try:
        t = reader.topography(**kw)
    except Exception as e:                                             # the readers raise many kinds
        _unreadable(path, e)
    if t.dim != 2:
        raise cal.DataError(path, 0, "channel \"%s\" is a line scan (%d-dimensional); expected an areal height map"
                            % (ch.name, t.dim))
    unit = t.unit
    if unit not in HEIGHT_UNITS:
        raise cal.DataError(path, 0, "channel \"%s\": unknown or missing length unit %r; expected one of %s"
                            % (ch.name, unit, ", ".join(sorted(HEIGHT_UNITS))))
    if t.has_undefined_data:
        raise cal.DataError(path, 0, "channel \"%s\": the height map has undefined (missing) points; fill or crop "
                            "them before the contact can be solved" % ch.name)
    h = np.asarray(t.heights(), dtype=float)
    if not np.all(np.isfinite(h)):
        raise cal.DataError(path, 0, "channel \"%s\": expected finite heights, found %d NaN or infinite value(s)"
                            % (ch.name, int(np.sum(~np.isfinite(h)))))
    if min(h.shape) < MIN_GRID:
        raise cal.DataError(path, 0, "channel \"%s\": sample too small: %d x %d grid points, at least %d x %d needed"
                            % (ch.name, h.shape[0], h.shape[1], MIN_GRID, MIN_GRID))
    sizes = [float(s) * HEIGHT_UNITS[unit] for s in t.physical_sizes]
    if not all(math.isfinite(s) and s > 0.0 for s in sizes):
        raise cal.DataError(path, 0, "channel \"%s\": expected a positive physical size, found %s"
                            % (ch.name, t.physical_sizes))
    h = level(h * HEIGHT_UNITS[unit])
    if not np.ptp(h) > 0.0:
        raise cal.DataError(path, 0, "channel \"%s\": the surface is flat after levelling (no roughness)" % ch.name)
    return Surface(h, sizes, os.path.basename(path), periodic=bool(t.is_periodic))


def composite(s1, s2):
    """The composite roughness of two facing surfaces on one grid: h = h1 + h2."""
    if s1.shape != s2.shape or any(abs(a - b) > 1e-6 * max(a, b) for a, b in zip(s1.sizes, s2.sizes)):
        raise cal.DataError(s2.name, 0, "the second surface has %s grid points over %s mm, the first %s over %s mm; "
                            "expected the same grid (resample one of them)"
                            % ("x".join(map(str, s2.shape)), "x".join("%.6g" % s for s in s2.sizes),
                               "x".join(map(str, s1.shape)), "x".join("%.6g" % s for s in s1.sizes)))
    return Surface(s1.heights + s2.heights, s1.sizes, "%s + %s" % (s1.name, s2.name))


def contact_modulus(E1, nu1, E2=None, nu2=None):
    """E* from 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2; the second body of the first's
    material where E2 is not given."""
    if E2 is None:
        E2, nu2 = E1, nu1 if nu2 is None else nu2
    if nu2 is None:
        nu2 = nu1
    for name, v in (("E1", E1), ("E2", E2)):
        if not (math.isfinite(v) and v > 0.0):
            raise ValueError("%s = %g: expected a positive Young's modulus" % (name, v))
    for name, v in (("nu1", nu1), ("nu2", nu2)):
        if not (math.isfinite(v) and -1.0 < v < 0.5):
            raise ValueError("%s = %g: expected a Poisson's ratio in (-1, 0.5)" % (name, v))
    return 1.0 / ((1.0 - nu1 ** 2) / E1 + (1.0 - nu2 ** 2) / E2)


class BEMCurve:
    """The BEM's pressure-closure curve, model units (N/mm2, mm): rows in the order solved."""

    def __init__(self):
        self.p, self.u, self.area, self.points, self.spots, self.branch, self.iterations = [], [], [], [], [], [], []

    def add(self, p, u, area, points, spots, branch, nit):
        self.p.append(p)
        self.u.append(u)
        self.area.append(area)
        self.points.append(points)
        self.spots.append(spots)
        self.branch.append(branch)
        self.iterations.append(nit)

    def arrays(self):
        return (np.array(self.p), np.array(self.u), np.array(self.area), np.array(self.branch))


def _spots(mask):
    """Separate contact spots (4-connected clusters of grid points in contact)."""
    from scipy import ndimage
    return int(ndimage.label(mask)[1]) if mask.any() else 0


def _solver(surface, Es, hardness):
    from ContactMechanics import PeriodicFFTElasticHalfSpace, make_plastic_system, make_system
    topo = surface.topography()
    sub = PeriodicFFTElasticHalfSpace(surface.shape, Es, surface.sizes)
    if hardness:
        from SurfaceTopography import PlasticTopography
        ptopo = PlasticTopography(topo, hardness)
        return make_plastic_system(substrate=sub, surface=ptopo), ptopo
    return make_system(substrate=sub, surface=topo), None


def solve(surface, Es, pressures, hardness=None, unload=None, check=None, pentol=1e-6):
    """Press the flat on the rough half-space at each pressure (N/mm2, increasing), then, with
    `unload`, at each pressure of it (decreasing, ending at 0).  `check(curve)` is called after
    the first solution (the refusals).  pentol: the penetration tolerance as a fraction of the
    rms height.  Returns a BEMCurve (closures in mm)."""
    system, ptopo = _solver(surface, Es, hardness)
    h0 = surface.heights
    ubar0 = float(h0.max() - h0.mean())
    area = float(np.prod(surface.sizes))
    tol = pentol * surface.rms_height()
    curve = BEMCurve()
    disp = None
    seq = [(p, "L") for p in pressures] + [(p, "U") for p in (unload or [])]
    for k, (p, branch) in enumerate(seq):
        hnow = ptopo.heights() if ptopo is not None else h0
        if p == 0.0:
            # at zero load the flat rests on the highest point of the (flattened) surface
            u = ubar0 - float(hnow.max() - h0.mean())
            curve.add(0.0, u, 0.0, 0, 0, branch, 0)
            continue
        r = system.minimize_proxy(external_force=p * area, pentol=tol, initial_displacements=disp,
                                  maxiter=100000)
        if not r.success:
            raise RuntimeError("the BEM did not converge at p = %.6g N/mm2 on %s: %s" % (p, surface.name, r.message))
        disp = r.x
        gap = system.compute_gap(r.x, r.offset)
        hnew = ptopo.heights() if ptopo is not None else h0
        # mean separation from the original mean plane: the gap's mean plus the mean plastic flattening
        ubar = float(np.mean(gap) + (hnew.mean() - h0.mean())) if ptopo is not None else float(np.mean(gap))
        mask = np.asarray(r.jac) > 0.0
        curve.add(p, ubar0 - ubar, float(mask.mean()), int(mask.sum()), _spots(mask), branch, int(r.nit))
        if k == 0 and check is not None:
            check(curve)
    return curve


def check_resolution(path, surface, pmin_text):
    """The refusal after the first solution (at PMIN): enough grid points and spots in contact."""
    def check(curve):
        n, spots = curve.points[0], curve.spots[0]
        dx = max(surface.spacing) * 1e3
        if n < MIN_CONTACT_POINTS:
            raise cal.DataError(path, 0, "sample too coarse for the pressure range: at p = %s only %d grid point(s) "
                                "are in contact (A/A0 = %.2g), at least %d needed to resolve the contact; use a scan "
                                "with a finer pixel (now %.3g um), or a PMIN of about %.3g times this one"
                                % (pmin_text, n, curve.area[0], MIN_CONTACT_POINTS, dx,
                                   MIN_CONTACT_POINTS / max(n, 1)))
        if spots < MIN_SPOTS:
            raise cal.DataError(path, 0, "sample too small for the pressure range: at p = %s the flat touches %d "
                                "contact spot(s), at least %d needed for a closure that does not hang on a few "
                                "asperities; use a larger scan (now %s mm) or a larger PMIN"
                                % (pmin_text, spots, MIN_SPOTS, " x ".join("%.4g" % s for s in surface.sizes)))
    return check


def write_curve(path, curve, units, header_comments):
    """The BEM curve as a `normal`-mode CSV in the cards' length and pressure units."""
    p, u, area, branch = curve.arrays()
    with open(path, "w") as f:
        for c in header_comments:
            f.write("# %s\n" % c)
        f.write("p [%s], u [%s], branch, area_ratio [-]\n" % (units.pressure_name, units.length_name))
        for k in range(len(p)):
            f.write("%.10g, %.10g, %s, %.6g\n" % (p[k] / units.pressure, u[k] / units.length, branch[k], area[k]))


def _power_fit(p, u):
    A = np.column_stack([np.ones(p.size), np.log(p)])
    coef = np.linalg.lstsq(A, np.log(u), rcond=None)[0]
    c, m = math.exp(coef[0]), float(coef[1])
    return c, m, float(np.max(np.abs(c * p ** m / u - 1.0)))


def power_law_range(p, u, tol=POWER_LAW_TOL, min_points=4):
    """The widest pressure window (in decades) over which one power law u = c p^m follows the
    loading points to `tol` (relative).  Returns (i, j, c, m, worst) with p[i]..p[j], or None."""
    best = None
    n = len(p)
    for i in range(n):
        for j in range(i + min_points - 1, n):
            c, m, worst = _power_fit(p[i:j + 1], u[i:j + 1])
            if worst <= tol and (best is None or math.log(p[j] / p[i]) > math.log(p[best[1]] / p[best[0]]) + 1e-12):
                best = (i, j, c, m, worst)
    return best


def log_law(p, u):
    """Persson's exponential pressure-separation relation at low pressure, p ~ exp(-ubar/u0),
    is a closure u = u0 ln(p/p1): the line through (ln p, u).  Returns (u0, p1, worst relative)."""
    A = np.column_stack([np.ones(p.size), np.log(p)])
    a, b = np.linalg.lstsq(A, u, rcond=None)[0]
    model = a + b * np.log(p)
    return float(b), float(math.exp(-a / b)) if b else float("nan"), float(np.max(np.abs(model / u - 1.0)))


class TopographyFit:
    """The outcome: the normal fit (k2d.calibration.Fit) plus the BEM's figures."""

    def __init__(self):
        self.fit = None
        self.curve = None
        self.surface = None
        self.Es = None
        self.hardness = None
        self.notes = []
        self.warnings = []
        self.doubtful = []
        self.convergence = []
        self.valid = None
        self.csv = None

    def report(self):
        L = ["normal law from the surface %s (BEM: %s grid points, %s mm, E* = %.6g N/mm2%s)"
             % (self.surface.name, " x ".join(map(str, self.surface.shape)),
                " x ".join("%.4g" % s for s in self.surface.sizes), self.Es,
                ", hardness %.6g N/mm2" % self.hardness if self.hardness else ", elastic")]
        L += ["  " + n for n in self.notes]
        L.append(self.fit.report())
        L += ["  " + c for c in self.convergence]
        L += ["warning: " + w for w in self.warnings]
        L += ["doubtful: " + d for d in self.doubtful]
        return "\n".join(L)


def _pressures(pmin, pmax, n):
    return list(np.geomspace(pmin, pmax, n))


def calibrate(surface, path, Es, pmin, pmax, units, hardness=None, points=16, out=".", stem=None,
              same_exponent=False, check=True):
    """BEM curve, CSV and normal fit over [pmin, pmax] (N/mm2).  Returns a TopographyFit."""
    tf = TopographyFit()
    tf.surface, tf.Es, tf.hardness = surface, Es, hardness
    load = _pressures(pmin, pmax, points)
    unload = [p for p in reversed(load[:-1])] + [0.0] if hardness else None
    pmin_text = "%.6g %s" % (pmin / units.pressure, units.pressure_name)
    chk = check_resolution(path, surface, pmin_text) if check else None
    tf.curve = curve = solve(surface, Es, load, hardness=hardness, unload=unload, check=chk)
    p, u, area, branch = curve.arrays()
    os.makedirs(out, exist_ok=True)
    stem = stem or os.path.splitext(os.path.basename(path))[0]
    tf.csv = os.path.join(out, stem + "_bem.csv")
    write_curve(tf.csv, curve, units, [
        "pressure-closure of %s by FFT boundary elements (ContactMechanics), tools/calibrate.py topography"
        % surface.name,
        "E* = %.8g N/mm2%s; closure from first touch; area_ratio = contact area / sample area"
        % (Es, ", hardness %.8g N/mm2" % hardness if hardness else ", elastic")])
    tf.fit = cal.fit_normal(tf.csv, units, loading_only=not hardness, same_exponent=same_exponent)
    if not hardness:
        # elastic asperities unload along the loading curve: c_n2 = c_n, m2 = m (the program's
        # default c_n2 = c_n/2 would invent a residual closure)
        c, m = tf.fit.value("c_n"), tf.fit.value("m")
        tf.fit.normal_card = tf.fit.cards[-1] = cal.card("NORMAL", c, m, c, m)
        tf.fit.notes.append("elastic: the card unloads along the loading curve (CN2 = CN, M2 = M, no residual "
                            "closure); --hardness for asperities that yield")
    L = branch == "L"
    tf.notes.append("rms height %.4g um, rms slope %.4g; contact area A/A0 from %.3g (p = %.4g) to %.3g (p = %.4g %s), "
                    "%d to %d spots"
                    % (surface.rms_height() * 1e3, surface.rms_gradient(), area[0], p[0] / units.pressure,
                       area[L][-1], p[L][-1] / units.pressure, units.pressure_name, curve.spots[0],
                       curve.spots[int(np.sum(L)) - 1]))
    if not surface.periodic:
        tf.notes.append("the scan is not periodic: the BEM repeats it, so its edges meet in a step; "
                        "the convergence runs on its quarters show how much the edges matter")
    if hardness:
        res = u[-1]
        tf.notes.append("unloaded to zero: residual closure %.4g %s (plastic flattening of the asperities)"
                        % (res / units.length, units.length_name))
    # where the power law holds
    pl, ul = p[L], u[L]
    c, m, worst = _power_fit(pl, ul)
    rng = power_law_range(pl, ul)
    u0, p1, logworst = log_law(pl, ul)
    tf.valid = rng
    ps = units.pressure_name
    if worst <= POWER_LAW_TOL:
        tf.notes.append("the power law follows the BEM loading curve to %.2g %% over the whole range (tolerance %g %%)"
                        % (100 * worst, 100 * POWER_LAW_TOL))
    else:
        where = ("it holds to %g %% from p = %.4g to %.4g %s (%.2g decades)"
                 % (100 * POWER_LAW_TOL, pl[rng[0]] / units.pressure, pl[rng[1]] / units.pressure, ps,
                    math.log10(pl[rng[1]] / pl[rng[0]]))) if rng else "it holds over no 4 consecutive points"
        tf.doubtful.append("the power law u = c_n p^m does not fit the BEM loading curve over %.4g to %.4g %s: "
                           "worst relative deviation %.2g %%; %s; Persson's logarithmic closure u = u0 ln(p/p1) "
                           "(exponential pressure-separation law) deviates by %.2g %% (u0 = %.4g %s); narrow "
                           "--pressure-range to the range where the power law holds"
                           % (pl[0] / units.pressure, pl[-1] / units.pressure, ps, 100 * worst, where,
                              100 * logworst, u0 / units.length, units.length_name))
    if area[L][-1] > 0.5:
        tf.warnings.append("A/A0 reaches %.2g at PMAX: near full contact the closure saturates and no power law "
                           "follows it" % area[L][-1])
    return tf


def convergence(tf, path, pmin, pmax, units, points=16, out="."):
    """The constants again on the half-resolution grid and on the four quarters of the sample:
    their change from the full sample.  Appends lines to tf.convergence; a change above 10 %
    makes the calibration doubtful."""
    names = [c.name for c in tf.fit.constants]
    full = {c.name: c.value for c in tf.fit.constants}
    runs = [("half resolution", [tf.surface.coarsened()]), ("quarters", tf.surface.quarters())]
    worst_all = 0.0
    for label, surfs in runs:
        vals, refused = [], []
        for k, s in enumerate(surfs):
            try:
                sub = calibrate(s, path, tf.Es, pmin, pmax, units, hardness=tf.hardness, points=points,
                                out=os.path.join(out, "convergence"),
                                stem="%s_%s%d" % (os.path.splitext(os.path.basename(path))[0],
                                                  label.replace(" ", "_"), k + 1))
                vals.append({c.name: c.value for c in sub.fit.constants})
            except cal.DataError as e:
                refused.append(str(e).split("error: ", 1)[-1])
        if not vals:
            tf.convergence.append("convergence, %s: not resolved (%s)" % (label, refused[0] if refused else "?"))
            continue
        parts = []
        for n in names:
            v = np.array([d[n] for d in vals])
            ch = float(np.max(np.abs(v / full[n] - 1.0)))
            worst_all = max(worst_all, ch)
            parts.append("%s %s (%+.2g %%)" % (n, "/".join("%.4g" % x for x in v),
                                               100 * float(v[np.argmax(np.abs(v / full[n] - 1.0))] / full[n] - 1.0)))
        tf.convergence.append("convergence, %s (%d sample(s)%s): %s"
                              % (label, len(vals), ", %d refused" % len(refused) if refused else "", ", ".join(parts)))
    tf.convergence.insert(0, "convergence of the BEM (constants from the full sample against the same sample at "
                          "half resolution and its four quarters):")
    tf.convergence_worst = worst_all
    if worst_all > 0.10:
        tf.doubtful.append("the constants change by up to %.2g %% between the full sample and its half-resolution "
                           "grid or quarters: the sample does not resolve the contact well enough (a finer or larger "
                           "scan)" % (100 * worst_all))
