"""Refinement to a requested accuracy: the library of tools/adapt.py (docs/adaptivity.md).

    from k2d import adapt as ad
    ad.deck_kind("plate_hole.dat")           # ("mesh", msh, geo) or ("cards", None, None)
    r = Result("run.h5")
    eta, est, source = ad.indicator(r, ad.deck_materials("plate_hole.dat"))
    ad.key_outputs(r)                        # peak pressure, width, approach, von Mises, slip zone, drift
    ad.richardson(f1, f2, f3)                # observed order, extrapolated value, error (3 levels h, h/2, h/4)
    rows = ad.adapt_mesh_deck(deck, target, max_dofs, out, exe)        # gmsh remeshing
    rows = ad.refine_card_deck(deck, target, max_dofs, out, exe)       # uniform splitting

The error estimate of a run is the program's when its result file has it (per increment the
dataset `error_indicator`, one eta_e per element, and the attribute `estimated_error`);
otherwise it is computed here from the result file's Gauss-point stresses (Zienkiewicz & Zhu
1987, 1992): the recovered stress sigma* is the nodal stress of superconvergent patch recovery
(spr_stress: a polynomial of the element order fitted to the Gauss-point stresses of the
elements around each corner node) interpolated with the element's shape functions to its
Gauss points, and

    e_e^2 = sum over the Gauss points of e of (sigma* - sigma_h) : C^-1 (sigma* - sigma_h) dV,
    eta_e = e_e / sqrt(U^2 + sum e_e^2),   U^2 = sum sigma_h : C^-1 sigma_h dV,

so that the global relative energy-norm estimate is sqrt(sum eta_e^2), the program's convention.
"""
import math
import os
import shutil
import subprocess
import time

import numpy as np

from . import adapt_mesh as am
from .results import Result


class AdaptError(Exception):
    """A request tools/adapt.py cannot serve; the message says what and why."""


# ------------------------------------------------------------------------------------ the deck
def _card_word(line):
    return line.split("#", 1)[0][:10].strip().upper()


def deck_kind(path):
    """("mesh", msh path, geo path or None) for a deck with a MESH block, ("cards", None, None)
    otherwise.  The .geo is the one of the .msh's base name beside it (tools/run.sh's rule)."""
    with open(path) as f:
        for line in f:
            if _card_word(line) == "GMSH":
                msh = line.split("#", 1)[0][10:].strip()
                if not os.path.isabs(msh):
                    msh = os.path.join(os.path.dirname(os.path.abspath(path)), msh)
                geo = os.path.splitext(msh)[0] + ".geo"
                return "mesh", msh, geo if os.path.isfile(geo) else None
    return "cards", None, None


def deck_materials(path):
    """{mat: (E, nu, thick)} from the MATERIALS block of a deck (either kind)."""
    mats, block = {}, None
    with open(path) as f:
        for line in f:
            s = line.split("#", 1)[0].rstrip()
            if not s.strip():
                continue
            if s.lstrip()[0].isalpha():
                block = s.split()[0].upper()
                continue
            if block == "MATERIALS":
                try:
                    thick = s[25:35].strip()
                    mats[int(s[0:5])] = (float(s[5:15].replace("D", "e")), float(s[15:25].replace("D", "e")),
                                         float(thick.replace("D", "e")) if thick else 1.0)
                except ValueError:
                    raise AdaptError("%s: a MATERIALS card that does not read: %r" % (path, s))
    if not mats:
        raise AdaptError("%s: no MATERIALS block" % path)
    return mats


def with_mesh_file(deck_text, msh):
    """The deck's text with its GMSH card naming `msh` instead."""
    out, done = [], False
    for line in deck_text.splitlines():
        if not done and _card_word(line) == "GMSH":
            line = "%-10s%s" % ("GMSH", msh)
            done = True
        out.append(line)
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------------- shape functions
def _shape_deriv(nn, xi, eta):
    """Shape functions (n, nn) and their derivatives (n, nn, 2) of the quadrilaterals."""
    xi, eta = np.asarray(xi, float), np.asarray(eta, float)
    if nn == 4:
        a = np.array([-1, 1, 1, -1.0])
        b = np.array([-1, -1, 1, 1.0])
        X, E = xi[:, None], eta[:, None]
        N = 0.25 * (1 + a * X) * (1 + b * E)
        dN = np.stack([0.25 * a * (1 + b * E), 0.25 * b * (1 + a * X)], axis=-1)
        return N, dN
    if nn == 8:
        a = np.array([-1, 1, 1, -1.0])
        b = np.array([-1, -1, 1, 1.0])
        X, E = xi[:, None], eta[:, None]
        Nc = 0.25 * (1 + a * X) * (1 + b * E) * (a * X + b * E - 1)
        dNc_x = 0.25 * a * (1 + b * E) * (2 * a * X + b * E)
        dNc_e = 0.25 * b * (1 + a * X) * (a * X + 2 * b * E)
        x, e = xi, eta
        Nm = np.stack([0.5 * (1 - x * x) * (1 - e), 0.5 * (1 + x) * (1 - e * e),
                       0.5 * (1 - x * x) * (1 + e), 0.5 * (1 - x) * (1 - e * e)], axis=1)
        dNm_x = np.stack([-x * (1 - e), 0.5 * (1 - e * e), -x * (1 + e), -0.5 * (1 - e * e)], axis=1)
        dNm_e = np.stack([-0.5 * (1 - x * x), -e * (1 + x), 0.5 * (1 - x * x), -e * (1 - x)], axis=1)
        N = np.concatenate([Nc, Nm], axis=1)
        dN = np.stack([np.concatenate([dNc_x, dNm_x], 1), np.concatenate([dNc_e, dNm_e], 1)], axis=-1)
        return N, dN

    def lag1d(s):
        return np.stack([0.5 * s * (s - 1), 1 - s * s, 0.5 * s * (s + 1)], 1), \
            np.stack([s - 0.5, -2 * s, s + 0.5], 1)
    lx, dlx = lag1d(xi)
    ly, dly = lag1d(eta)
    ij = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 0), (2, 1), (1, 2), (0, 1), (1, 1)]
    N = np.stack([lx[:, i] * ly[:, j] for i, j in ij], 1)
    dN = np.stack([np.stack([dlx[:, i] * ly[:, j] for i, j in ij], 1),
                   np.stack([lx[:, i] * dly[:, j] for i, j in ij], 1)], axis=-1)
    return N, dN


def _inverse_map(nn, X, P):
    """Local coordinates of the points P (n, 2) in the elements of node coordinates X (n, nn, 2),
    with the Jacobian determinant there: (N (n, nn), detJ (n), (xi, eta) (n, 2))."""
    n = len(P)
    if nn == 3:
        x1, x2, x3 = X[:, 0], X[:, 1], X[:, 2]
        J = np.stack([x2 - x1, x3 - x1], axis=-1)              # columns: d/dxi, d/deta
        loc = _solve2(J, P - x1)
        xi, eta = loc[:, 0], loc[:, 1]
        N = np.stack([1 - xi - eta, xi, eta], 1)
        return N, J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0], loc
    loc = np.zeros((n, 2))
    active = np.arange(n)
    for _ in range(30):
        N, dN = _shape_deriv(nn, loc[active, 0], loc[active, 1])
        Xa = X[active]
        x = np.einsum("pk,pkd->pd", N, Xa)
        J = np.einsum("pkd,pka->pda", Xa, dN)                  # dx_d / dxi_a
        step = _solve2(J, P[active] - x)
        loc[active] += step
        active = active[np.max(np.abs(step), axis=1) > 1e-12]
        if not len(active):
            break
    N, dN = _shape_deriv(nn, loc[:, 0], loc[:, 1])
    J = np.einsum("pkd,pka->pda", X, dN)
    return N, J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0], loc


def _solve2(J, r):
    """Solutions of the 2 x 2 systems J s = r (n of them), by Cramer's rule."""
    det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
    return np.stack([(J[:, 1, 1] * r[:, 0] - J[:, 0, 1] * r[:, 1]) / det,
                     (J[:, 0, 0] * r[:, 1] - J[:, 1, 0] * r[:, 0]) / det], axis=1)


def _gauss_weights(nn, loc, count):
    """Weights of the Gauss points at the local coordinates loc, for elements of `count`
    points: the tensor-product Gauss-Legendre rules (1, 4, 9, 16 points) and the triangle's
    1- and 3-point rules; other counts share the reference area equally."""
    if nn == 3:
        return np.full(len(loc), 0.5 / count)
    if count == 4:
        return np.ones(len(loc))
    if count == 9:
        w = np.where(np.abs(loc) > 0.4, 5.0 / 9.0, 8.0 / 9.0)
        return w[:, 0] * w[:, 1]
    if count == 16:
        w = np.where(np.abs(loc) > 0.6, 0.3478548451374538, 0.6521451548625461)
        return w[:, 0] * w[:, 1]
    return np.full(len(loc), 4.0 / count)


def energy_density(s, E, nu):
    """s : C^-1 s of stresses (n, 4) = xx, yy, xy, zz with the 3-D isotropic compliance (the zz
    column is the program's: 0 in plane stress, nu (xx + yy) in plane strain, hoop in
    axisymmetry, so that one formula serves every analysis type)."""
    xx, yy, xy, zz = s[:, 0], s[:, 1], s[:, 2], s[:, 3]
    return (xx * xx + yy * yy + zz * zz - 2 * nu * (xx * yy + yy * zz + zz * xx) + 2 * (1 + nu) * xy * xy) / E


