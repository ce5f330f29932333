#!/usr/bin/python3
"""Tests of the size view's ghost cells and the mesh-shape measure of tools/adapt.py
(k2d.adapt_mesh; docs/adaptivity.md, "Mesh quality").

Run by ctest (tests/tools/CMakeLists.txt: tools_adapt_mesh) with PYTHONPATH=<source>/tools;
by hand:  PYTHONPATH=tools /usr/bin/python3 tests/tools/test_adapt_mesh.py [-v]

* Angles: the largest interior angle of a square (90), of a quadrilateral with a known obtuse
  corner and of a reflex (non-convex) one, either orientation.
* Ghosts: the ghost cells of a chord-sided mesh of a quarter disc cover the arc between every two
  boundary nodes (where the old mesh's cells, chords, end), carry the sizes of their edge's
  nodes, and lie outside the cells.
* CurvedRemesh (gmsh): hertz_uniform.geo's cylinder remeshed from a size view of its own start
  mesh asking for 1 mm everywhere: every segment of the contact arc at most 1.5 mm and no
  quadrilateral beyond 150 degrees.  Without the ghost cells gmsh found no size on the arc
  outside the chords and left segments of several millimetres (a chord for the arc), with
  quadrilaterals up to 169 degrees beside them (the effectivity 0.61 of docs/adaptivity.md).
  With the cylinder asking for 0.2 mm and the half-plane for 2 mm, one view per body restricted
  to its entities keeps every segment of the arc within 0.3 mm, where the half-plane's ghost cells
  reach into the contact's gap.
* ExampleDecks (gmsh, kontakt2d): the three examples' .geo decks of inputs/adapt/ mesh and
  solve to the end of their load histories, the contact carrying the whole load.
"""
import os
import shutil
import tempfile
import unittest

import numpy as np

from k2d import adapt as ad
from k2d import adapt_mesh as am
from k2d.build import ROOT


def inside(P, pt):
    """pt inside the convex polygon P (either orientation), boundary included to 1e-12."""
    s = []
    for i in range(len(P)):
        a, b = P[i], P[(i + 1) % len(P)]
        s.append((b[0] - a[0]) * (pt[1] - a[1]) - (b[1] - a[1]) * (pt[0] - a[0]))
    s = np.array(s)
    return bool(np.all(s >= -1e-12) or np.all(s <= 1e-12))


class Angles(unittest.TestCase):
    def test_known_polygons(self):
        sq = [[0, 0], [1, 0], [1, 1], [0, 1]]
        # a convex quadrilateral whose corner (1, -0.1) has the angle 180 - 2 atan(0.1) deg
        obtuse = [[0, 0], [1, -0.1], [2, 0], [1, 1]]
        reflex = [[0, 0], [2, 0], [1, 0.5], [1, 2]]       # the corner (1, 0.5) turns inwards
        got = am.polygon_max_angles([sq, obtuse, reflex, sq[::-1], obtuse[::-1]])
        want_obtuse = 180.0 - 2.0 * np.degrees(np.arctan(0.1))
        a, b = np.array([2.0, 0.0]) - [1, 0.5], np.array([1.0, 2.0]) - [1, 0.5]
        want_reflex = 360.0 - np.degrees(np.arccos(a @ b / np.linalg.norm(a) / np.linalg.norm(b)))
        np.testing.assert_allclose(got, [90.0, want_obtuse, want_reflex, 90.0, want_obtuse], atol=1e-9)
        self.assertGreater(want_reflex, 180.0)


