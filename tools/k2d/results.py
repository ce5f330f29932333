"""The one Python reader of Kontakt2D's result file (docs/results-format.md).

No other Python file of the project knows the HDF5 group, dataset or attribute
names: scripts and tests read results through this module.

    from k2d.results import Result
    r = Result("punch_5_1.h5")
    r.status, r.completed            # 'completed', increments_completed
    r.attrs["analysis_type"]         # root attributes (strings decoded)
    r.mesh.coordinates               # (npoin, 2); also connectivity, element_nodes, material, ...
    r.contact is None                # a deck without contact
    r.contact.position, r.contact.area, r.contact.normal      # the contact definition
    r.contact.interfaces[0]["law"]   # each interface's attributes
    for s in r.steps:                # the increment groups, in the order of their numbers
        s.number, s.load_factor, s.attrs["iterations"]
        s.field("displacement")      # (npoin, 2); stress_nodal, stress_gauss, reaction
        s.error_indicator, s.estimated_error   # (nelem) per element, and the model's: fractions
        s.contact_zone                # {"zone_width": (niface), "zone_pairs": (niface)} or {}
        s.contact("pressure")        # (npair); closure, slip, normal_state, ...
        s.contact_attrs              # attributes of the increment's contact group (per interface)
    r.step(12)                       # the group of increment 12 (KeyError if not kept)
    r.last                           # the last kept increment
    r.history("law_drift")           # an increment attribute over r.steps (NaN where absent)
    r.cycles                         # the group /cycles as a dict of arrays ({} when absent)
    r.summary                        # the group /summary (the listing's closing summary) as a dict
    dataset("x.h5", "/mesh/cells_quad4")   # one dataset by its path (the XDMF sidecar names them)
    first_nonfinite("x.h5")          # the first dataset or attribute with a NaN or an infinity (None: none)
    audit("x.h5")                    # status, increments_completed, (group, readable, converged): a run cut short

Per-increment datasets are read when asked for (a result file may hold
hundreds of increments); the file is opened for each read and closed again,
so a Result can be kept while the program writes more.
"""
import h5py
import numpy as np

__all__ = ["ContactDefinition", "Step", "Result", "dataset", "first_nonfinite", "audit"]


def _text(v):
    """An attribute value as Python: strings decoded, 1-element arrays kept as arrays."""
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.dtype.kind in "SO":
        return [x.decode() if isinstance(x, bytes) else str(x) for x in v.ravel()]
    if isinstance(v, np.generic):
        return v.item()
    return v


def _attrs(obj):
    return {k: _text(v) for k, v in obj.attrs.items()}


class _Namespace:
    """Datasets of one group as attributes (arrays read at once)."""

    def __init__(self, group):
        self.names = sorted(k for k in group.keys() if isinstance(group[k], h5py.Dataset))
        for k in self.names:
            setattr(self, k, group[k][()])
        self.attrs = _attrs(group)

    def __contains__(self, name):
        return name in self.names


class ContactDefinition(_Namespace):
    """The `/contact` group: one entry per pair, plus the interfaces' laws."""

    def __init__(self, group):
        super().__init__(group)
        self.interfaces = []
        k = 1
        while "interface_%d" % k in group:
            g = group["interface_%d" % k]
            d = _attrs(g)
            for name in g.keys():
                d[name] = g[name][()]
            self.interfaces.append(d)
            k += 1

    @property
    def npair(self):
        return len(self.node_a)