def _basis(d, deg):
    """Complete polynomial basis of degree deg (0, 1, 2) at the scaled offsets d (n, 2)."""
    x, y = d[:, 0], d[:, 1]
    cols = [np.ones(len(d))]
    if deg >= 1:
        cols += [x, y]
    if deg >= 2:
        cols += [x * x, x * y, y * y]
    return np.stack(cols, axis=1)


def spr_stress(result, sg, order):
    """Nodal stresses recovered by superconvergent patch recovery (Zienkiewicz & Zhu 1992): around
    every corner node, a complete polynomial of the elements' order is fitted by least squares to
    the Gauss-point stresses `sg` of the elements that share the node (degree 0 when the patch
    has fewer points than terms) and evaluated at every node of those elements; each node gets the
    mean of the fits of the patches it belongs to."""
    m = result.mesh
    xy = m.coordinates
    conn, nnode = m.connectivity, m.element_nodes
    ge = m.gauss_element - 1
    gp = m.gauss_coordinates.reshape(-1, 2)
    order_gp = np.argsort(ge, kind="stable")
    start = np.searchsorted(ge[order_gp], np.arange(len(nnode) + 1))
    ncorner = np.where(nnode == 3, 3, 4)
    pairs = [(conn[e, k] - 1, e) for e in range(len(nnode)) for k in range(ncorner[e])]
    pairs.sort()
    acc = np.zeros((len(xy), sg.shape[1]))
    cnt = np.zeros(len(xy))
    i = 0
    while i < len(pairs):
        j = i
        while j < len(pairs) and pairs[j][0] == pairs[i][0]:
            j += 1
        node = pairs[i][0]
        els = [pairs[k][1] for k in range(i, j)]
        i = j
        idx = np.concatenate([order_gp[start[e]:start[e + 1]] for e in els])
        nodes = np.unique(np.concatenate([conn[e, :nnode[e]] - 1 for e in els]))
        scale = max(np.ptp(xy[nodes, 0]), np.ptp(xy[nodes, 1]), 1e-300)
        deg = int(order)
        while deg > 0 and len(idx) < [1, 3, 6][deg]:
            deg -= 1
        P = _basis((gp[idx] - xy[node]) / scale, deg)
        coef = np.linalg.lstsq(P, sg[idx], rcond=None)[0]
        acc[nodes] += _basis((xy[nodes] - xy[node]) / scale, deg) @ coef
        cnt[nodes] += 1
    used = cnt > 0
    acc[used] /= cnt[used, None]
    return acc


def _gauss_volumes(result, materials):
    """Per Gauss point of the model: (its element (0-based), its volume dV = w |det J| times the
    thickness or 2 pi r, its shape functions N (list per element type: (indices, N)), E, nu)."""
    m = result.mesh
    ge = m.gauss_element - 1
    gp = m.gauss_coordinates.reshape(-1, 2)
    conn = m.connectivity
    nnode = m.element_nodes
    xy = m.coordinates
    axi = int(result.attrs.get("ntype", 1)) == 3
    nelem = len(nnode)
    count = np.bincount(ge, minlength=nelem)
    Emat = np.array([materials[int(k)][0] for k in m.material])
    numat = np.array([materials[int(k)][1] for k in m.material])
    tmat = np.array([materials[int(k)][2] for k in m.material])
    dv = np.zeros(len(ge))
    shapes = []
    for nn in np.unique(nnode):
        sel = np.where(nnode[ge] == nn)[0]
        e = ge[sel]
        c = conn[e, :nn] - 1
        N, detJ, loc = _inverse_map(int(nn), xy[c], gp[sel])
        w = np.zeros(len(sel))
        for cnt in np.unique(count[e]):
            k = count[e] == cnt
            w[k] = _gauss_weights(int(nn), loc[k], int(cnt))
        dv[sel] = w * np.abs(detJ) * (2 * np.pi * gp[sel, 0] if axi else tmat[e])
        shapes.append((sel, c, N))
    return ge, dv, shapes, Emat[ge], numat[ge]


def _element_energies(result, materials, step, recovered=True):
    """Per element: (integral of (sigma* - sigma_h) : C^-1 (sigma* - sigma_h) dV, or None without
    `recovered`; integral of sigma_h : C^-1 sigma_h dV) over the element's Gauss points."""
    sg = step.field("stress_gauss")
    sn = spr_stress(result, sg, 2 if np.max(result.mesh.element_nodes) >= 8 else 1) if recovered else None
    nelem = len(result.mesh.element_nodes)
    ge, dv, shapes, E, nu = _gauss_volumes(result, materials)
    err = np.zeros(nelem)
    ref = np.zeros(nelem)
    for sel, c, N in shapes:
        e = ge[sel]
        h = sg[sel]
        if recovered:
            star = np.einsum("pk,pkc->pc", N, sn[c])
            err += np.bincount(e, dv[sel] * energy_density(star - h, E[sel], nu[sel]), minlength=nelem)
        ref += np.bincount(e, dv[sel] * energy_density(h, E[sel], nu[sel]), minlength=nelem)
    return (err if recovered else None), ref


class ReferenceField:
    """The stresses of a result `reference` (a much finer solution of the same bodies) anywhere
    in its bodies: per material (the bodies are not mixed: a stress jumps across an interface), a
    complete quadratic fitted by least squares to the stresses of the `k` Gauss points of the
    reference nearest to the point (a linear fit where the quadratic is undetermined, their mean
    where the linear one is too), evaluated at the point.  A local fit
    rather than the linear interpolation over a Delaunay triangulation of the Gauss points: along
    a straight boundary the rows of Gauss points make sliver triangles whose barycentric
    coordinates came out in the thousands (a stress of -6800 interpolated from values about 1 on
    the punch's Q8 meshes).  Built once, evaluated for many meshes."""

    def __init__(self, reference, k=16, terms=6):
        from scipy.spatial import cKDTree
        m = reference.mesh
        ge = m.gauss_element - 1
        gp = m.gauss_coordinates.reshape(-1, 2)
        sg = reference.last.field("stress_gauss")
        gmat = m.material[ge]
        self.path = reference.path
        self.estimate = reference.last.estimated_error
        self.dofs = 2 * len(m.coordinates)
        self.k, self.terms = k, terms
        self.fields = {}
        for mat in np.unique(gmat):
            src = np.where(gmat == mat)[0]
            self.fields[int(mat)] = (cKDTree(gp[src]), gp[src], sg[src])

    def __call__(self, points, material):
        """Stresses (n, 4) at `points` (n, 2) of materials `material` (n)."""
        out = np.full((len(points), 4), np.nan)
        for mat in np.unique(material):
            if int(mat) not in self.fields:
                raise AdaptError("%s: no elements of material %d, which the mesh compared has"
                                 % (self.path, mat))
            at = np.where(material == mat)[0]
            tree, xy, sg = self.fields[int(mat)]
            k = min(self.k, len(xy))
            dist, idx = tree.query(points[at], k=k)
            idx = idx.reshape(len(at), k)
            scale = np.maximum(np.max(dist.reshape(len(at), k), axis=1), 1e-300)[:, None]
            d = (xy[idx] - points[at][:, None, :]) / scale[:, :, None]     # (n, k, 2)
            full = np.concatenate([np.ones((len(at), k, 1)), d, d[:, :, :1] ** 2, d[:, :, :1] * d[:, :, 1:],
                                   d[:, :, 1:] ** 2], axis=2)                      # (n, k, 6)
            val = np.mean(sg[idx], axis=1)          # where no fit is determined: the mean
            todo = np.ones(len(at), dtype=bool)
            for terms in (self.terms, 3):           # quadratic; linear where that is undetermined
                if terms > self.terms or not todo.any():
                    continue
                P = full[todo][:, :, :terms]
                A = np.einsum("nki,nkj->nij", P, P)
                ev = np.linalg.eigvalsh(A)
                ok = ev[:, 0] > 1e-10 * ev[:, -1]
                sel = np.where(todo)[0][ok]
                val[sel] = np.linalg.solve(A[ok], np.einsum("nki,nkc->nic", P[ok], sg[idx[sel]]))[:, 0, :]
                todo[sel] = False
            out[at] = val
        return out


def reference_error(result, materials, reference):
    """(true relative energy-norm error, ||sigma_ref - sigma_h||^2, ||u_h||^2) of the last step of
    `result` against a much finer solution `reference` of the same bodies (an overkill mesh: a
    Result, or its ReferenceField; or any function (points, materials) -> stresses (n, 4), a
    closed form): the error energy ||sigma_ref - sigma_h||^2 = integral of (sigma_ref - sigma_h) : C^-1 (sigma_ref -
    sigma_h) dV by the Gauss rules of `result`, sigma_ref interpolated from the reference's
    Gauss points (ReferenceField), and the relative error in the estimate's convention,
    sqrt(e^2 / (||u_h||^2 + e^2)).  Needs no Galerkin orthogonality (contact with initial gaps,
    non-nested meshes); the reference's own error adds to e^2 about its square."""
    m = result.mesh
    ge, dv, _, E, nu = _gauss_volumes(result, materials)
    gp = m.gauss_coordinates.reshape(-1, 2)
    sh = result.last.field("stress_gauss")
    field = reference if callable(reference) else ReferenceField(reference)
    sr = field(gp, m.material[ge])
    e2 = float(np.sum(dv * energy_density(sr - sh, E, nu)))
    u2 = float(np.sum(dv * energy_density(sh, E, nu)))
    return math.sqrt(e2 / (u2 + e2)), e2, u2