class Ghosts(unittest.TestCase):
    def test_arc_covered(self):
        # a quarter disc R = 1 as a fan of triangles from the centre: its arc is 8 chords
        R, n = 1.0, 8
        th = np.linspace(0.0, 0.5 * np.pi, n + 1)
        xy = np.vstack([[0.0, 0.0], np.column_stack([R * np.cos(th), R * np.sin(th)])])
        cells = [[0, i + 1, i + 2] for i in range(n)]
        nodal = np.linspace(0.1, 0.5, len(xy))
        ghosts = am.boundary_ghosts(xy, cells, nodal)
        # boundary edges: the 8 chords and the two radii
        self.assertEqual(len(ghosts), n + 2)
        for corners, sizes in ghosts:
            ends = [int(np.argmin(np.hypot(*(xy - c).T))) for c in corners[:2]]
            np.testing.assert_allclose(sizes, nodal[[ends[0], ends[1], ends[1], ends[0]]])
            far = 0.5 * (corners[2] + corners[3])
            self.assertFalse(any(inside(xy[c], far) for c in cells))    # outwards
        # every point of the arc lies in a cell or a ghost (the chords leave the arc outside
        # the cells: the bulge h^2 / (8 R) = 0.031 for h = 0.39)
        outside = 0
        for t in np.linspace(0.0, 0.5 * np.pi, 401):
            pt = (R * np.cos(t), R * np.sin(t))
            in_cell = any(inside(xy[c], pt) for c in cells)
            outside += not in_cell
            self.assertTrue(in_cell or any(inside(g, pt) for g, _ in ghosts), pt)
        self.assertGreater(outside, 300)        # the test is about those points


class _Mesh:
    def __init__(self, msh):
        xyd, elems = am.read_msh2d(msh)
        tags = sorted(xyd)
        index = {t: i for i, t in enumerate(tags)}
        self.coordinates = np.array([xyd[t] for t in tags])
        self.element_nodes = np.array([len(c) for _e, c in elems])
        self.connectivity = np.zeros((len(elems), 9), dtype=int)
        for e, (_ety, c) in enumerate(elems):
            self.connectivity[e, :len(c)] = [index[t] + 1 for t in c]


class _Result:
    contact = None

    def __init__(self, msh):
        self.mesh = _Mesh(msh)


@unittest.skipIf(shutil.which("gmsh") is None, "gmsh not installed")
class CurvedRemesh(unittest.TestCase):
    def test_arc_resolved_and_no_flat_quads(self):
        work = tempfile.mkdtemp(prefix="adapt_mesh_", dir=os.environ.get("K2D_TEST_WORK"))
        self.addCleanup(shutil.rmtree, work, ignore_errors=True)
        geo = os.path.join(ROOT, "inputs", "adapt", "hertz_uniform.geo")
        start = os.path.join(work, "start.msh")
        ad.gmsh_mesh(geo, start, start + ".log", factor=1.0)       # 3 mm everywhere
        r = _Result(start)
        size = 1.0
        pos = os.path.join(work, "size.pos")
        ad.write_size_view(pos, r, np.full(len(r.mesh.element_nodes), size))
        msh = os.path.join(work, "next.msh")
        ad.gmsh_mesh(geo, msh, msh + ".log", pos=pos)
        # the arc's nodes (curve 1, its end points included) in order along it
        xy, _ = am.read_msh2d(msh)
        R = 15.0
        pts = np.array([p for p in xy.values() if abs(np.hypot(p[0], p[1] - R) - R) < 1e-9 * R
                        and p[1] < R - 1e-9])
        pts = pts[np.argsort(np.arctan2(pts[:, 0], R - pts[:, 1]))]
        seg = np.hypot(*np.diff(pts, axis=0).T)
        # the arc is 0.5 pi R = 23.6 mm: at 1 mm about 24 segments; 1.5 mm allows gmsh's rounding
        self.assertGreater(len(seg), 15)
        self.assertLess(seg.max(), 1.5 * size, seg.max())
        q = am.quality(msh)
        self.assertGreater(q["quads"], 100)
        self.assertEqual(q["over_limit"], 0, q)

    def test_each_body_its_own_sizes(self):
        # the cylinder asks for 0.2 mm, the half-plane for 2 mm: the half-plane's ghost cells reach
        # 0.75 mm into the gap (a quarter of its 3 mm edges), over the cylinder's arc out to
        # x = 4.7 mm; one view per body, restricted to the body's entities, keeps the cylinder's
        # own size on its whole arc (without the restriction the arc took 2 mm segments there)
        work = tempfile.mkdtemp(prefix="adapt_mesh_", dir=os.environ.get("K2D_TEST_WORK"))
        self.addCleanup(shutil.rmtree, work, ignore_errors=True)
        geo = os.path.join(ROOT, "inputs", "adapt", "hertz_uniform.geo")
        start = os.path.join(work, "start.msh")
        ad.gmsh_mesh(geo, start, start + ".log", factor=1.0)
        r = _Result(start)
        m = r.mesh
        centre_y = np.array([m.coordinates[m.connectivity[e, :4] - 1, 1].mean() for e in range(len(m.element_nodes))])
        small, large = 0.2, 2.0
        hnew = np.where(centre_y > 0.0, small, large)
        pos = os.path.join(work, "size.pos")
        restrict = ad.write_size_view(pos, r, hnew, msh=start)
        self.assertEqual(len(restrict), 2)                      # the two bodies matched
        self.assertEqual(sorted(s for surf, _c, _p in restrict for s in surf), [1, 2])
        msh = os.path.join(work, "next.msh")
        ad.gmsh_mesh(geo, msh, msh + ".log", pos=pos, restrict=restrict)
        xy, _ = am.read_msh2d(msh)
        R = 15.0
        pts = np.array([p for p in xy.values() if abs(np.hypot(p[0], p[1] - R) - R) < 1e-9 * R
                        and p[1] < R - 1e-9])
        pts = pts[np.argsort(np.arctan2(pts[:, 0], R - pts[:, 1]))]
        seg = np.hypot(*np.diff(pts, axis=0).T)
        self.assertGreater(len(seg), 80)                        # 23.6 mm of arc at 0.2 mm
        self.assertLess(seg.max(), 1.5 * small, seg.max())


