"""The history of a run with contact: what the increments of a result file say together.

    from k2d.results import Result
    from k2d.history import History
    h = History(Result("punch.h5"))
    h.lam                     # (nsteps) the scalar load factor (the case whose factor varies most)
    h.direction               # (nsteps) +1 loading, -1 unloading, 0 holding (sign of the change of lam)
    h.kind                    # (nsteps) what changes in the step: "loading", "unloading" (the normal
                              # load), "tangential +", "tangential -" (the tangential displacement
                              # under a held normal load), "holding"
    h.approach                # (nsteps) relative normal displacement of the bodies [length]
    h.figures(k)              # dict of the figures of step k: peak pressure and where, width, area,
                              # total normal and tangential force, slipping pairs, law drift, ...
    h.stages()                # [(first, last) step indices] of the monotone stages of the load history

Definitions (docs/results-format.md names the datasets; docs/history.md these figures):

* approach: the relative displacement of the two bodies along the mean pair normal n (from
  body B into body A), measured between the points of each body farthest from the interface
  along n (the far face of each body: its nodes within 1e-6 of the model size from the
  extreme), delta = mean(u_B . n) - mean(u_A . n), positive when the bodies approach.  A
  rigid body is its reference node.  `approach_nodes=(a, b)` measures it between two nodes
  instead (deck numbers).
* contact width: the extent of the closed pairs along the interface coordinate (the pairs'
  coordinate of largest spread); contact area: the sum of the lumped areas A_j of the closed
  pairs (ring areas in axisymmetry).
* slip zone: the pairs in slip (tangential state 2) that carry a normal force (F_n above
  1e-12 of the largest pair force of the run: a pair at zero force holds nothing tangentially
  and is not "slipping"); its share of the closed area.
* what changes in a step (h.kind): of the total normal force and the mean u_T of the closed
  pairs, the one whose change relative to its largest magnitude over the run (for u_T: the
  largest of u_T, closure and approach) is larger and above 1e-6: the normal load (loading /
  unloading: the sign of the change of lam, else of the force) or the tangential displacement
  (tangential + / -); when neither changes, the sign of the change of lam (a load change with
  the pairs open or at zero force), else holding.  The
  unloaded origin (zero load, zero displacement) is the state before the first increment.

Reads the results through k2d.results only.
"""
import numpy as np

from k2d import laws

__all__ = ["STATE_NAMES", "KIND_STYLE", "History", "law_curves", "unit_labels"]

STATE_NAMES = {0: "open", 1: "loading", 2: "unloading"}
# line style of a step by what changes in it (history plots)
KIND_STYLE = {"loading": "-", "unloading": "--", "tangential +": "-", "tangential -": "-.", "holding": ":"}


