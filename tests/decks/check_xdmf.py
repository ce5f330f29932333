#!/usr/bin/python3
"""Check a Kontakt2D XDMF sidecar against its HDF5 result file.

    check_xdmf.py RESULTS.xdmf [--every N --steps S]

Well-formed XML (xml.etree); a temporal collection with one uniform grid per
finished increment (root attribute increments_completed of the HDF5 file);
every HDF DataItem names a dataset that exists, with the declared dimensions;
hyperslabs select inside their dataset; topologies count the elements of the
mesh and point at existing nodes (0-based).  With --every N --steps S (OPTIONS
RESULTS N on a run of S steps) the increment groups must be exactly the steps
N, 2N, ... and the last, S.  Exit code 0 when all holds.  Reads the HDF5 file
through k2d.results (tools/k2d on the Python path; ctest sets PYTHONPATH).
"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

from k2d.results import Result, dataset

NNODE = {"Triangle": 3, "Quadrilateral": 4, "Quadrilateral_8": 8, "Quadrilateral_9": 9}
MIXED = {4: 3, 5: 4, 37: 8, 35: 9}


def fail(msg):
    print("check_xdmf: " + msg)
    sys.exit(1)


def dims(item):
    return tuple(int(v) for v in item.get("Dimensions").split())


def hdf_dataset(item, base):
    fname, path = item.text.strip().split(":", 1)
    h5path = os.path.join(base, fname)
    if not os.path.exists(h5path):
        fail(f"DataItem names {fname}, which does not exist")
    try:
        ds = dataset(h5path, path)
    except KeyError:
        fail(f"DataItem names {fname}:{path}, which does not exist")
    if tuple(ds.shape) != dims(item):
        fail(f"{path}: shape {ds.shape} but the XDMF declares {dims(item)}")
    return ds


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
    for g in grids:
        times.append(float(g.find("Time").get("Value")))
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
        for att in g.findall("Attribute"):
            item = att.find("DataItem")
            if item.get("ItemType") == "HyperSlab":
                sel, src = item.findall("DataItem")
                start, stride, count = np.array(sel.text.split(), dtype=int).reshape(3, 2)
                ds = hdf_dataset(src, base)
                last = start + stride * (count - 1)
                if np.any(last >= np.array(ds.shape)) or tuple(count) != dims(item):
                    fail(f"hyperslab of {att.get('Name')} lies outside its dataset")
            else:
                if hdf_dataset(item, base).shape[0] != npoin:
                    fail(f"attribute {att.get('Name')} is not one value per node")
    if times != sorted(times):
        fail("times do not increase")
    print(f"check_xdmf: {xdmf}: {len(grids)} grid(s), {nelem} elements, {npoin} nodes: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