# the three examples as .geo decks (docs/adaptivity.md, "The example decks"): the load each body
# carries through the contact [N]: the punch p0 (B/2) t, the sphere's and the cylinder's P
EXAMPLES = {"punch_5_1": 1.2 * 50.0 * 10.0, "sphere_5_2": 0.28294212 * np.pi * 15.0 ** 2, "cylinder_5_3": 1.0e5}


@unittest.skipIf(shutil.which("gmsh") is None, "gmsh not installed")
class ExampleDecks(unittest.TestCase):
    def test_start_meshes_solve(self):
        # each example's .geo start mesh, made as tools/adapt.py makes it, solves to the end of its
        # load history (exit code 0), and the contact carries the whole load (equilibrium of the
        # loaded body, SPEC 7: 1e-8); its estimate is written and above zero
        from k2d.build import find_or_build
        exe = find_or_build(os.environ.get("K2D_EXECUTABLE"))
        work = tempfile.mkdtemp(prefix="adapt_examples_", dir=os.environ.get("K2D_TEST_WORK"))
        self.addCleanup(shutil.rmtree, work, ignore_errors=True)
        for name, load in EXAMPLES.items():
            with self.subTest(deck=name):
                for ext in (".dat", ".geo"):
                    shutil.copy(os.path.join(ROOT, "inputs", "adapt", name + ext), work)
                msh = os.path.join(work, name + ".msh")
                ad.gmsh_mesh(os.path.join(work, name + ".geo"), msh, msh + ".log")
                h5 = os.path.join(work, name + ".h5")
                r, _cpu, rc = ad.solve(exe, os.path.join(work, name + ".dat"), h5, os.path.join(work, name + ".lis"))
                self.assertEqual(rc, 0)
                fn = r.last.contact("force_normal")
                self.assertAlmostEqual(float(np.sum(fn)) / load, 1.0, delta=1e-8)
                eta, est, source = ad.indicator(r, ad.deck_materials(os.path.join(work, name + ".dat")))
                self.assertEqual(source, "program")
                self.assertGreater(est, 0.0)
                self.assertEqual(len(eta), len(r.mesh.element_nodes))