class Step:
    """One increment group of the file."""

    def __init__(self, result, name, attrs):
        self._result = result
        self.name = name
        self.attrs = attrs
        self.number = int(attrs.get("increment", int(name)))
        self.load_factor = np.atleast_1d(np.asarray(attrs["load_factor"], dtype=float))

    def _read(self, sub, name):
        with h5py.File(self._result.path, "r") as f:
            g = f["increments"][self.name]
            if sub:
                if sub not in g:
                    raise KeyError("increment %d has no %s results" % (self.number, sub))
                g = g[sub]
            if name not in g:
                raise KeyError("increment %d has no dataset %r" % (self.number, name))
            return g[name][()]

    def field(self, name):
        """A nodal, Gauss-point or element field: displacement, stress_nodal, stress_gauss, reaction,
        error_indicator."""
        return self._read(None, name)

    @property
    def error_indicator(self):
        """The a posteriori error estimate per element (nelem, in element order): the element's
        energy-norm error relative to the model's norm, sqrt(sum of squares) = estimated_error.
        None in a file written before the estimate existed."""
        try:
            return self._read(None, "error_indicator")
        except KeyError:
            return None

    @property
    def estimated_error(self):
        """The model's relative energy-norm error estimate (a fraction; None if absent)."""
        v = self.attrs.get("estimated_error")
        return None if v is None else float(np.atleast_1d(v)[0])

    @property
    def contact_zone(self):
        """The contact zone of every interface (attributes of the increment's contact group):
        zone_width (2a) and zone_pairs (closed pairs); {} without them."""
        with h5py.File(self._result.path, "r") as f:
            g = f["increments"][self.name]
            if "contact" not in g or "zone_width" not in g["contact"].attrs:
                return {}
            a = g["contact"].attrs
            return {"zone_width": np.atleast_1d(a["zone_width"]), "zone_pairs": np.atleast_1d(a["zone_pairs"])}

    def contact(self, name):
        """A contact quantity per pair: pressure, shear, force_normal, closure, slip, resolution, ..."""
        return self._read("contact", name)

    def contact_names(self):
        """The names of the increment's contact datasets (without reading them)."""
        with h5py.File(self._result.path, "r") as f:
            g = f["increments"][self.name]
            return list(g["contact"].keys()) if "contact" in g else []

    @property
    def contact_attrs(self):
        """The attributes of the increment's contact group (one entry per interface: zone_width,
        zone_pairs, and where the program writes them dissipated_energy, dissipated_increment,
        tangential_force_total, slip_mean) as 1-D arrays; {} without a contact group."""
        with h5py.File(self._result.path, "r") as f:
            g = f["increments"][self.name]
            if "contact" not in g:
                return {}
            return {k: np.atleast_1d(v) for k, v in g["contact"].attrs.items()}

    def contact_all(self):
        """Every contact dataset of the increment, as a dict."""
        with h5py.File(self._result.path, "r") as f:
            g = f["increments"][self.name]
            if "contact" not in g:
                return {}
            return {k: v[()] for k, v in g["contact"].items()}

    def __repr__(self):
        return "<Step %d of %s>" % (self.number, self._result.path)


class Result:
    """The documented contents of one result file."""

    def __init__(self, path):
        self.path = str(path)
        with h5py.File(self.path, "r") as f:
            self.attrs = _attrs(f)
            self.mesh = _Namespace(f["mesh"]) if "mesh" in f else None
            self.contact = ContactDefinition(f["contact"]) if "contact" in f else None
            names = sorted(f["increments"].keys()) if "increments" in f else []
            self.steps = [Step(self, k, _attrs(f["increments"][k])) for k in names]
        self._by_number = {s.number: s for s in self.steps}

    @property
    def status(self):
        return str(self.attrs.get("status", ""))

    @property
    def completed(self):
        return int(self.attrs.get("increments_completed", 0))

    @property
    def version(self):
        return str(self.attrs.get("version", ""))

    @property
    def last(self):
        if not self.steps:
            raise KeyError("%s holds no increment" % self.path)
        return self.steps[-1]

    def step(self, number):
        return self._by_number[int(number)]

    def history(self, attr):
        """An increment attribute over the kept increments (NaN where absent)."""
        return np.array([float(np.atleast_1d(s.attrs[attr])[0]) if attr in s.attrs else np.nan
                         for s in self.steps])

    @property
    def cycles(self):
        """The periodic histories (group /cycles: first_increment, last_increment (ncycle) and
        (ncycle, ninterface) energy, force_amplitude, slip_amplitude, secant_stiffness,
        loss_factor, damping_ratio) as a dict of arrays; {} when the file has none (a file
        written before the program wrote them, or a history without cycles)."""
        with h5py.File(self.path, "r") as f:
            if "cycles" not in f:
                return {}
            g = f["cycles"]
            return {k: g[k][()] for k in g.keys() if isinstance(g[k], h5py.Dataset)}

    @property
    def summary(self):
        """The closing summary of the run (group /summary: its attributes and its stage_*
        datasets, docs/results-format.md "Run summary") as one dict; {} when the file has none
        (a run that failed at its set-up, or a file written before the program wrote it)."""
        with h5py.File(self.path, "r") as f:
            if "summary" not in f:
                return {}
            g = f["summary"]
            out = _attrs(g)
            out.update({k: g[k][()] for k in g.keys() if isinstance(g[k], h5py.Dataset)})
            return out

    def load_factors(self):
        """(nsteps, ncase) load factors of the kept increments."""
        return np.array([s.load_factor for s in self.steps]).reshape(len(self.steps), -1)