def energy_norm2(result, materials, step=None):
    """||u_h||^2 = integral of sigma_h : C^-1 sigma_h dV over the model (twice its strain energy)
    at a step (default the last), by the elements' Gauss rules."""
    return float(np.sum(_element_energies(result, materials, step or result.last, recovered=False)[1]))


def zz_indicator(result, materials, step=None):
    """(eta_e (nelem), the global relative estimate) of a step (default the last) from the
    difference of the recovered and the Gauss-point stresses: module docstring."""
    err, ref = _element_energies(result, materials, step or result.last)
    nelem = len(ref)
    total = ref.sum() + err.sum()
    if total <= 0.0:
        return np.zeros(nelem), 0.0
    eta = np.sqrt(np.maximum(err, 0.0) / total)
    return eta, float(np.sqrt(np.sum(eta ** 2)))


def design_step(result):
    """The step whose estimate drives the refinement: the one of the largest strain energy
    (the attribute energy_norm the program writes with every estimate; ties to the later), so
    that a history unloaded to zero is refined for the load it carried and not for the
    round-off field of its end; the last step when no step has energy_norm."""
    best = None
    for s in result.steps:
        e = s.attrs.get("energy_norm")
        if e is None:
            continue
        e = float(np.atleast_1d(e)[0])
        if best is None or e >= best[0]:
            best = (e, s)
    return best[1] if best else result.last


def indicator(result, materials, step=None):
    """(eta_e, estimate, source) of a step (default design_step: the largest strain energy):
    the program's indicator when the result file has it (source "program": the step's
    error_indicator, one per element, and its estimated_error, read by k2d.results), else
    zz_indicator (source "stress recovery")."""
    step = step or design_step(result)
    eta = step.error_indicator
    if eta is not None:
        eta = np.asarray(eta, dtype=float).ravel()
        if eta.shape != (len(result.mesh.element_nodes),):
            raise AdaptError("%s: increment %d has %d error indicators for %d elements"
                             % (result.path, step.number, eta.size, len(result.mesh.element_nodes)))
        est = step.estimated_error
        return eta, float(np.sqrt(np.sum(eta ** 2))) if est is None else est, "program"
    eta, est = zz_indicator(result, materials, step)
    return eta, est, "stress recovery"


# ------------------------------------------------------------------------------ key outputs
SCHEMES = {"RETURN": "NEWTON", "EXPLICIT": "INCREMENTAL"}   # the result file's names -> the deck's
OUTPUTS = [("peak_pressure", "peak pressure"), ("width", "contact width"), ("approach", "approach"),
           ("von_mises", "largest von Mises stress"), ("slip_share", "slip zone (share of the closed area)")]


def von_mises(s):
    xx, yy, xy, zz = s[:, 0], s[:, 1], s[:, 2], s[:, 3]
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3 * xy * xy)


def key_outputs(result):
    """The outputs Richardson extrapolation is applied to, at the increment of the largest
    strain energy (design_step: the last kept increment unless the history unloads), and the
    increment-size figures of the scheme: {"peak_pressure", "width", "approach", "von_mises",
    "slip_share" (NaN without contact), "law_drift" (largest over the kept increments),
    "residual", "scheme"}."""
    out = {k: float("nan") for k, _ in OUTPUTS}
    step = design_step(result)
    out["von_mises"] = float(np.max(von_mises(step.field("stress_gauss"))))
    drift = result.history("law_drift")
    out["law_drift"] = float(np.nanmax(drift)) if np.any(np.isfinite(drift)) else float("nan")
    res = result.history("residual")
    out["residual"] = float(np.nanmax(res)) if np.any(np.isfinite(res)) else float("nan")
    out["scheme"] = ""
    if result.contact is not None:
        from .history import History
        h = History(result)
        f = h.figures(next(k for k, s in enumerate(h.steps) if s.number == step.number))
        for k in ("peak_pressure", "width", "approach", "slip_share"):
            out[k] = f[k]
        out["scheme"] = SCHEMES.get(str(result.contact.attrs.get("update", "")).upper(),
                                str(result.contact.attrs.get("update", "")))
    return out


# -------------------------------------------------------------------------------- Richardson
def richardson(f1, f2, f3, r=2.0, fs=1.25):
    """Richardson extrapolation (Richardson 1911) of a value on three meshes of sizes h, h/r,
    h/r^2 (f1 coarsest) and Roache's grid convergence index (Roache 1998, Fs = 1.25 for three
    meshes): {"order", "extrapolated", "error" (|f_ext - f3|, the estimated error of the finest),
    "gci" (relative), "note"}.  A sequence that is not monotone, or whose observed order is not
    positive, is "not in the asymptotic range": no order or extrapolation then, and the error is
    given as Roache's two-mesh GCI with Fs = 3 on the formal order's place taken by 1,
    3 |f3 - f2| / (r - 1)."""
    out = {"order": float("nan"), "extrapolated": float("nan"), "error": float("nan"),
           "gci": float("nan"), "note": ""}
    vals = [f1, f2, f3]
    if any(v is None or not math.isfinite(v) for v in vals):
        out["note"] = "not available"
        return out
    d1, d2 = f1 - f2, f2 - f3
    scale = max(abs(f1), abs(f2), abs(f3), 1e-300)
    if abs(d2) <= 1e-12 * scale and abs(d1) <= 1e-12 * scale:
        out.update(order=float("nan"), extrapolated=f3, error=0.0, gci=0.0, note="unchanged by refinement")
        return out
    if d1 * d2 <= 0.0 or abs(d2) >= abs(d1):
        out["error"] = 3.0 * abs(d2) / (r - 1.0)
        out["gci"] = out["error"] / abs(f3) if f3 != 0 else float("nan")
        out["note"] = "not in the asymptotic range (%s)" % ("oscillating" if d1 * d2 <= 0.0 else NOT_CONVERGING)
        return out
    p = math.log(d1 / d2) / math.log(r)
    ext = f3 + (f3 - f2) / (r ** p - 1.0)
    out.update(order=p, extrapolated=ext, error=abs(ext - f3),
               gci=fs * abs((f3 - f2) / f3) / (r ** p - 1.0) if f3 != 0 else float("nan"))
    return out


NOT_CONVERGING = "not converging (singular point?)"


# a key output that changed by less than this share of its value over the last step is not flagged
# as not converging (convergence_note)
SIGNIFICANT_CHANGE = 0.01


def convergence_note(values, dofs=None, rel=1e-9, significant=SIGNIFICANT_CHANGE):
    """Whether the last three values of a key output over a sequence of meshes converge:
    NOT_CONVERGING when they move one way with successive differences that do not decrease --
    the observed order log(d1 / d2) / log(r) is <= 0, as for a stress at a singular point (the
    largest von Mises stress at a punch's edge grows without limit under refinement) -- else "".
    A sequence that changes direction is not flagged here: the contact width moves in steps of
    the pair spacing and the peak pressure scatters by about 0.5 % on remeshed meshes (Richardson's
    table calls such a sequence "oscillating").  With `dofs` (a sequence of unequal steps,
    adaptive meshes) each difference is taken per unit of log(DOFs), so a small step is not
    mistaken for convergence; without, the meshes are equal steps (h, h/2, h/4).  A last change
    below `significant` times the last value is not flagged: a singular value changes by tens of
    per cent per step (the punch's edge pressure doubled), while the outputs of remeshed meshes
    that do converge wander by a few tenths of a per cent (Hertz's approach changed by 0.15 % then
    0.12 % over its last two adaptive steps, the second one short).  Values unchanged to `rel`, or
    fewer than three finite values: ""."""
    if len(values) < 3:
        return ""
    f = [float(v) for v in values[-3:]]
    if any(not math.isfinite(v) for v in f):
        return ""
    d1, d2 = f[1] - f[0], f[2] - f[1]
    scale = max(abs(v) for v in f)
    if abs(d1) <= rel * scale and abs(d2) <= rel * scale:
        return ""
    if abs(d2) < significant * abs(f[2]):
        return ""
    r1 = r2 = 1.0
    if dofs is not None:
        n = [float(v) for v in dofs[-3:]]
        if min(n) <= 0.0 or n[1] <= n[0] or n[2] <= n[1]:
            return ""            # no refinement between the meshes: nothing to say about the rate
        r1, r2 = math.log(n[1] / n[0]), math.log(n[2] / n[1])
    if abs(d2) / r2 < abs(d1) / r1:
        return ""
    return NOT_CONVERGING if d1 * d2 > 0.0 else ""