class LayerChain(unittest.TestCase):
    def test_straight_continuation_joined_corner_ends(self):
        # a rectangle 3 x 1 whose top is two collinear curves 11 (x 0..1) and 12 (x 1..3): a layer
        # seeded on 11 is carried on along 12 (its end column would lie along the boundary) and
        # ends at the corners (3, 0) and (0, 0), where the boundary turns by 90 degrees
        pts = {1: (0, 0), 2: (1, 0), 3: (3, 0), 4: (3, -1), 5: (0, -1)}
        curves = {11: (1, 2), 12: (2, 3), 13: (3, 4), 14: (4, 5), 15: (5, 1)}
        topo = {"points": {k: np.array(v, float) for k, v in pts.items()}, "curves": curves,
                "curve_nodes": {c: 0.5 * (np.array(pts[a], float) + np.array(pts[b], float))[None, :]
                                for c, (a, b) in curves.items()}}
        self.assertEqual(am.layer_chain(topo, [11], list(curves)), ([11, 12], [1, 2, 3]))
        # a turn of 30 degrees (below the 45 of LAYER_CORNER) is carried on, 60 is not
        for turn, joined in ((30.0, True), (60.0, False)):
            t = np.radians(turn)
            q = dict(topo, points=dict(topo["points"]))
            q["points"][3] = np.array([1 + 2 * np.cos(t), -2 * np.sin(t)])
            q["curve_nodes"] = dict(topo["curve_nodes"])
            q["curve_nodes"][12] = (0.5 * (q["points"][2] + q["points"][3]))[None, :]
            got = am.layer_chain(q, [11], [11, 12, 15])[0]
            self.assertEqual(12 in got, joined, (turn, got))


