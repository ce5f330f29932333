"""Open a Kontakt2D XDMF sidecar in ParaView's readers and compare what they
see with the HDF5 result file.  Runs under pvpython (Debian's paraview):

    pvpython check_paraview.py RESULTS.xdmf

For each reader -- the legacy "XDMF Reader" and the two Xdmf3 readers ParaView
picks by default for .xdmf -- the time steps must be the increment numbers of
the result file; at every time step the bodies' grid must carry the
displacement (at least the two components of the file), the nodal stresses as
one 4-component array and the load factors as field data (one tuple, one
component per load case), and for a model with
contact a second grid of one point per pair must carry every pair quantity the
sidecar names; the range of every array component must equal the range of the
same column in the HDF5 file (both read the same float64 numbers, so the
tolerance is a few units in the last place: 1e-12 relative to the largest
magnitude).  Prints what it saw; exit code 0 when all holds, 1 otherwise.
The result file is read through k2d.results (tools/ on PYTHONPATH).
"""
import sys

import numpy as np
from paraview import servermanager as sm
from paraview import simple

from k2d.results import Result

READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
CONTACT = ("pressure", "shear", "closure", "slip", "slip_irreversible", "force_normal",
           "force_tangential", "friction", "normal_state", "tangential_state")
RTOL = 1e-12


def fail(msg):
    print("check_paraview: FAILED: " + msg)
    sys.exit(1)


def leaves(obj):
    """The leaf datasets of a reader's output."""
    if obj.IsA("vtkCompositeDataSet"):
        out = []
        it = obj.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            out.append(it.GetCurrentDataObject())
            it.GoToNextItem()
        return out
    return [obj]


def same_range(name, arr, comp, col):
    lo, hi = arr.GetRange(comp)
    want = (float(np.min(col)), float(np.max(col)))
    scale = max(abs(want[0]), abs(want[1]), 1e-300)
    if abs(lo - want[0]) > RTOL * scale or abs(hi - want[1]) > RTOL * scale:
        fail(f"{name}[{comp}]: range ({lo:.17g}, {hi:.17g}) in ParaView, "
             f"({want[0]:.17g}, {want[1]:.17g}) in the HDF5 file")


def open_reader(kind, path):
    if kind == "XDMFReader":
        return simple.XDMFReader(FileNames=[path])
    return getattr(simple, kind)(FileName=[path])


def check_reader(kind, path, res):
    reader = open_reader(kind, path)
    reader.UpdatePipelineInformation()
    times = [float(t) for t in reader.TimestepValues]
    want = [float(s.number) for s in res.steps]
    if times != want:
        fail(f"{kind}: time steps {times}, the result file has increments {want}")
    npoin = res.mesh.coordinates.shape[0]
    npair = res.contact.npair if res.contact is not None else 0
    seen = set()
    for step in res.steps:
        reader.UpdatePipeline(float(step.number))
        blocks = leaves(sm.Fetch(reader))
        bodies = [b for b in blocks if b.GetPointData().GetArray("stress") is not None]
        pairs = [b for b in blocks if b.GetPointData().GetArray("pressure") is not None]
        if len(bodies) != 1 or bodies[0].GetNumberOfPoints() != npoin:
            fail(f"{kind}, increment {step.number}: no grid of the bodies with {npoin} points")
        pd = bodies[0].GetPointData()
        u = step.field("displacement")
        disp = pd.GetArray("displacement")
        # three components in every reader: Warp By Vector needs them
        if disp is None or disp.GetNumberOfComponents() != 3:
            fail(f"{kind}, increment {step.number}: no displacement vector of 3 components")
        for c in range(2):
            same_range("displacement", disp, c, u[:, c])
        same_range("displacement", disp, 2, np.zeros(1))
        stress = pd.GetArray("stress")
        if stress.GetNumberOfComponents() != 4:
            fail(f"{kind}: stress has {stress.GetNumberOfComponents()} components, expected 4 (xx, yy, xy, zz)")
        s = step.field("stress_nodal")
        for c in range(4):
            same_range("stress", stress, c, s[:, c])
        seen.add(f"displacement ({disp.GetNumberOfComponents()} components)")
        seen.add("stress (4 components)")
        grids = bodies
        if npair > 0:
            if len(pairs) != 1 or pairs[0].GetNumberOfPoints() != npair or pairs[0].GetNumberOfCells() != npair:
                fail(f"{kind}, increment {step.number}: no contact grid of {npair} points and vertices")
            for name in CONTACT:
                arr = pairs[0].GetPointData().GetArray(name)
                if arr is None:
                    fail(f"{kind}, increment {step.number}: the contact grid has no array {name}")
                same_range(name, arr, 0, step.contact(name))
                seen.add("contact " + name)
            grids = bodies + pairs
        elif pairs:
            fail(f"{kind}: a contact grid for a model without contact")
        for g in grids:
            lf = g.GetFieldData().GetArray("load_factor")
            if lf is None or lf.GetNumberOfTuples() != 1 or lf.GetNumberOfComponents() != len(step.load_factor):
                fail(f"{kind}, increment {step.number}: no load_factor field of one tuple of "
                     f"{len(step.load_factor)} component(s)")
            got = np.array(lf.GetTuple(0))
            if np.max(np.abs(got - step.load_factor)) > RTOL * max(1.0, np.max(np.abs(step.load_factor))):
                fail(f"{kind}, increment {step.number}: load_factor {got}, the file {step.load_factor}")
        seen.add("load_factor (field)")
    simple.Delete(reader)
    print(f"check_paraview: {kind}: {len(times)} time step(s) {[int(t) for t in times]}; arrays: "
          + ", ".join(sorted(seen)))


def main():
    path = sys.argv[1]
    res = Result(path.rsplit(".", 1)[0] + ".h5")
    if not res.steps:
        fail(f"{path}: the result file holds no increment")
    for kind in READERS:
        check_reader(kind, path, res)
    print(f"check_paraview: {path}: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