def convergence_flags(rows):
    """Mark the key outputs that do not converge: every row gets "not_converging", the outputs
    (their labels, "; "-separated) whose values on this mesh and the two meshes before it of the
    same method do not converge (convergence_note; a remeshed sequence per unit of log(DOFs), a
    card deck's splitting as equal steps).  Returns {method: [(label, note, last three values)]}
    for the last mesh of each method."""
    last = {}
    by_method = {}
    for r in rows:
        by_method.setdefault(r["method"], []).append(r)
    for method, rs in by_method.items():
        equal = all(r.get("split") for r in rs)
        for k, r in enumerate(rs):
            seq = rs[max(0, k - 2):k + 1]
            dofs = None if equal else [x["dofs"] for x in seq]
            flagged = []
            for key, label in OUTPUTS:
                note = convergence_note([x[key] for x in seq], dofs)
                if note:
                    flagged.append((label, note, [x[key] for x in seq]))
            r["not_converging"] = "; ".join("%s: %s" % (lab, note) for lab, note, _v in flagged)
            if k == len(rs) - 1:
                last[method] = flagged
    return last


def print_flags(rows, log=print):
    """The terminal's word on the key outputs that do not converge (convergence_flags)."""
    for method, flagged in convergence_flags(rows).items():
        for label, note, vals in flagged:
            log("adapt: %s, %s: %s (the last three meshes: %s)"
                % (method, label, note, ", ".join("%.6g" % v for v in vals)))


# -------------------------------------------------------------------------------- running
def run_cpu(cmd, log, cwd=None):
    """Run cmd, its output into `log`; (exit code, wall s, user + system CPU s of the child)."""
    with open(log, "w") as f:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=cwd)
        _, status, ru = os.wait4(p.pid, 0)
    return os.waitstatus_to_exitcode(status), time.perf_counter() - t0, ru.ru_utime + ru.ru_stime


def solve(exe, deck, h5, lis):
    """kontakt2d on one deck; (result, CPU s).  AdaptError when no complete result came out."""
    rc, wall, cpu = run_cpu([exe, deck, "-o", h5, "-l", lis, "-q"], os.path.splitext(h5)[0] + ".log")
    if rc not in (0, 4) or not os.path.isfile(h5):
        with open(os.path.splitext(h5)[0] + ".log") as f:
            tail = f.read().strip().splitlines()[-3:]
        raise AdaptError("kontakt2d %s ended with exit code %d: %s" % (deck, rc, " / ".join(tail)))
    return Result(h5), cpu, rc


def _row(label, result, eta_est, source, cpu_solve, cpu_mesh, rc):
    ko = key_outputs(result)
    row = {"step": label, "elements": len(result.mesh.element_nodes),
           "dofs": 2 * len(result.mesh.coordinates), "estimated_error": eta_est, "source": source,
           "cpu_solve": cpu_solve, "cpu_mesh": cpu_mesh, "exit": rc}
    row.update(ko)
    return row


# ---------------------------------------------------------------------- gmsh: the size field
def element_sizes(result):
    """(h_e, polynomial order p_e) of every element: h from the corners' area (a quadrilateral
    sqrt(A), a triangle the edge of the equilateral triangle of its area)."""
    m = result.mesh
    nn = m.element_nodes
    nc = np.where(nn == 3, 3, 4)
    xy = m.coordinates
    area = np.zeros(len(nn))
    for k in range(4):
        a = m.connectivity[:, k] - 1
        b = np.where(k + 1 < nc, m.connectivity[:, (k + 1) % 4], m.connectivity[:, 0]) - 1
        valid = k < nc
        area += np.where(valid, xy[a, 0] * xy[b, 1] - xy[b, 0] * xy[a, 1], 0.0)
    area = 0.5 * np.abs(area)
    h = np.where(nn == 3, np.sqrt(4.0 * area / math.sqrt(3.0)), np.sqrt(area))
    p = np.where(nn >= 8, 2, 1)
    return h, p


def new_sizes(eta, h, p, target, max_elements=None, shrink=(0.2, 2.0), safety=0.8, rate=None,
              max_growth=None):
    """The element sizes of the next mesh: equidistribution of the error over the new elements.

    With eta_e^2 ~ h^(2p+2) in an element's area (eta_e^2 = c h^2p times its area h^2), a size
    s_e h_e there gives (1/s_e^2) elements of error^2 eta_e^2 s_e^(2p+2) each; the fewest
    elements with sum eta_e^2 s_e^2p = (safety target)^2 have every new element's error equal:
    s_e = (lam / eta_e^2)^(1/(2p+2)), lam^(p/(p+1)) = (safety target)^2 / sum eta_e^(2/(p+1)).
    `rate` (per element, default None: every element smooth) gives the exponent lambda_e of an
    element at a singular point, where the solution goes like r^lambda: its error^2 is
    concentrated at the point and falls only like h^(2 lambda), so the child at the point keeps
    eta_e^2 s^(2 lambda) and s_e = (lam / eta_e^2)^(1/(2 lambda)) there (lambda = 0 or NaN:
    smooth).  s is kept within `shrink` per step.  With max_growth the predicted element count
    sum 1/s_e^2 is at most max_growth times the present one: the step aims at a larger target
    (found by bisection) whose equidistributed mesh fits, so a long way to the target is made in
    several meshes of the same shape rather than one.  With max_elements the sizes grow together
    until the predicted count fits.  Returns (new h_e, predicted element count)."""
    pe = float(np.max(p))          # one order for the mesh (gmsh meshes with one order)
    eta = np.maximum(eta, 1e-300)
    expo = np.full(len(eta), 1.0 / (2.0 * pe + 2.0))
    if rate is not None:
        lam_s = np.nan_to_num(np.asarray(rate, float), nan=0.0)
        sing = (lam_s > 0.0) & (lam_s < pe)
        expo[sing] = 1.0 / (2.0 * lam_s[sing])

    def sizes(t):
        lam = ((safety * t) ** 2 / np.sum(eta ** (2.0 / (pe + 1.0)))) ** ((pe + 1.0) / pe)
        return np.clip((lam / eta ** 2) ** expo, shrink[0], shrink[1])

    s = sizes(target)
    n_new = float(np.sum(1.0 / s ** 2))
    if max_growth and n_new > max_growth * len(eta):
        lo, hi = math.log(target), math.log(max(target, 1.0) * 1e6)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if np.sum(1.0 / sizes(math.exp(mid)) ** 2) > max_growth * len(eta):
                lo = mid
            else:
                hi = mid
        s = sizes(math.exp(hi))
        n_new = float(np.sum(1.0 / s ** 2))
    if max_elements and n_new > max_elements:
        s *= math.sqrt(n_new / max_elements)
        n_new = float(np.sum(1.0 / s ** 2))
    return s * h, n_new


# a contact zone's end is a singular edge only where its pair's pressure is this much above its
# neighbour's (singular_end)
SINGULAR_RISE = 1.1


def singular_end(pr, s, kc, end, rise=SINGULAR_RISE):
    """Whether the end `end` (0: the first, -1: the last) of a contact zone is a flat-punch-type
    singular edge: its closed pairs kc in the order of their positions s along the interface
    (s indexed by pair), their pressures pr.  The outermost pair's pressure at least the mean of
    the closed pairs' and at least `rise` times its inner neighbour's, and, with three or more
    closed pairs, the pressure rising towards the end ever more steeply (the slope between the
    two outermost pairs above the slope between the next two), as p ~ r^-1/2 does.  Where
    p ~ r^-1/2 the two outermost pairs' tributary means differ by a factor of about 2.7 on a
    uniform spacing (more than 1.4 on any grading).  The end of a half model on its symmetry
    axis, where the pressure has a flat maximum (Hertz's axis), passes neither test: its pair
    differs from its neighbour by the discretization's scatter, about 0.5 %, on a fine contact
    mesh, and where the spacing is coarse enough for the ellipse's own fall to exceed `rise`,
    the slope falls towards the axis.  Before these tests that maximum was taken for a singular
    edge and sized at the singular rate."""
    if len(kc) < 2:
        return False
    mean = float(np.mean(pr[kc]))
    j, inner = (kc[0], kc[1]) if end == 0 else (kc[-1], kc[-2])
    if not (mean > 0.0 and pr[j] >= mean and pr[j] >= rise * pr[inner]):
        return False
    if len(kc) < 3:
        return True
    outer2 = kc[2] if end == 0 else kc[-3]
    d01, d12 = abs(s[j] - s[inner]), abs(s[inner] - s[outer2])
    if d01 <= 0.0 or d12 <= 0.0:
        return True
    return (pr[j] - pr[inner]) / d01 > (pr[inner] - pr[outer2]) / d12


def singular_rates(result, lam=0.5):
    """The exponent lambda of the singular points of the solution the contact shows, per element
    (0 elsewhere): an interface whose contact zone ends at its largest pressures, rising
    steeply towards the end (singular_end) -- a flat punch's edge where p ~ r^-1/2 and
    u ~ r^1/2 (Johnson 1985, sec. 2.8), not Hertz's edge where p falls to zero nor the symmetry
    axis of a half model, where p has a flat maximum --
    gives lambda = 1/2 to the elements at the nodes of that pair (node a, and node b or the nodes
    of surface B under it).  Re-entrant corners of the bodies are not detected."""
    m = result.mesh
    rate = np.zeros(len(m.element_nodes))
    c = result.contact
    if c is None:
        return rate
    last = result.last
    pr = last.contact("pressure")
    closed = last.contact("normal_state") > 0
    pos = c.position
    nodes = set()
    for itf in np.unique(c.interface):
        k = np.where(c.interface == itf)[0]
        axis = 0 if np.ptp(pos[k, 0]) >= np.ptp(pos[k, 1]) else 1
        k = k[np.argsort(pos[k, axis])]
        kc = k[closed[k]]
        for end in (0, -1):
            if not singular_end(pr, pos[:, axis], kc, end):
                continue
            j = kc[end]
            nodes.add(int(c.node_a[j]) - 1)
            if "master_nodes" in c:
                nodes.update(int(v) - 1 for v, w in zip(c.master_nodes[j], c.master_weights[j])
                             if v > 0 and w > 0)
            else:
                nodes.add(int(c.node_b[j]) - 1)
    if not nodes:
        return rate
    sel = np.array(sorted(nodes))
    for e in range(len(rate)):
        if np.isin(m.connectivity[e, :m.element_nodes[e]] - 1, sel).any():
            rate[e] = lam
    return rate


