#!/usr/bin/python3
"""Check a Kontakt2D XDMF sidecar against its HDF5 result file.

    check_xdmf.py RESULTS.xdmf [--every N --steps S]

Well-formed XML (xml.etree); a temporal collection with one uniform grid per
finished increment (root attribute increments_completed of the HDF5 file);
every HDF DataItem names a dataset that exists, with the declared dimensions;
every node attribute is a plain HDF DataItem (no hyperslab or function, which
the Xdmf3 readers drop) of one row per point, the cell attribute error_indicator
one of one row per element; topologies count the elements of
the mesh and point at existing nodes (0-based); each grid carries the
increment's load factors as a grid-centred attribute; a model with contact has
per increment a spatial collection of the bodies and a Polyvertex grid of the
pairs with their results.  With --every N --steps S (OPTIONS
RESULTS N on a run of S steps) the increment groups must be exactly the steps
N, 2N, ... and the last, S.  Exit code 0 when all holds.  Reads the HDF5 file
through k2d.results (tools/k2d on the Python path; ctest sets PYTHONPATH).
"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

from k2d.results import DatasetReader, Result

NNODE = {"Triangle": 3, "Quadrilateral": 4, "Quadrilateral_8": 8, "Quadrilateral_9": 9}
MIXED = {4: 3, 5: 4, 37: 8, 35: 9}


def fail(msg):
    print("check_xdmf: " + msg)
    sys.exit(1)


def dims(item):
    return tuple(int(v) for v in item.get("Dimensions").split())


READERS = {}   # one open reader per HDF5 file the sidecar names (4000 increments: 80 000 reads)


def hdf_dataset(item, base):
    fname, path = item.text.strip().split(":", 1)
    h5path = os.path.join(base, fname)
    if h5path not in READERS:
        if not os.path.exists(h5path):
            fail(f"DataItem names {fname}, which does not exist")
        READERS[h5path] = DatasetReader(h5path)
    try:
        ds = READERS[h5path](path)
    except KeyError:
        fail(f"DataItem names {fname}:{path}, which does not exist")
    if tuple(ds.shape) != dims(item):
        fail(f"{path}: shape {ds.shape} but the XDMF declares {dims(item)}")
    return ds


def check_load_factor(g, step):
    """The grid-centred attribute load_factor: the increment's factors, inline."""
    att = [a for a in g.findall("Attribute") if a.get("Name") == "load_factor"]
    if len(att) != 1 or att[0].get("Center") != "Grid":
        fail(f"grid {g.get('Name')}: no grid-centred attribute load_factor")
    item = att[0].find("DataItem")
    vals = np.array(item.text.split(), dtype=float)
    if item.get("Format") != "XML" or dims(item) != (1, len(step.load_factor)) or \
            np.max(np.abs(vals - step.load_factor)) > 1e-15 * max(1.0, np.max(np.abs(step.load_factor))):
        fail(f"grid {g.get('Name')}: load_factor {vals}, the file {step.load_factor}")


def check_node_attributes(g, base, npoints):
    """Every node-centred attribute: a plain HDF DataItem (no hyperslab, no
    function: the Xdmf3 readers drop them) of one row per point."""
    return check_attributes(g, base, npoints, lambda c: c not in ("Grid", "Cell"), "point")


def check_attributes(g, base, nrows, centred, per):
    """The attributes of grid g whose Center passes `centred`: each a plain HDF DataItem of
    nrows rows (one value per `per`); their names."""
    names = []
    for att in g.findall("Attribute"):
        if not centred(att.get("Center")):
            continue
        item = att.find("DataItem")
        if item.get("ItemType") not in (None, "Uniform") or item.get("Format") != "HDF":
            fail(f"attribute {att.get('Name')} is not a plain HDF DataItem")
        ds = hdf_dataset(item, base)
        if ds.shape[0] != nrows:
            fail(f"attribute {att.get('Name')} is not one value per {per}")
        names.append(att.get("Name"))
    return names


def check_cell_attributes(g, base, nelem):
    """Every cell-centred attribute: a plain HDF DataItem of one row per element."""
    return check_attributes(g, base, nelem, lambda c: c == "Cell", "element")