class History:
    """The figures of every kept increment of a result file with contact."""

    def __init__(self, result, approach_nodes=None):
        if result.contact is None:
            raise ValueError("%s: no contact pairs, no history of the interface" % result.path)
        if not result.steps:
            raise ValueError("%s: no completed increment" % result.path)
        self.result = result
        self.steps = result.steps
        c = result.contact
        self.npair = c.npair
        lf = result.load_factors()
        self.case = int(np.argmax(np.ptp(lf, axis=0))) if lf.shape[1] > 1 else 0
        self.lam = lf[:, self.case]
        dl = np.diff(np.concatenate([[0.0], self.lam]))
        tol = 1e-12 * max(1.0, np.max(np.abs(self.lam)))
        self.direction = np.where(dl > tol, 1, np.where(dl < -tol, -1, 0))
        self.position = c.position
        self.area = c.area
        self.axis = 0 if np.ptp(self.position[:, 0]) >= np.ptp(self.position[:, 1]) else 1
        self.coord = self.position[:, self.axis]
        n = np.mean(c.normal, axis=0)
        self.normal = n / np.linalg.norm(n)
        self.ntype = int(result.attrs.get("ntype", 1))
        self._fields = [s.contact_all() for s in self.steps]
        fn_all = np.array([f["force_normal"] for f in self._fields])
        # a pair "carries" a normal force above round-off of the run's largest pair force
        self.fn_floor = 1e-12 * max(float(np.max(np.abs(fn_all))) if fn_all.size else 0.0, np.finfo(float).tiny)
        self._far = self._far_points(approach_nodes)
        self.approach = np.array([self._approach(s) for s in self.steps])
        self.kind = self._kinds()

    # ---- the bodies and their far points
    def _bodies(self):
        """Body of every node (0-based labels): connected components of the elements."""
        conn = self.result.mesh.connectivity
        nn = self.result.mesh.element_nodes
        npoin = self.result.mesh.coordinates.shape[0]
        parent = np.arange(npoin)

        def find(i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i
        for e, k in zip(conn, nn):
            nodes = e[:k] - 1
            r0 = find(nodes[0])
            for j in nodes[1:]:
                r = find(j)
                if r != r0:
                    parent[r] = r0
        return np.array([find(i) for i in range(npoin)])

    def _far_points(self, approach_nodes):
        """(nodes of A, nodes of B) whose displacements define the approach (0-based)."""
        if approach_nodes is not None:
            a, b = approach_nodes
            npoin = self.result.mesh.coordinates.shape[0]
            for k in (a, b):
                if not 1 <= k <= npoin:
                    raise ValueError("approach node %d does not exist (nodes 1..%d)" % (k, npoin))
            return np.array([a - 1]), np.array([b - 1])
        c = self.result.contact
        xy = self.result.mesh.coordinates
        body = self._bodies()
        size = max(np.ptp(xy[:, 0]), np.ptp(xy[:, 1]))
        s = xy @ self.normal

        def far(nodes, sign):
            members = np.isin(body, np.unique(body[nodes]))
            v = sign * s[members]
            idx = np.where(members)[0]
            return idx[v >= v.max() - 1e-6 * size]
        far_a = far(c.node_a - 1, +1.0)
        kind = getattr(c, "kind", np.zeros(self.npair, dtype=int))
        if np.all(kind == 2):
            far_b = np.unique(c.master_nodes[:, 0] - 1)     # the rigid body's reference node
        else:
            far_b = far(c.node_b[kind != 2] - 1, -1.0)
        return far_a, far_b

    def _approach(self, step):
        u = step.field("displacement")
        ua = np.mean(u[self._far[0]] @ self.normal)
        ub = np.mean(u[self._far[1]] @ self.normal)
        return float(ub - ua)

    def _kinds(self):
        """What changes in every step (see the module's text)."""
        fn = np.array([0.0] + [float(f["force_normal"].sum()) for f in self._fields])
        ut = np.array([0.0] + [self.mean_slip(k) for k in range(len(self.steps))])
        fn_max = max(np.max(np.abs(fn)), np.finfo(float).tiny)
        # u_T is measured against the run's displacements at the interface (the largest of u_T,
        # the closures and the approach): in a purely normal history u_T is round-off
        closure = max(float(np.max(np.abs(f["closure"]))) if f["closure"].size else 0.0 for f in self._fields)
        ut_max = max(np.max(np.abs(ut)), closure, float(np.max(np.abs(self.approach))))
        ut_max = ut_max if ut_max > 0 else np.inf
        out = []
        for k in range(len(self.steps)):
            rel_n, rel_t = abs(fn[k + 1] - fn[k]) / fn_max, abs(ut[k + 1] - ut[k]) / ut_max
            if rel_n > 1e-6 and rel_n >= rel_t:
                d = self.direction[k] or (1 if fn[k + 1] > fn[k] else -1)
                out.append("loading" if d > 0 else "unloading")
            elif rel_t > 1e-6:
                out.append("tangential +" if ut[k + 1] > ut[k] else "tangential -")
            elif self.direction[k]:
                # the load changes but not the interface's forces (pairs open at zero force)
                out.append("loading" if self.direction[k] > 0 else "unloading")
            else:
                out.append("holding")
        return np.array(out, dtype=object)

    def carrying(self, k):
        """The closed pairs of step index k that carry a normal force above round-off."""
        f = self._fields[k]
        return (f["normal_state"] > 0) & (f["force_normal"] > self.fn_floor)

    def mean_slip(self, k, iface=None):
        """The area-weighted mean tangential displacement u_T of the closed pairs of step index k
        (of interface `iface`, 1-based, or of all), 0 when none is closed."""
        f = self._fields[k]
        sel = f["normal_state"] > 0
        if iface is not None:
            sel &= self.result.contact.interface == iface
        a = self.area[sel]
        return float(np.sum(a * f["slip"][sel]) / a.sum()) if a.sum() > 0 else 0.0

    def tangential_totals(self, iface=1):
        """(sum F_T, mean u_T) of interface `iface` (1-based) over the kept steps, the unloaded
        origin first (zeros): the program's attributes tangential_force_total and slip_mean where
        the file has them, else computed here from force_tangential, slip, area and normal_state
        (the same definitions).  Returns (force, slip, "file" or "computed")."""
        force, slip, src = [0.0], [0.0], "file"
        sel = self.result.contact.interface == iface
        for k, s in enumerate(self.steps):
            a = s.contact_attrs
            if "tangential_force_total" in a and "slip_mean" in a and len(a["slip_mean"]) >= iface:
                force.append(float(a["tangential_force_total"][iface - 1]))
                slip.append(float(a["slip_mean"][iface - 1]))
            else:
                src = "computed"
                force.append(float(self._fields[k]["force_tangential"][sel].sum()))
                slip.append(self.mean_slip(k, iface))
        return np.array(force), np.array(slip), src

    # ---- per-step figures
    def field(self, k, name):
        """A contact quantity of step index k (0-based over the kept steps)."""
        return self._fields[k][name]

    def figures(self, k):
        """The figures of step index k."""
        f = self._fields[k]
        p = f["pressure"]
        closed = f["normal_state"] > 0
        slip = self.carrying(k) & (f["tangential_state"] == 2)
        j = int(np.argmax(np.where(closed, p, -np.inf))) if closed.any() else -1
        cc = self.coord[closed]
        area_closed = float(self.area[closed].sum())
        residual = np.where(closed & (f["normal_state"] == 2) | (~closed & (f["closure"] > 0)), f["closure"], 0.0)
        return {
            "step": self.steps[k].number,
            "load_factor": float(self.lam[k]),
            "direction": int(self.direction[k]),
            "kind": str(self.kind[k]),
            "mean_slip": self.mean_slip(k),
            "max_slip": float(f["slip"][np.argmax(np.abs(f["slip"]))]) if f["slip"].size else 0.0,
            "max_irreversible": float(np.max(np.abs(f["slip_irreversible"]))) if "slip_irreversible" in f else 0.0,
            "peak_pressure": float(p[j]) if j >= 0 else 0.0,
            "peak_at": tuple(self.position[j]) if j >= 0 else (np.nan, np.nan),
            "closed": int(closed.sum()),
            "width": float(np.ptp(cc)) if closed.sum() > 1 else 0.0,
            "area": area_closed,
            "approach": float(self.approach[k]),
            "normal_force": float(f["force_normal"].sum()),
            "tangential_force": float(f["force_tangential"].sum()),
            "slipping": int(slip.sum()),
            "slip_share": float(self.area[slip].sum() / area_closed) if area_closed > 0 else 0.0,
            "max_closure": float(f["closure"].max()),
            "residual_closure": float(residual.max()) if residual.size else 0.0,
            "law_drift": float(self.steps[k].attrs.get("law_drift", np.nan)),
            "solutions": int(self.steps[k].attrs.get("iterations", 0)),
        }

    def stages(self):
        """(first, last) step indices of the monotone stages: a new stage starts where what
        changes turns (normal loading to unloading or back, the tangential displacement
        reversed, normal to tangential; holding joins the stage before)."""
        out, start, cur = [], 0, None
        for k in range(len(self.steps)):
            d = self.kind[k]
            if d == "holding":
                continue
            if cur is not None and d != cur:
                out.append((start, k - 1))
                start = k
            cur = d
        out.append((start, len(self.steps) - 1))
        return out

    def stage_name(self, first, last):
        """loading, unloading (the normal load), tangential loading (the first tangential stage
        from rest), tangential reversal (a tangential stage after one of the other sign), or
        holding (nothing changes)."""
        d = [v for v in self.kind[first:last + 1] if v != "holding"]
        if not d:
            return "holding"
        if not d[0].startswith("tangential"):
            return d[0]
        before = [v for v in self.kind[:first] if v.startswith("tangential")]
        sign = d[0][-1]
        if before and before[-1] != d[0]:
            return "tangential reversal (%s)" % sign
        return "tangential loading (%s)" % sign

    # ---- choices for the plots
    def default_pairs(self):
        """The most and the least loaded pair: largest and smallest peak pressure over the run
        among the pairs that closed (the least loaded that carried any pressure)."""
        peak = np.max([f["pressure"] * (f["normal_state"] > 0) for f in self._fields], axis=0)
        loaded = np.where(peak > 0)[0]
        if loaded.size == 0:
            return []
        most = int(loaded[np.argmax(peak[loaded])])
        least = int(loaded[np.argmin(peak[loaded])])
        return [most] if most == least else [most, least]

    def default_increments(self, nmax=6):
        """Step indices to draw along the interface: the turning points of the load history,
        the peak and the last step, filled up with evenly spaced steps to about nmax."""
        n = len(self.steps)
        pick = {n - 1, int(np.argmax(self.lam))}
        for first, last in self.stages():
            pick.add(last)
        spare = max(nmax - len(pick), 0)
        if spare:
            pick.update(int(round(v)) for v in np.linspace(0, n - 1, spare + 2)[1:-1])
        return sorted(pick)

    def index_of(self, number):
        """Step index of increment `number` (ValueError if the file does not keep it)."""
        for k, s in enumerate(self.steps):
            if s.number == number:
                return k
        raise ValueError("%s: increment %d is not in the file (kept: %s)"
                         % (self.result.path, number, ", ".join(str(s.number) for s in self.steps)))


def law_curves(interface, pa_ua=None, pmax=1.0, n=200):
    """The virgin curve (u = cn p^m) and, for each reversal point (u_A, p_A), the unloading
    curve through it (u = u_A - cn2 (p_A^m2 - p^m2), SPEC D8, through the origin beyond p*), in the model units of
    /contact/interface_K (normal_model = (cn, m, cn2, m2)).  Returns [(label, u, p)]."""
    cn, m, cn2, m2 = (float(v) for v in np.atleast_1d(interface["normal_model"])[:4])
    p = np.linspace(0.0, pmax, n)
    out = [("virgin curve u = c_n p^m", laws.virgin_closure(p, cn, m), p)]
    for ua, pa in pa_ua or []:
        q = np.linspace(0.0, pa, n)
        out.append(("unloading from (%.3g, %.3g)" % (ua, pa), laws.unloading_closure(q, ua, pa, cn2, m2), q))
    return out


def unit_labels(result):
    """Axis labels of length, stress and force from the deck's unit convention: with the
    roughness constants in the literature's units (UNITS KGF_UM) the model is in mm and N/mm²
    (docs/deck-format.md, UNITS); otherwise the model's own units, which the file does not
    name."""
    units = ""
    if result.contact is not None and result.contact.interfaces:
        units = str(result.contact.interfaces[0].get("units", ""))
    ntype = int(result.attrs.get("ntype", 1))
    if units.upper().startswith("KGF_UM"):
        force = {1: "N", 2: "N per mm of thickness", 3: "N (whole ring)"}.get(ntype, "N")
        return {"length": "mm", "stress": "N/mm²", "force": force}
    force = {2: "force per unit thickness", 3: "force (whole ring)"}.get(ntype, "force")
    return {"length": "model length", "stress": "model stress", "force": "model " + force}