def traction_sizes(result, target):
    """The element sizes the contact tractions ask for: along each interface, in the order of the
    pairs' positions, the pressure's second difference p'' at a pair between two others (one of
    the three closed) bounds the error of its interpolation over an edge of length h by
    h^2 |p''| / 8; keeping it below target times the interface's peak pressure asks for
    h <= sqrt(8 target p_max / |p''|) at the pair's nodes (node a, and node b or the nodes of
    surface B under it).  Returns {node index (0-based): size}, empty without contact."""
    c = result.contact
    if c is None:
        return {}
    last = result.last
    p = last.contact("pressure")
    closed = last.contact("normal_state") > 0
    pos = c.position
    want = {}
    for itf in np.unique(c.interface):
        k = np.where(c.interface == itf)[0]
        axis = 0 if np.ptp(pos[k, 0]) >= np.ptp(pos[k, 1]) else 1
        k = k[np.argsort(pos[k, axis])]
        pk = p[k]
        pmax = float(np.max(np.where(closed[k], pk, 0.0))) if np.any(closed[k]) else 0.0
        if pmax <= 0.0 or len(k) < 3:
            continue
        s = pos[k, axis]
        for j in range(1, len(k) - 1):
            if not closed[k[j - 1:j + 2]].any():
                continue
            h1, h2 = s[j] - s[j - 1], s[j + 1] - s[j]
            if h1 <= 0.0 or h2 <= 0.0:
                continue
            d2 = 2.0 * (h1 * pk[j + 1] - (h1 + h2) * pk[j] + h2 * pk[j - 1]) / (h1 * h2 * (h1 + h2))
            if d2 == 0.0:
                continue
            hreq = math.sqrt(8.0 * target * pmax / abs(d2))
            nodes = [int(c.node_a[k[j]]) - 1]
            if "master_nodes" in c:
                nodes += [int(v) - 1 for v, w in zip(c.master_nodes[k[j]], c.master_weights[k[j]]) if v > 0 and w > 0]
            else:
                nodes.append(int(c.node_b[k[j]]) - 1)
            for n in nodes:
                want[n] = min(want.get(n, np.inf), hreq)
    return want


def limit_by_tractions(result, hnew, h, target, shrink=0.2):
    """hnew with the sizes of the elements at the contact pairs limited by traction_sizes (never
    below shrink times their present size); returns (sizes, number of elements limited)."""
    want = traction_sizes(result, target)
    if not want:
        return hnew, 0
    out = hnew.copy()
    limited = 0
    m = result.mesh
    for e in range(len(out)):
        nodes = m.connectivity[e, :m.element_nodes[e]] - 1
        w = min((want[n] for n in nodes if n in want), default=np.inf)
        if w < out[e]:
            out[e] = max(w, shrink * h[e])
            limited += 1
    return out, limited


def msh_nodes(path):
    """The node count of a gmsh .msh file (format 4.1 or 2.2, ASCII) from its $Nodes header."""
    with open(path) as f:
        for line in f:
            if line.strip() == "$Nodes":
                head = f.readline().split()
                return int(head[1]) if len(head) >= 4 else int(head[0])
    raise AdaptError("%s: no $Nodes section" % path)


# the nodes of surface A along a contact take this share of the size both sides ask for there
FINER_A = 0.8


def interface_sizes(result, nodal, finer=FINER_A):
    """The nodal sizes `nodal` (npoin) with surface A made the finer side of every contact: the
    size of each pair's node a at most `finer` times the smallest size of the nodes of surface B
    it is coupled with (its `master_nodes`, or node b).  Each body's side of an interface is
    meshed from that body's own indicators, and where surface B came out finer than surface A a
    node of A faced more nodes of B than MATCHING SEGMENT takes (7; the program stops with
    E-SEGMENT-SIDE -- met on the second adaptive mesh of a Q8 Hertz model, surface B beside the
    contact zone 2.5 times as fine as A); a node of A a little finer than B spans at most three
    edges of B.  Surface B is not changed (taking the smaller of the two sides' sizes on both
    would pass each pair's minimum on to the next through their shared nodes of B, along the
    whole interface).  Node-to-node pairs are matched by no remeshing (docs/adaptivity.md)."""
    c = result.contact
    if c is None or not c.npair:
        return nodal
    nodal = np.array(nodal, dtype=float)
    base = nodal.copy()
    for j in range(c.npair):
        b = []
        if "master_nodes" in c:
            b = [int(v) - 1 for v, w in zip(c.master_nodes[j], c.master_weights[j]) if v > 0 and w != 0]
        if not b:
            b = [int(c.node_b[j]) - 1]
        sizes = [base[k] for k in b if 0 <= k < len(base) and np.isfinite(base[k])]
        a = int(c.node_a[j]) - 1
        if sizes and np.isfinite(base[a]):
            nodal[a] = min(nodal[a], finer * min(sizes))
    return nodal


# the uniform spacing along a curved contact covers the contact zone and this share of its
# extent beyond each end (plus one pair spacing): the zone's edge moves from mesh to mesh
CONTACT_MARGIN = 0.25


def _pair_b_nodes(c, j):
    """The nodes (0-based) of surface B that pair j is coupled with (master_nodes, or node b)."""
    if "master_nodes" in c:
        b = [int(v) - 1 for v, w in zip(c.master_nodes[j], c.master_weights[j]) if v > 0 and w != 0]
        if b:
            return b
    return [int(c.node_b[j]) - 1]


def curved_contact_zones(result, margin=CONTACT_MARGIN, bend=0.05):
    """The contact zones whose surface spacing is made uniform (contact_spacing): per interface
    whose closed pairs' initial gaps g0 are not an affine function of the position along the
    interface -- a curved surface, whose chords add to the mortar gap an offset that depends on
    the local spacing (h^2 / (6 R) for a Q4 chord h on a radius R) -- and whose zone is not
    ended by a flat-punch-type singular edge (the outermost closed pair's pressure at least the
    mean of the closed pairs', singular_rates: those edges want grading).  "Not affine": the
    largest residual of the straight line fitted to g0 over the closed pairs is more than `bend`
    times g0's range, a range above 1e-9 of the zone's extent.  Returns [(interface, the pairs
    within the zone extended by `margin` times its extent plus one pair spacing beyond each end)]."""
    c = result.contact
    if c is None or not c.npair or "gap" not in c:
        return []
    step = design_step(result)
    pr = step.contact("pressure")
    closed = step.contact("normal_state") > 0
    pos = c.position
    gap = np.asarray(c.gap, dtype=float)
    out = []
    for itf in np.unique(c.interface):
        k = np.where(c.interface == itf)[0]
        axis = 0 if np.ptp(pos[k, 0]) >= np.ptp(pos[k, 1]) else 1
        k = k[np.argsort(pos[k, axis])]
        kc = k[closed[k]]
        if len(kc) < 1:
            continue
        if any(singular_end(pr, pos[:, axis], kc, end) for end in (0, -1)):
            continue                        # a singular edge: keep the grading
        s = pos[k, axis]
        lo, hi = float(pos[kc[0], axis]), float(pos[kc[-1], axis])
        i0, i1 = int(np.searchsorted(s, lo)), int(np.searchsorted(s, hi, side="right")) - 1
        spacing = max(s[min(i0 + 1, len(s) - 1)] - s[i0], s[i1] - s[max(i1 - 1, 0)], 0.0)
        ext = margin * (hi - lo) + spacing
        # the curvature, from the gaps of the closed pairs and their neighbours on both sides
        j0, j1 = max(i0 - 1, 0), min(i1 + 1, len(k) - 1)
        sg, gg = s[j0:j1 + 1], gap[k[j0:j1 + 1]]
        if len(sg) < 3:
            continue
        rng = float(np.ptp(gg))
        if rng <= 1e-9 * max(float(np.ptp(sg)), 1e-300):
            continue
        res = gg - np.polyval(np.polyfit(sg, gg, 1), sg)
        if np.max(np.abs(res)) <= bend * rng:
            continue
        out.append((int(itf), k[(s >= lo - ext) & (s <= hi + ext)]))
    return out