@unittest.skipIf(shutil.which("gmsh") is None, "gmsh not installed")
class ContactLayer(unittest.TestCase):
    def test_layer_follows_the_contact_spacing(self):
        # hertz_adapt's start mesh solved, the next mesh made from a view of its own sizes with the
        # contact layer (tools/adapt.py --contact-layer): both bodies get a layer (the cylinder's
        # arc 1 carried on along its tangent arc 2, the half-plane's top line 11 along the
        # collinear 12), every element is valid and none beyond 150 degrees, and at every node of
        # the contact curves within the contact zone the nearest node off the curve lies on the
        # curve's normal (within 10 degrees: a column of the layer) at 0.8 - 1.25 times the local
        # spacing along the curve (gmsh interpolates the first thickness quadratically between
        # the curves' end points, the 1-D mesh follows the view: measured 1.02 - 1.13 here).
        # Without the layer (the control) the nodes beside the curves are gmsh's unstructured
        # ones: 5 of the 8 lie off the normal, at 0.71 - 1.35 times the spacing.
        from k2d.build import find_or_build
        exe = find_or_build(os.environ.get("K2D_EXECUTABLE"))
        work = tempfile.mkdtemp(prefix="adapt_layer_", dir=os.environ.get("K2D_TEST_WORK"))
        self.addCleanup(shutil.rmtree, work, ignore_errors=True)
        for ext in (".dat", ".geo"):
            shutil.copy(os.path.join(ROOT, "inputs", "adapt", "hertz_adapt" + ext), work)
        geo = os.path.join(work, "hertz_adapt.geo")
        start = os.path.join(work, "hertz_adapt.msh")
        ad.gmsh_mesh(geo, start, start + ".log")
        r, _cpu, rc = ad.solve(exe, os.path.join(work, "hertz_adapt.dat"), os.path.join(work, "start.h5"),
                               os.path.join(work, "start.lis"))
        self.assertEqual(rc, 0)
        h, _p = ad.element_sizes(r)
        layers = ad.contact_layers(r, ad.view_sizes(r, h), start)
        self.assertEqual(sorted(lay["curves"] for lay in layers), [[1, 2], [11, 12]])
        pos = os.path.join(work, "size.pos")
        restrict = ad.write_size_view(pos, r, h, msh=start)
        a, R = 0.5754, 15.0
        for with_layer in (True, False):
            msh = os.path.join(work, "next_%d.msh" % with_layer)
            used = [dict(lay) for lay in layers] if with_layer else None
            ad.gmsh_mesh(geo, msh, msh + ".log", pos=pos, restrict=restrict, layers=used)
            if with_layer:
                self.assertEqual(len(used), 2)              # gmsh made it (not meshed again without)
                q = am.quality(msh)
                self.assertEqual(q["over_limit"], 0, q)
            xy, elems = am.read_msh2d(msh)
            for _ety, c in elems:                           # valid: every corner convex
                P = np.array([xy[t] for t in c])
                self.assertLess(am.corner_angles(P).max(), 180.0)
            allxy = np.array(list(xy.values()))
            topo = am.msh_topology(msh)
            ratios, off = [], 0
            for curve, on in ((1, lambda p: abs(np.hypot(p[:, 0], p[:, 1] - R) - R) < 1e-9 * R),
                              (11, lambda p: np.abs(p[:, 1]) < 1e-9)):
                nodes = topo["curve_nodes"][curve]
                ends = np.array([topo["points"][e] for e in topo["curves"][curve]])
                seq = np.vstack([nodes, ends])
                seq = seq[np.argsort(seq[:, 0])]
                cand = allxy[~on(allxy)]
                cand = cand[(cand[:, 1] > 0) if curve == 1 else (cand[:, 1] < 0)]
                for i in range(1, len(seq) - 1):
                    if seq[i, 0] > a:
                        break
                    d = cand - seq[i]
                    k = int(np.argmin(np.hypot(d[:, 0], d[:, 1])))
                    t = seq[i + 1] - seq[i - 1]
                    normal = np.array([-t[1], t[0]]) / np.hypot(t[0], t[1])
                    dist = float(np.hypot(*d[k]))
                    spacing = 0.5 * float(np.hypot(*(seq[i + 1] - seq[i])) + np.hypot(*(seq[i] - seq[i - 1])))
                    if abs(float(d[k] @ normal)) / dist < np.cos(np.radians(10.0)):
                        off += 1
                    ratios.append(dist / spacing)
            self.assertGreater(len(ratios), 5)                # the pairs within a on both curves
            if with_layer:
                self.assertEqual(off, 0)
                self.assertGreater(min(ratios), 0.8, ratios)
                self.assertLess(max(ratios), 1.25, ratios)
            else:
                self.assertGreater(off, 0)

    def test_failed_layer_meshed_again_without(self):
        # gmsh crashing on the layer (gmsh 4.8's algorithm 8 segfaults on hertz_adapt.geo, with
        # and without a layer): the mesh is made again without the layer, the layers handed in
        # are emptied (the route then reports no layer for that mesh) and gmsh's log of the
        # failure is kept beside the new one.  The crash is simulated: every gmsh run whose
        # .geo asks for a BoundaryLayer field exits with a segmentation fault's -11.
        work = tempfile.mkdtemp(prefix="adapt_layer_", dir=os.environ.get("K2D_TEST_WORK"))
        self.addCleanup(shutil.rmtree, work, ignore_errors=True)
        geo = os.path.join(ROOT, "inputs", "adapt", "hertz_adapt.geo")
        real = ad.run_cpu
        calls = []

        def crash_on_layer(cmd, log, cwd=None):
            with open(cmd[4]) as f:
                layered = "BoundaryLayer" in f.read()
            calls.append(layered)
            if layered:
                with open(log, "w") as f:
                    f.write("Segmentation fault\n")
                return -11, 0.0, 0.0
            return real(cmd, log, cwd)
        ad.run_cpu = crash_on_layer
        self.addCleanup(setattr, ad, "run_cpu", real)
        layers = [{"curves": [1, 2], "sizes": {1: 0.2, 2: 0.3, 3: 3.0}, "depth": 0.8}]
        msh = os.path.join(work, "next.msh")
        ad.gmsh_mesh(geo, msh, msh + ".log", layers=layers)
        self.assertEqual(calls, [True, False])
        self.assertEqual(layers, [])
        self.assertTrue(os.path.isfile(msh + ".log.layer"))
        self.assertGreater(am.quality(msh)["elements"], 100)


if __name__ == "__main__":
    unittest.main()