def dataset(path, name):
    """The dataset `name` (a path inside the file, e.g. "/increments/00003/displacement", as the
    XDMF sidecar names it) of the result file `path`, read whole.  KeyError if the file holds
    no dataset of that name."""
    with DatasetReader(path) as read:
        return read(name)


class DatasetReader:
    """Datasets of one result file read by their paths, the file opened once (for a reader of
    thousands of increments: `dataset` opens the file per call).  A context manager:

        with DatasetReader(path) as read:
            u = read("/increments/00003/displacement")
    """

    def __init__(self, path):
        self.path = str(path)
        self._file = h5py.File(self.path, "r")

    def __call__(self, name):
        try:
            obj = self._file[name]          # one lookup (a test `name in f` first doubles it)
        except KeyError:
            obj = None
        if not isinstance(obj, h5py.Dataset):
            raise KeyError("%s holds no dataset %s" % (self.path, name))
        return obj[()]

    def close(self):
        self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def first_nonfinite(path):
    """The first dataset or attribute of the file holding a NaN or an infinity
    (as "/group/dataset" or "/group@attribute"), None when every number is
    finite: the fuzzing contract for a run that ended with exit code 0."""
    bad = []

    def finite(v):
        arr = np.asarray(v)
        return arr.dtype.kind != "f" or bool(np.all(np.isfinite(arr)))

    def visit(name, obj):
        if bad:
            return
        if isinstance(obj, h5py.Dataset) and not finite(obj[()]):
            bad.append("/" + name)
        for k, v in obj.attrs.items():
            if not bad and not finite(v):
                bad.append(f"/{name}@{k}")

    with h5py.File(path, "r") as f:
        for k, v in f.attrs.items():
            if not bad and not finite(v):
                bad.append(f"/@{k}")
        f.visititems(visit)
    return bad[0] if bad else None


def audit(path):
    """What a run that ended early (a full disk) left readable, without
    trusting any of it: (status, increments_completed, groups), each group a
    tuple (name, readable, converged) -- readable when its four fields
    (displacement, stress_nodal, stress_gauss, reaction) can be read,
    converged the attribute or None.  Raises OSError when the file cannot be
    opened at all."""
    fields = ("displacement", "stress_nodal", "stress_gauss", "reaction")
    with h5py.File(str(path), "r") as f:
        status = str(_text(f.attrs.get("status", "")))
        completed = int(f.attrs.get("increments_completed", 0))
        names = sorted(f["increments"].keys()) if "increments" in f else []
        groups = []
        for name in names:
            readable, converged = True, None
            try:
                g = f["increments"][name]
                converged = g.attrs.get("converged")
                for d in fields:
                    g[d][()]
            except Exception:   # noqa: BLE001 -- any failure: the group is not readable
                readable = False
            groups.append((name, readable, None if converged is None else int(converged)))
    return status, completed, groups