def contact_spacing(result, nodal, margin=CONTACT_MARGIN):
    """The nodal sizes `nodal` (npoin) with a uniform spacing along every curved contact zone
    (curved_contact_zones): the nodes of both surfaces of the zone's pairs (node a and the nodes
    of surface B under it) all take the smallest size any of them asks.  On a graded contact
    mesh the chords' offset h^2 / (6 R) of the mortar gap varies along the zone, on a uniform
    one it is a rigid shift that changes no pressure; this was the suspected source of the
    peak pressure's +-0.5 % noise on Hertz's adaptive meshes.  Measured (docs/adaptivity.md,
    "The peak pressure's scatter on Hertz's adaptive meshes"): it makes the offset uniform to
    0.04 % of the zone's edge gap and the pressure profile smoother, but the peak pressure
    scatters as much (+-0.6 %), so it is not the route's default (tools/adapt.py
    --uniform-contact).  Returns (sizes, nodes changed)."""
    nodal = np.array(nodal, dtype=float)
    changed = 0
    c = result.contact
    for _itf, pairs in curved_contact_zones(result, margin):
        nodes = set()
        for j in pairs:
            nodes.add(int(c.node_a[j]) - 1)
            nodes.update(_pair_b_nodes(c, j))
        sel = np.array(sorted(n for n in nodes if 0 <= n < len(nodal) and np.isfinite(nodal[n])), dtype=int)
        if not len(sel):
            continue
        h = float(np.min(nodal[sel]))
        changed += int(np.count_nonzero(nodal[sel] > h))
        nodal[sel] = h
    return nodal, changed


def view_sizes(result, hnew, uniform_contact=False):
    """The nodal sizes of the size view: the smallest of the sizes `hnew` wanted by the elements
    around each node, with `uniform_contact` one size along each curved contact zone
    (contact_spacing), and surface A the finer side (interface_sizes)."""
    m = result.mesh
    nn = m.element_nodes
    nodal = np.full(len(m.coordinates), np.inf)
    for k in range(4):
        valid = (nn != 3) | (k < 3)
        np.minimum.at(nodal, m.connectivity[valid, k] - 1, hnew[valid])
    if uniform_contact:
        nodal = contact_spacing(result, nodal)[0]
    return interface_sizes(result, nodal)


def contact_layers(result, nodal, msh, first=None, depth=None):
    """The boundary layers of quadrilaterals of the next mesh (k2d.adapt_mesh.layer_lines) along
    the curved contact zones (curved_contact_zones: the curved interfaces without a singular
    edge): per body, the curves of `msh` (the .msh the result was computed on; the next mesh is
    made from the same .geo) that hold a node of a zone's pairs (node a or a node of surface B
    under it), carried on along straight or tangent continuations to a corner
    (am.layer_chain); the first thickness at each end point of the curves `first` times the
    view's size `nodal` at the nearest node of the result's mesh, the layer's depth `depth`
    times the smallest of them on the contact curves.  Returns [{"curves", "sizes", "depth"}]
    (empty without a curved zone or when the bodies of `msh` do not match the result's)."""
    first = am.LAYER_FIRST if first is None else first
    depth = am.LAYER_DEPTH if depth is None else depth
    zones = curved_contact_zones(result)
    if not zones or msh is None:
        return []
    c = result.contact
    xy = result.mesh.coordinates
    nodes = set()
    for _itf, pairs in zones:
        for j in pairs:
            nodes.add(int(c.node_a[j]) - 1)
            nodes.update(_pair_b_nodes(c, j))
    zone_xy = xy[sorted(n for n in nodes if 0 <= n < len(xy))]
    if not len(zone_xy):
        return []
    topo = am.msh_topology(msh)
    bodies = am.msh_bodies(msh)
    tol = 1e-9 * float(np.ptp(xy, axis=0).max() or 1.0)
    seeds = []
    for curve, inner in topo["curve_nodes"].items():
        if len(inner) and any(np.min(np.hypot(*(zone_xy - q).T)) <= tol for q in inner):
            seeds.append(curve)
    out = []
    for body in bodies:
        mine = [cv for cv in seeds if cv in body["curves"]]
        if not mine:
            continue
        curves, points = am.layer_chain(topo, mine, body["curves"])
        sizes = {}
        for p in points:
            i = int(np.argmin(np.hypot(*(xy - topo["points"][p]).T)))
            if np.isfinite(nodal[i]):
                sizes[p] = first * float(nodal[i])
        contact_points = {p for cv in mine for p in topo["curves"].get(cv, ()) if p in sizes}
        if not contact_points:
            continue
        out.append({"curves": curves, "sizes": sizes, "depth": depth * min(sizes[p] for p in contact_points)})
    return out


def write_size_view(path, result, hnew, msh=None, uniform_contact=False):
    """A gmsh post-processing view (.pos) of the sizes at the corners of the current mesh: the
    smallest of the sizes wanted by the elements around each node, with ghost cells beyond the
    boundary (k2d.adapt_mesh.boundary_ghosts); with `uniform_contact` one size along each curved
    contact zone (contact_spacing), and surface A the finer side (interface_sizes).  With `msh`,
    the .msh the result was computed on, one view per body (the cells connected through shared
    nodes): the ghosts of one body
    reach into the gap of a contact, and with one view of everything gmsh took either body's
    size there (a Q8 Hertz model's cylinder took the coarser sizes of the half-plane and stopped
    with E-SEGMENT-SIDE); gmsh_mesh meshes each body's inside from its own view and the curves
    from the smallest size of the views.  Returns the entity lists [(surfaces, curves, points)] of the views, in
    their order in the file, or None for one view of everything (no `msh`, or its bodies do not
    match the result's)."""
    m = result.mesh
    xy = m.coordinates
    nn = m.element_nodes
    nodal = view_sizes(result, hnew, uniform_contact)
    cells = [m.connectivity[e, :3 if nn[e] == 3 else 4] - 1 for e in range(len(nn))]
    bodies = am.msh_bodies(msh) if msh else None
    which = am.match_bodies(xy, cells, bodies) if bodies else None
    groups = [np.arange(len(cells))] if which is None else [np.where(which == b)[0] for b in range(len(bodies))]

    def point(i):
        return "%.10g,%.10g,0" % (xy[i, 0], xy[i, 1])
    with open(path, "w") as f:
        for g, sel in enumerate(groups):
            f.write('View "size%d" {\n' % g)
            for e in sel:
                c = cells[e]
                f.write("S%s(%s){%s};\n" % ("T" if len(c) == 3 else "Q", ",".join(point(i) for i in c),
                                            ",".join("%.6g" % nodal[i] for i in c)))
            for corners, sizes in am.boundary_ghosts(xy, [cells[e] for e in sel], nodal):
                f.write("SQ(%s){%s};\n" % (",".join("%.10g,%.10g,0" % (x, y) for x, y in corners),
                                           ",".join("%.6g" % v for v in sizes)))
            f.write("};\n")
    if which is None:
        return None
    return [(b["surfaces"], b["curves"], b["points"]) for b in bodies]


def gmsh_mesh(geo, msh, log, pos=None, factor=None, gmsh="gmsh", restrict=None, layers=None):
    """Mesh `geo` into `msh` (format 4.1) with the sizes of the view `pos` as the only size
    field, or with the .geo's own sizes times `factor`; returns the CPU seconds of gmsh.  With
    `restrict` (write_size_view's entity lists) `pos` holds one view per body: the inside of a
    body's surfaces is meshed from its own view, the curves and points from the smallest size
    of the views that cover them.  With `layers` (contact_layers) boundary layers of
    quadrilaterals along those curves; should gmsh fail with them (it crashed with other 2-D
    algorithms on Hertz's .geo) the mesh is made again without them and `layers` emptied, so
    the caller sees that the mesh has none."""
    if shutil.which(gmsh) is None:
        raise AdaptError("gmsh is needed to remesh %s (Debian package gmsh)" % geo)
    wrapper = os.path.splitext(msh)[0] + "_mesh.geo"
    lines = ['Include "%s";' % os.path.abspath(geo)] + QUADRATIC_ALL_QUADS
    if factor is not None:
        lines.append("Mesh.MeshSizeFactor = %.10g;" % factor)
    if pos is not None:
        lines += ["Mesh.MeshSizeFromPoints = 0;", "Mesh.MeshSizeFromCurvature = 0;",
                  "Mesh.MeshSizeExtendFromBoundary = 0;", 'Merge "%s";' % os.path.abspath(pos)]
        if not restrict:
            lines += ["Field[99001] = PostView;", "Field[99001].ViewIndex = PostProcessing.NbViews - 1;",
                      "Background Field = 99001;"]
        else:
            # the inside of each body's surfaces from its own view only; its curves and points
            # (the boundaries, contact surfaces among them) from every view that covers them, the
            # smallest size winning: the sides of a contact may take each other's finer size (the
            # half-plane under a punch's edge the punch's), never a coarser one
            mins = []
            all_curves = sorted({c for _s, cs, _p in restrict for c in cs})
            all_points = sorted({q for _s, _c, ps in restrict for q in ps})
            for k, (surfaces, _curves, _points) in enumerate(restrict):
                fv, fr, fb = 99001 + 3 * k, 99002 + 3 * k, 99003 + 3 * k
                lines += ["Field[%d] = PostView;" % fv,
                          "Field[%d].ViewIndex = PostProcessing.NbViews - %d;" % (fv, len(restrict) - k),
                          "Field[%d] = Restrict;" % fr, "Field[%d].InField = %d;" % (fr, fv),
                          "Field[%d].SurfacesList = {%s};" % (fr, ", ".join(map(str, surfaces))),
                          "Field[%d] = Restrict;" % fb, "Field[%d].InField = %d;" % (fb, fv),
                          "Field[%d].CurvesList = {%s};" % (fb, ", ".join(map(str, all_curves))),
                          "Field[%d].PointsList = {%s};" % (fb, ", ".join(map(str, all_points)))]
                mins += [fr, fb]
            lines += ["Field[99000] = Min;", "Field[99000].FieldsList = {%s};" % ", ".join(map(str, mins)),
                      "Background Field = 99000;"]
    cpu = 0.0
    if layers:
        with open(wrapper, "w") as f:
            f.write("\n".join(lines + am.layer_lines(layers)) + "\n")
        if os.path.isfile(msh):
            os.remove(msh)
        rc, wall, cpu = run_cpu([gmsh, "-2", "-format", "msh41", wrapper, "-o", msh], log)
        if rc == 0 and os.path.isfile(msh):
            return cpu + _check_types(msh, geo)
        with open(log, "a") as f:
            f.write("\n(the contact layer failed, exit code %d: meshed again without it)\n" % rc)
        layers.clear()
        os.rename(log, log + ".layer")
    with open(wrapper, "w") as f:
        f.write("\n".join(lines) + "\n")
    rc, wall, cpu1 = run_cpu([gmsh, "-2", "-format", "msh41", wrapper, "-o", msh], log)
    cpu += cpu1
    if rc != 0 or not os.path.isfile(msh):
        raise AdaptError("gmsh failed on %s (exit code %d; its output: %s)" % (wrapper, rc, log))
    return cpu + _check_types(msh, geo)