def check_bodies(g, base, npoin, nelem, step):
    topo = g.find("Topology")
    if int(topo.get("NumberOfElements")) != nelem:
        fail(f"topology has {topo.get('NumberOfElements')} elements, the mesh {nelem}")
    tds = hdf_dataset(topo.find("DataItem"), base)
    if topo.get("TopologyType") == "Mixed":
        pos, n = 0, 0
        while pos < len(tds):
            nn = MIXED[int(tds[pos])]
            cell = tds[pos + 1:pos + 1 + nn]
            if cell.min() < 0 or cell.max() >= npoin:
                fail("mixed topology points at a node that does not exist")
            pos += 1 + nn
            n += 1
        if n != nelem:
            fail(f"mixed topology holds {n} cells, the mesh {nelem}")
    else:
        if tds.shape[1] != NNODE[topo.get("TopologyType")]:
            fail("topology type and connectivity width differ")
        if tds.min() < 0 or tds.max() >= npoin:
            fail("topology points at a node that does not exist (connectivity must be 0-based)")
    geo = g.find("Geometry")
    if geo.get("GeometryType") != "XY":
        fail("geometry is not XY")
    if hdf_dataset(geo.find("DataItem"), base).shape != (npoin, 2):
        fail("geometry shape")
    names = check_node_attributes(g, base, npoin)
    if sorted(names) != ["displacement", "stress"]:
        fail(f"the bodies' attributes are {names}, expected displacement and stress")
    cells = check_cell_attributes(g, base, nelem)
    if cells != ["error_indicator"]:
        fail(f"the bodies' cell attributes are {cells}, expected error_indicator")
    disp = hdf_dataset(g.find("Attribute[@Name='displacement']/DataItem"), base)
    u = step.field("displacement")
    if disp.shape != (npoin, 3) or not np.array_equal(disp[:, :2], u) or np.any(disp[:, 2] != 0.0):
        fail("the displacement attribute is not the displacements with a zero third component")
    check_load_factor(g, step)


def check_contact(g, base, npair, step):
    topo = g.find("Topology")
    if topo.get("TopologyType") != "Polyvertex" or int(topo.get("NumberOfElements")) != npair:
        fail("the contact grid is not a Polyvertex of one vertex per pair")
    cells = np.array(topo.find("DataItem").text.split(), dtype=int)
    if not np.array_equal(cells, np.arange(npair)):
        fail("the contact grid's vertices are not the pairs 0 .. npair-1")
    if hdf_dataset(g.find("Geometry/DataItem"), base).shape != (npair, 2):
        fail("contact geometry shape")
    names = check_node_attributes(g, base, npair)
    have = set(step.contact_names())
    for want in ("pressure", "shear", "closure", "slip", "slip_irreversible", "normal_state", "tangential_state"):
        if want not in names:
            fail(f"the contact grid has no attribute {want}")
    if not set(names) <= have:
        fail(f"contact attributes {sorted(set(names) - have)} are no datasets of the increment")
    check_load_factor(g, step)


def main():
    xdmf = sys.argv[1]
    opts = dict(zip(sys.argv[2::2], sys.argv[3::2]))
    base = os.path.dirname(os.path.abspath(xdmf))
    root = ET.parse(xdmf).getroot()             # raises on malformed XML
    if root.tag != "Xdmf":
        fail("root element is not Xdmf")
    coll = root.find("Domain/Grid")
    if coll is None or coll.get("CollectionType") != "Temporal":
        fail("no temporal collection under Domain")
    grids = coll.findall("Grid")
    h5name = None
    for item in root.iter("DataItem"):
        if item.get("Format") == "HDF":
            h5name = item.text.strip().split(":", 1)[0]
            break
    if h5name is None:
        h5name = os.path.splitext(os.path.basename(xdmf))[0] + ".h5"
    res = Result(os.path.join(base, h5name))
    ncomp = res.completed
    if "--every" in opts:
        every, steps = int(opts["--every"]), int(opts["--steps"])
        want = ["%05d" % k for k in range(1, steps + 1) if k % every == 0 or k == steps]
        have = [s.name for s in res.steps]
        if have != want:
            fail(f"increment groups {have}, expected {want} (every {every} of {steps})")
    npoin = res.mesh.coordinates.shape[0]
    nelem = res.mesh.element_nodes.shape[0]
    if len(grids) != ncomp:
        fail(f"{len(grids)} grids but {ncomp} finished increments")
    times = []
    npair = res.contact.npair if res.contact is not None else 0
    for g, step in zip(grids, res.steps):
        times.append(float(g.find("Time").get("Value")))
        if npair > 0:
            # a spatial collection: the bodies and the contact pairs
            if g.get("CollectionType") != "Spatial":
                fail("a model with contact needs a spatial collection per increment")
            parts = {c.get("Name"): c for c in g.findall("Grid")}
            if sorted(parts) != ["bodies", "contact"]:
                fail(f"the increment's grids are {sorted(parts)}, expected bodies and contact")
            check_bodies(parts["bodies"], base, npoin, nelem, step)
            check_contact(parts["contact"], base, npair, step)
        else:
            if g.get("GridType") != "Uniform":
                fail("a model without contact has one uniform grid per increment")
            check_bodies(g, base, npoin, nelem, step)
    if times != sorted(times):
        fail("times do not increase")
    print(f"check_xdmf: {xdmf}: {len(grids)} grid(s), {nelem} elements, {npoin} nodes: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