def _check_types(msh, geo):
    """0.0, or AdaptError when gmsh made elements of `msh` the program does not read."""
    bad = {t: n for t, n in msh_element_types(msh).items() if t not in MSH_SURFACE_TYPES_READ}
    if bad:
        what = ", ".join("%d elements of gmsh type %d" % (n, t) for t, n in sorted(bad.items()))
        raise AdaptError("%s: gmsh made %s from %s, which kontakt2d does not read (it reads 3- and "
                         "4-node, 8- and 9-node elements; docs/adaptivity.md, \"Quadratic meshes\")"
                         % (msh, what, geo))
    return 0.0


# gmsh's 2-D element types kontakt2d reads: 3-node triangle, 4-node quadrilateral, 8- and 9-node
# quadrilaterals (src/io/gmsh_reader.f90); a 6-node triangle (type 9) is not among them
MSH_SURFACE_TYPES_READ = {2, 3, 16, 10}
# Lines added after the .geo: a quadratic mesh is made all quadrilaterals, gmsh's blossom
# recombination of everything with the full-quad option (Mesh.RecombinationAlgorithm = 3),
# whatever the .geo asks; otherwise blossom leaves a few triangles on graded meshes, which second
# order makes 6-node triangles.  A linear mesh keeps the .geo's own choices.
QUADRATIC_ALL_QUADS = ["If (Mesh.ElementOrder > 1)", "  Mesh.RecombineAll = 1;",
                       "  Mesh.RecombinationAlgorithm = 3;", "EndIf"]


def msh_element_types(path):
    """{gmsh element type: count} of the 2-D elements of a .msh file (format 4.1, ASCII)."""
    out = {}
    with open(path) as f:
        for line in f:
            if line.strip() == "$Elements":
                nblocks = int(f.readline().split()[0])
                for _ in range(nblocks):
                    dim, _tag, ety, n = (int(v) for v in f.readline().split())
                    for _ in range(n):
                        f.readline()
                    if dim == 2:
                        out[ety] = out.get(ety, 0) + n
                break
    return out


# ------------------------------------------------------------------------------- the drivers
MAX_GROWTH = 4.0      # elements of an adaptive mesh over the last one's, at most (predicted)


def adapt_mesh_deck(deck, target, max_dofs, out, exe, uniform=False, max_steps=8, log=print,
                    max_growth=MAX_GROWTH, singular=True, uniform_contact=False, contact_layer=False):
    """Remesh the .geo of a MESH deck until the estimated error is below `target` or the next
    mesh would exceed `max_dofs`: adaptively from the indicators (a size field; each mesh at most
    about `max_growth` times the elements of the last, None: no limit; with `singular` the
    contact's singular edges refined at their own rate, singular_rates; with `uniform_contact` a
    uniform spacing along curved contact zones, contact_spacing; with `contact_layer` a boundary
    layer of quadrilaterals along them, contact_layers), or with uniform=True by halving the
    .geo's sizes at each step.  Returns the rows of the table."""
    kind, msh, geo = deck_kind(deck)
    if kind != "mesh" or geo is None:
        raise AdaptError("%s: a MESH deck with the .geo of its mesh beside it is needed for remeshing" % deck)
    mats = deck_materials(deck)
    name = os.path.splitext(os.path.basename(deck))[0]
    tag = "uniform" if uniform else "adaptive"
    wdir = os.path.join(out, "steps_" + tag)
    os.makedirs(wdir, exist_ok=True)
    with open(deck) as f:
        text = f.read()
    rows, pos, restrict, layers = [], None, None, []
    r = hnew = r_msh = None         # the last result, its new sizes and its .msh (from step 1 on)
    for k in range(max_steps):
        base = os.path.join(wdir, "%s_%02d" % (name, k))
        cpu_mesh = gmsh_mesh(geo, base + ".msh", base + "_gmsh.log", pos=pos,
                             factor=0.5 ** k if uniform else None, restrict=restrict, layers=layers)
        # the predicted size of a mesh is approximate: one that came out beyond the budget, or
        # beyond 1.25 times the growth allowed, is made again with all sizes grown by the excess
        # (at most four times)
        for _ in range(4):
            dofs = 2 * msh_nodes(base + ".msh")
            if pos is None:
                break
            want, limit = math.inf, math.inf          # the DOFs aimed at, and allowed
            if max_dofs:
                want, limit = max_dofs / 1.05 ** 2, max_dofs
            if max_growth and 1.25 * max_growth * rows[-1]["dofs"] < limit:
                want, limit = max_growth * rows[-1]["dofs"], 1.25 * max_growth * rows[-1]["dofs"]
            if dofs <= limit:
                break
            hnew *= math.sqrt(dofs / want)
            restrict = write_size_view(pos, r, hnew, msh=r_msh, uniform_contact=uniform_contact)
            if contact_layer:
                layers = contact_layers(r, view_sizes(r, hnew, uniform_contact), r_msh)
            cpu_mesh += gmsh_mesh(geo, base + ".msh", base + "_gmsh.log", pos=pos, restrict=restrict,
                                  layers=layers)
        if max_dofs and 2 * msh_nodes(base + ".msh") > max_dofs:
            rows[-1]["stop"] = "budget"
            break
        with open(base + ".dat", "w") as f:
            f.write(with_mesh_file(text, os.path.basename(base + ".msh")))
        t0 = time.process_time()
        r, cpu, rc = solve(exe, base + ".dat", base + ".h5", base + ".lis")
        eta, est, source = indicator(r, mats)
        row = _row(k, r, est, source, cpu, cpu_mesh + time.process_time() - t0, rc)
        row["method"] = tag
        row["h5"] = base + ".h5"
        shape = am.quality(base + ".msh", limit=am.ANGLE_LIMIT)
        row["max_angle"] = max(v for v in (shape["max_angle_quad"], shape["max_angle_tri"]) if math.isfinite(v))
        row["quads_over_limit"] = shape["over_limit"]
        row["layer_curves"] = sum(len(lay["curves"]) for lay in layers)
        rows.append(row)
        log("  %s step %d: %d DOFs, estimated error %.4g (%s), CPU %.2f s; largest angle %.1f deg%s"
            % (tag, k, row["dofs"], est, source, cpu, row["max_angle"],
               ", %d quadrilaterals beyond %g deg" % (shape["over_limit"], am.ANGLE_LIMIT)
               if shape["over_limit"] else ""))
        if est <= target:
            break
        if uniform:
            if 4 * row["dofs"] > max_dofs:
                row["stop"] = "budget"
                break
            continue
        h, p = element_sizes(r)
        max_el = max_dofs / row["dofs"] * len(h) if max_dofs else None
        if max_el and len(h) >= 0.8 * max_el:
            row["stop"] = "budget"          # this mesh already has the DOFs allowed
            break
        t0 = time.process_time()
        rate = singular_rates(r) if singular else None
        row["singular_elements"] = int(np.count_nonzero(rate)) if rate is not None else 0
        hnew, n_new = new_sizes(eta, h, p, target, max_el, rate=rate, max_growth=max_growth)
        hnew, row["traction_limited"] = limit_by_tractions(r, hnew, h, target)
        pos = base + "_size.pos"
        r_msh = base + ".msh"
        restrict = write_size_view(pos, r, hnew, msh=r_msh, uniform_contact=uniform_contact)
        if contact_layer:
            layers = contact_layers(r, view_sizes(r, hnew, uniform_contact), r_msh)
        row["cpu_mesh"] += time.process_time() - t0
    return rows


def refine_card_deck(deck, target, max_dofs, out, exe, min_levels=3, max_levels=6, log=print):
    """Split every element of a card deck into four, level after level, until the estimated
    error is below `target` (after at least `min_levels` meshes, for Richardson) or the next
    level would exceed `max_dofs`.  Returns the rows of the table."""
    from .refine import RefineError, read_card_deck, refine_deck
    try:
        read_card_deck(deck)        # what the splitting cannot take is refused before any run
    except RefineError as e:
        raise AdaptError(str(e))
    mats = deck_materials(deck)
    name = os.path.splitext(os.path.basename(deck))[0]
    wdir = os.path.join(out, "steps_uniform")
    os.makedirs(wdir, exist_ok=True)
    rows = []
    src = deck
    for k in range(max_levels):
        base = os.path.join(wdir, "%s_%02d" % (name, k))
        t0 = time.process_time()
        if k == 0:
            shutil.copyfile(deck, base + ".dat")
        else:
            try:
                text = refine_deck(read_card_deck(src), "level %d of the uniform refinement of %s by tools/adapt.py: "
                                   "every element of level %d split into 4" % (k, os.path.basename(deck), k - 1))
            except RefineError as e:
                raise AdaptError(str(e))
            with open(base + ".dat", "w") as f:
                f.write(text)
        src = base + ".dat"
        t_refine = time.process_time() - t0
        r, cpu, rc = solve(exe, src, base + ".h5", base + ".lis")
        t0 = time.process_time()
        eta, est, source = indicator(r, mats)
        row = _row(k, r, est, source, cpu, t_refine + time.process_time() - t0, rc)
        row["method"] = "uniform"
        row["split"] = True         # every element split into four: equal steps h, h/2, h/4
        row["h5"] = base + ".h5"
        rows.append(row)
        log("  level %d: %d DOFs, estimated error %.4g (%s), CPU %.2f s" % (k, row["dofs"], est, source, cpu))
        if k + 1 >= min_levels and est <= target:
            break
        if 4 * row["dofs"] > max_dofs:
            row["stop"] = "budget"
            break
    return rows


def richardson_table(rows):
    """Richardson on the last three rows (meshes h, h/2, h/4): {output: richardson(...)}."""
    if len(rows) < 3:
        return {}
    a, b, c = rows[-3:]
    return {k: richardson(a[k], b[k], c[k]) for k, _ in OUTPUTS}


# ------------------------------------------------------------------------------- the report
COLUMNS = ["method", "step", "elements", "dofs", "estimated_error", "source", "cpu_solve", "cpu_mesh",
           "cpu_cumulative", "peak_pressure", "width", "approach", "von_mises", "slip_share", "scheme",
           "law_drift", "residual", "traction_limited", "singular_elements", "max_angle", "quads_over_limit",
           "layer_curves",
           "exit", "not_converging"]


def cumulate(rows):
    """cpu_cumulative: the CPU seconds of every step of the same method up to this one (the
    cost of reaching this mesh: meshing, solving, estimating)."""
    total = {}
    for r in rows:
        total[r["method"]] = total.get(r["method"], 0.0) + r["cpu_solve"] + r["cpu_mesh"]
        r["cpu_cumulative"] = total[r["method"]]
    return rows


def write_tables(rows, rich, out, name, deck, target, max_dofs):
    """<name>_adapt.csv and <name>_adapt.md in `out`; returns the Markdown path."""
    from .tables import markdown_table, write_dict_csv
    flags = convergence_flags(rows)          # also each row's not_converging column
    csv_path = os.path.join(out, name + "_adapt.csv")
    write_dict_csv(csv_path, COLUMNS, rows)
    final = [r for r in rows if r["method"] == rows[0]["method"]][-1]
    reached = final["estimated_error"] <= target
    md = ["# Refinement of %s to an estimated error of %g" % (os.path.basename(deck), target), "",
          "Deck `%s`; budget %d DOFs; the estimate and the key outputs are those of the increment of the "
          "largest strain energy (the last one unless the history unloads; source: %s; "
          "docs/adaptivity.md)." % (os.path.basename(deck), max_dofs, final["source"]), "",
          ("**Reached**: %.4g <= %g with %d DOFs (%s, step %s)." if reached else
           "**Not reached**: %.4g > %g with %d DOFs (%s, step %s): the budget or the step limit ended it.")
          % (final["estimated_error"], target, final["dofs"], final["method"], final["step"]), ""]
    head = ["method", "step", "elements", "DOFs", "est. error", "CPU solve [s]", "CPU mesh+estimate [s]",
            "CPU cumulative [s]", "peak pressure", "width", "approach", "max von Mises", "slip share",
            "law drift"]
    fmt = {"est. error": "%.4g", "CPU solve [s]": "%.2f", "CPU mesh+estimate [s]": "%.2f",
           "CPU cumulative [s]": "%.2f", "peak pressure": "%.5g", "width": "%.5g", "approach": "%.5g",
           "max von Mises": "%.5g", "slip share": "%.3f", "law drift": "%.3g"}
    body = [[r["method"], str(r["step"]), str(r["elements"]), str(r["dofs"]), r["estimated_error"], r["cpu_solve"],
             r["cpu_mesh"], r["cpu_cumulative"], r["peak_pressure"], r["width"], r["approach"], r["von_mises"],
             r["slip_share"], r["law_drift"]] for r in rows]
    md.append(markdown_table("Convergence", head, body, fmt))
    if any(flags.values()):
        md += ["### Key outputs that do not converge", "",
               "Over the last three meshes of the method, the successive differences of these outputs do not "
               "decrease (per unit of log(DOFs) on remeshed sequences; the observed order is <= 0): a value at a "
               "singular point (a stress at a punch's edge or a re-entrant corner grows without limit under "
               "refinement) or one that the refinement does not settle. Its last value is no converged result and "
               "no extrapolation is made of it.", ""]
        for method, fl in flags.items():
            for label, note, vals in fl:
                md.append("* %s, %s: **%s**; the last three meshes: %s" % (
                    method, label, note, ", ".join("%.6g" % v for v in vals)))
        md.append("")
    if rich:
        rb = []
        for k, label in OUTPUTS:
            v = rich[k]
            rb.append([label, final[k], v["order"], v["extrapolated"], v["error"], v["gci"], v["note"]])
        md.append(markdown_table("Richardson extrapolation of the last three meshes (h, h/2, h/4)",
                                 ["output", "finest", "observed order p", "extrapolated", "error of the finest",
                                  "GCI", "note"], rb, {"finest": "%.6g", "observed order p": "%.2f",
                                                       "extrapolated": "%.6g", "error of the finest": "%.3g",
                                                       "GCI": "%.3g"}))
        md.append("p = log2((f1 - f2)/(f2 - f3)), f_ext = f3 + (f3 - f2)/(2^p - 1) (Richardson 1911); GCI = "
                  "1.25 |f3 - f2| / |f3| / (2^p - 1), the grid convergence index (Roache 1998, relative); "
                  "a sequence that oscillates or does not converge is not in the asymptotic range, and its error "
                  "is Roache's safety-factor estimate 3 |f3 - f2| (its GCI that relative to |f3|).\n")
    scheme = final.get("scheme") or ""
    if scheme:
        md += ["### Increment size", "",
               "Scheme %s; the largest law drift over the increments of the final mesh is %.3g (the normal spring "
               "forces' distance from the interface law, relative to the largest force)."
               % (scheme, final["law_drift"]),
               ("The explicit (INCREMENTAL) scheme drifts off the law by about 1/N for N loading increments: "
                "this drift is its increment-size error, and more increments reduce it."
                if scheme.upper() in ("EXPLICIT", "INCREMENTAL") else
                "NEWTON and MODIFIED return the forces to the laws at every increment end, so the drift is "
                "round-off: the increment size does not enter the end states' law error (a path-dependent "
                "friction history between the ends is not estimated here)."), ""]
    path = os.path.join(out, name + "_adapt.md")
    with open(path, "w") as f:
        f.write("\n".join(md) + "\n")
    return path


def plot_convergence(rows, png, target=None):
    """Estimated error against DOFs and against cumulative CPU seconds, one line per method."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for method in sorted({r["method"] for r in rows}):
        rs = [r for r in rows if r["method"] == method]
        e = [r["estimated_error"] for r in rs]
        ax[0].loglog([r["dofs"] for r in rs], e, "o-", label=method)
        ax[1].loglog([max(r["cpu_cumulative"], 1e-3) for r in rs], e, "o-", label=method)
    for a, xl in zip(ax, ["DOFs", "CPU seconds (cumulative: meshing, solving, estimating)"]):
        if target:
            a.axhline(target, color="k", lw=0.8, ls="--", label="target")
        a.set_xlabel(xl)
        a.set_ylabel("estimated relative error (energy norm)")
        a.grid(True, which="both", alpha=0.3)
        a.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return png


def publish(h5, out, name):
    """The final result as tools/run.sh leaves it: out/<name>.h5 with its .xdmf (naming the
    copied file) and .lis; returns the path of the .h5."""
    src = os.path.splitext(h5)[0]
    dst = os.path.join(out, name)
    shutil.copyfile(h5, dst + ".h5")
    if os.path.isfile(src + ".lis"):
        shutil.copyfile(src + ".lis", dst + ".lis")
    if os.path.isfile(src + ".xdmf"):
        with open(src + ".xdmf") as f:
            text = f.read()
        with open(dst + ".xdmf", "w") as f:
            f.write(text.replace(os.path.basename(h5), name + ".h5"))
    return dst + ".h5"
