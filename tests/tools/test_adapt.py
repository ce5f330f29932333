#!/usr/bin/python3
"""Tests of tools/adapt.py and its library (k2d.adapt, k2d.refine); docs/adaptivity.md.

Run by ctest (tests/tools/CMakeLists.txt: tools_adapt_cards runs Richardson, Validation and CardDeck,
tools_adapt_geo runs Sizes and GeoDeck, tools_adapt_curved CurvedContact, tools_adapt_reference
ReferenceFit) with PYTHONPATH=<source>/tools and K2D_EXECUTABLE;
by hand:  PYTHONPATH=tools /usr/bin/python3 tests/tools/test_adapt.py [-v] [CLASS ...]

* Richardson: a value f(h) = f0 + c h^2 on h, h/2, h/4 gives the order 2 and f0 to round-off;
  an oscillating or diverging sequence is "not in the asymptotic range" and gets no order.
* Validation: the arithmetic of tools/adapt_validation.py -- the energy extrapolation recovers
  U_inf, C, q of U = U_inf - C N^-q; Hertz's p0 a = 2 P'/pi; the punch's edge-band mean pressure
  against a trapezoidal integration of Sadowsky's p(x) (the studies themselves are scripts).
* CardDeck: the uniform splitting keeps the V1 patch tests exact (Q8 plane strain with graded
  elements and quadratic edge loads, Q4 axisymmetric): after one and two splittings every pair
  carries p = 1, the contact area and the total force are unchanged, the pairs double (the new
  surface nodes joined the surfaces, the new restrained nodes are restrained) -- a constant
  stress state is reproduced to round-off, so 1e-9; the recovery-based estimate of a constant
  stress is round-off (1e-9).  Lame's cylinder through tools/adapt.py: three meshes of 8, 32,
  128 elements; the estimate against the exact energy-norm error from the closed form (effectivity
  in [0.7, 1.5] past the coarsest mesh, issue 23's band), and the
  Richardson extrapolation of the largest von Mises stress against the closed form at the bore;
  the V2 tangential patch test (a tied rigid plate) stays exact after splitting; a deck with
  contact PAIRS is refused with exit code 2 and a message naming file, line and PAIRS.
* Sizes: the size formula equidistributes the error (every new element the same share) and
  meets the target; the program's `error_indicator` is used when a result file has it (and the
  recovery estimate of k2d.adapt for a result without it); the
  contact tractions ask for their smallest elements at the edge of the punch, sizes ~ sqrt(target).
* GeoDeck: tools/adapt.py on a small punch-on-foundation .geo deck reaches the target, and
  adaptive remeshing reaches it with fewer DOFs than uniform remeshing; no mesh exceeds the DOF
  budget (exit code 1 when it ends the refinement); a MESH deck without its .geo is refused with
  exit code 2; surface A of a contact is made the finer side of the size field, and a Q8 Hertz
  model's second adaptive mesh solves (it stopped with E-SEGMENT-SIDE before).
* CurvedContact: the uniform route's meshes put the nodes of the cylinder's contact arc (Q8
  midside nodes too) on the circle.
* SingularEdges: a flat punch's edge (p ~ r^-1/2, uniform and graded pairs) is a singular edge,
  Hertz's axis (the largest pressure, also with 1 % of noise on it) and edge are not; a curved
  contact zone (gaps x^2 / 2R) gets one size along both surfaces (--uniform-contact), a flat or
  tilted one and a zone ended by a singular edge do not.
* KeyOutputConvergence: an output whose successive differences do not decrease (per unit of
  log(DOFs) on unequal steps) is flagged "not converging (singular point?)" in the .md, the CSV
  and the terminal; converging, unchanged and oscillating ones are not.
* ReferenceFit: the overkill reference of tools/adapt_validation.py reproduces a quadratic stress
  field between its Gauss points (corners and straight edges included); CardDeck's Lame test
  checks the true error against a reference with the closed-form stresses (= the exact error).
"""

import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from k2d import adapt as ad
from k2d.build import ROOT, find_or_build
from k2d.refine import RefineError, read_card_deck, refine_file
from k2d.results import Result

TOOL = os.path.join(ROOT, "tools", "adapt.py")
CONTACT = os.path.join(ROOT, "tests", "decks", "contact")
LAME = os.path.join(ROOT, "inputs", "lame_cylinder.dat")
PUNCH = os.path.join(ROOT, "tests", "tools", "data", "punch_adapt")


def work_dir(prefix):
    base = os.environ.get("K2D_TEST_WORK")
    if base:
        os.makedirs(base, exist_ok=True)
    return tempfile.mkdtemp(prefix=prefix, dir=base)


def run_tool(*args):
    env = dict(os.environ, MPLBACKEND="Agg")
    p = subprocess.run([sys.executable, TOOL] + list(args), capture_output=True, text=True, env=env)
    return p.returncode, p.stdout + p.stderr


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


class Richardson(unittest.TestCase):
    def test_quadratic_sequence(self):
        f = [2.0 + 3.0 * h * h for h in (1.0, 0.5, 0.25)]
        r = ad.richardson(*f)
        self.assertAlmostEqual(r["order"], 2.0, delta=1e-12)
        self.assertAlmostEqual(r["extrapolated"], 2.0, delta=1e-12)
        self.assertAlmostEqual(r["error"], abs(f[2] - 2.0), delta=1e-12)
        self.assertEqual(r["note"], "")

    def test_first_order_from_below(self):
        f = [5.0 - 0.7 * h for h in (0.4, 0.2, 0.1)]
        r = ad.richardson(*f)
        self.assertAlmostEqual(r["order"], 1.0, delta=1e-10)
        self.assertAlmostEqual(r["extrapolated"], 5.0, delta=1e-12)

    def test_not_asymptotic(self):
        for f in ([1.0, 2.0, 1.5], [1.0, 1.1, 1.3]):       # oscillating; diverging
            r = ad.richardson(*f)
            self.assertIn("not in the asymptotic range", r["note"])
            self.assertTrue(math.isnan(r["order"]) and math.isnan(r["extrapolated"]))
            self.assertAlmostEqual(r["error"], 3.0 * abs(f[2] - f[1]), delta=1e-12)

    def test_unchanged(self):
        r = ad.richardson(4.0, 4.0, 4.0)
        self.assertEqual(r["error"], 0.0)
        self.assertEqual(r["extrapolated"], 4.0)


class Validation(unittest.TestCase):
    """The arithmetic of tools/adapt_validation.py (the study itself is too long for the suite)."""

    @classmethod
    def setUpClass(cls):
        sys.path.insert(0, os.path.join(ROOT, "tools"))
        import adapt_validation
        cls.v = adapt_validation

    def test_energy_extrapolation(self):
        # U_inf - U = C N^-q through three points: U_inf, C and q back to round-off
        N = np.array([900.0, 3700.0, 15000.0])
        U = 5.0 - 3.0 * N ** -0.7
        Uinf, C, q = self.v.extrapolate(N, U)
        self.assertAlmostEqual(Uinf, 5.0, delta=1e-9)
        self.assertAlmostEqual(C, 3.0, delta=1e-6)
        self.assertAlmostEqual(q, 0.7, delta=1e-8)

    def test_closed_forms(self):
        # Hertz (plane strain, two equal cylinders' E*): p0 a = 2 P' / pi, a of the deck's comment
        h = self.v.hertz_exact()
        self.assertAlmostEqual(h["p0"] * h["a"], 2 * 200.0 / math.pi, delta=1e-9)
        self.assertAlmostEqual(h["a"], 0.5754, delta=5e-5)
        # the punch's edge band: the integral of P'/(pi sqrt(b^2 - x^2)) over 0.9 b..b, by the
        # trapezoidal rule after x = b - t^2 (a smooth integrand), against the arcsine form
        t = np.linspace(0.0, math.sqrt(0.1), 20001)
        f = 2.0 * 100.0 / (math.pi * np.sqrt(2.0 - t * t))
        band = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)))
        self.assertAlmostEqual(self.v.punch_exact()["band_mean"], band / 0.1, delta=1e-6)


class ReferenceFit(unittest.TestCase):
    def test_quadratic_field_reproduced(self):
        # the overkill reference's stresses between its Gauss points (k2d.adapt.ReferenceField: a
        # local quadratic least-squares fit): a quadratic stress field sampled at the 2 x 2 Gauss
        # points of a 20 x 10 grid of squares is reproduced to round-off anywhere in the body,
        # at the corners and along the straight edges too, where the rows of Gauss points
        # made sliver triangles of the Delaunay interpolation used before (values off by 10^3);
        # two materials side by side are not mixed (material 2 carries another field)
        g = 1.0 / math.sqrt(3.0)
        xs, ys = np.meshgrid(np.arange(20) + 0.5, np.arange(10) + 0.5, indexing="ij")
        centres = np.stack([xs.ravel(), ys.ravel()], 1)
        off = 0.5 * g * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]])
        gp = (centres[:, None, :] + off[None]).reshape(-1, 2)
        elem = np.repeat(np.arange(len(centres)), 4) + 1
        mat = np.where(centres[:, 0] < 10, 1, 2)

        def field(p, m):
            x, y = p[:, 0], p[:, 1]
            f = np.stack([1 + 2 * x - y + 0.3 * x * x, 3 - x * y, 0.5 * y * y - x, 2 + 0 * x], 1)
            return np.where((m == 1)[:, None], f, -7 * f + 5)

        class Mesh:
            gauss_element, gauss_coordinates, material = elem, gp, mat
            coordinates = np.zeros((1, 2))

        class Last:
            estimated_error = 0.0

            @staticmethod
            def field(name):
                return field(gp, mat[elem - 1])

        class Reference:
            path, mesh, last = "synthetic", Mesh, Last

        ref = ad.ReferenceField(Reference)
        rng = np.random.default_rng(7)
        pts = np.concatenate([rng.uniform([0, 0], [10, 10], (300, 2)), rng.uniform([10, 0], [20, 10], (300, 2)),
                              [[0, 0], [10 - 1e-9, 10], [0, 5], [5, 0], [20, 10], [15, 10]]])
        m = np.where(pts[:, 0] < 10, 1, 2)
        np.testing.assert_allclose(ref(pts, m), field(pts, m), rtol=0, atol=1e-8)
        self.assertGreater(len(pts), 600)


class CardDeck(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = work_dir("adapt_cards_")
        cls.exe = find_or_build(os.environ.get("K2D_EXECUTABLE"))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work, ignore_errors=True)

    def solve(self, deck):
        base = os.path.join(self.work, os.path.splitext(os.path.basename(deck))[0])
        h5 = base + ".h5"
        rc = subprocess.call([self.exe, deck, "-o", h5, "-l", base + ".lis", "-q"], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
        self.assertIn(rc, (0, 4), deck)      # 4: the explicit scheme's drift in the V1 decks (their own checks say so)
        return Result(h5)

    def test_patch_tests_survive_splitting(self):
        for name in ("v1_plane_q8_graded", "v1_axi_q4"):
            decks = [os.path.join(CONTACT, name + ".dat")]
            for level in (1, 2):
                decks.append(os.path.join(self.work, "%s_%d.dat" % (name, level)))
                refine_file(decks[-2], decks[-1])
            res = [self.solve(d) for d in decks]
            mats = ad.deck_materials(decks[0])
            for k, r in enumerate(res):
                with self.subTest(deck=name, level=k):
                    p = r.last.contact("pressure")
                    np.testing.assert_allclose(p, 1.0, atol=1e-9)
                    self.assertAlmostEqual(r.contact.area.sum() / res[0].contact.area.sum(), 1.0, delta=1e-12)
                    fn = r.last.contact("force_normal").sum()
                    self.assertAlmostEqual(fn / res[0].last.contact("force_normal").sum(), 1.0, delta=1e-9)
                    self.assertEqual(r.contact.npair, 2 ** k * (res[0].contact.npair - 1) + 1)
                    self.assertEqual(len(r.mesh.element_nodes), 4 ** k * len(res[0].mesh.element_nodes))
                    self.assertLess(ad.indicator(r, mats)[1], 1e-9)

    def test_triangles_split(self):
        deck = os.path.join(self.work, "tri.dat")
        with open(deck, "w") as f:
            f.write("TITLE\nt\nCONTROL\n    3    1    2    1    3    1    0\nELEMENTS\n    1    1    1    2    3\n"
                    "NODES\n    1       0.0       0.0\n    2       2.0       0.0\n    3       0.0       2.0\n"
                    "RESTRAINTS\n    1   11\n    2   01\nMATERIALS\n    1    1000.0       0.3       1.0\n"
                    "LOADS\nEDGE\n    1    2    3            1.0       1.0\nEND\n")
        out = os.path.join(self.work, "tri_1.dat")
        refine_file(deck, out)
        d = read_card_deck(out)
        self.assertEqual((len(d.nodes), len(d.elements)), (6, 4))
        area = 0.0
        for mat, c in d.elements.values():
            (x1, y1), (x2, y2), (x3, y3) = (d.nodes[i] for i in c)
            a = 0.5 * ((x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1))
            self.assertGreater(a, 0.0)          # anticlockwise children
            area += a
        self.assertAlmostEqual(area, 2.0, delta=1e-12)
        self.assertEqual(d.restraints[4][0], "01")     # the midpoint of the restrained edge 1-2
        self.assertEqual(len(d.edge), 2)               # the loaded edge 2-3 in two halves
        self.solve(out)

    def test_q9_split(self):
        # one Q9 square 2 x 2 in uniform tension 1 (plane stress): after two splittings 16 Q9
        # with their own centre nodes, and the stress is still exactly uniform
        deck = os.path.join(self.work, "q9.dat")
        xy = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 0), (2, 1), (1, 2), (0, 1), (1, 1)]
        with open(deck, "w") as f:
            f.write("TITLE\nq9\nCONTROL\n    9    1    3    1    9    1    0\nELEMENTS\n    1    1"
                    + "".join("%5d" % k for k in range(1, 10)) + "\nNODES\n"
                    + "".join("%5d%10.1f%10.1f\n" % (k + 1, x, y) for k, (x, y) in enumerate(xy))
                    + "RESTRAINTS\n    1   11\n    4   10\n    8   10\nMATERIALS\n    1    1000.0       0.3       1.0\n"
                    + "LOADS\nEDGE\n    1    2    6    3      -1.0      -1.0      -1.0\nEND\n")
        decks = [deck, os.path.join(self.work, "q9_1.dat"), os.path.join(self.work, "q9_2.dat")]
        refine_file(decks[0], decks[1])
        refine_file(decks[1], decks[2])
        d = read_card_deck(decks[2])
        self.assertEqual((len(d.nodes), len(d.elements)), (81, 16))
        for mat, c in d.elements.values():      # the centre node is the mean of the corners
            centre = np.mean([d.nodes[i] for i in c[:4]], axis=0)
            np.testing.assert_allclose(d.nodes[c[8]], centre, atol=1e-12)
        s = self.solve(decks[2]).last.field("stress_gauss")
        np.testing.assert_allclose(s[:, 0], 1.0, atol=1e-10)   # a constant stress: round-off
        np.testing.assert_allclose(s[:, 1:3], 0.0, atol=1e-10)

    def test_lame_cylinder(self):
        out = os.path.join(self.work, "lame")
        rc, text = run_tool(LAME, "--target", "0.5", "-o", out, "--exe", self.exe)
        self.assertEqual(rc, 0, text)
        rows = read_rows(os.path.join(out, "lame_cylinder_adapt.csv"))
        self.assertEqual([int(r["elements"]) for r in rows], [8, 32, 128])     # three meshes for Richardson
        for name in ("lame_cylinder_adapt.md", "lame_cylinder_adapt.png", "lame_cylinder.h5", "lame_cylinder.xdmf",
                     "lame_cylinder.png"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        # the exact energy-norm error: ||u||^2 = work of the bore pressure = 2 pi a H p u(a) (u_r(a)
        # is uniform along the slice), and ||u - u_h||^2 = ||u||^2 - ||u_h||^2 (Galerkin)
        E, nu, a, b, p = 2e5, 0.3, 10.0, 20.0, 100.0
        A, B = p * a * a / (b * b - a * a), p * a * a * b * b / (b * b - a * a)
        ua = (1 + nu) / E * ((1 - 2 * nu) * A * a + B / a)
        effs = []
        for r in rows:
            res = Result(os.path.join(out, "steps_uniform", "lame_cylinder_%02d.h5" % int(r["step"])))
            self.assertEqual(r["source"], "program")        # the program's estimate, not the fallback
            xy, u = res.mesh.coordinates, res.last.field("displacement")
            uha = u[np.abs(xy[:, 0] - a) < 1e-9, 0].mean()
            true = math.sqrt((ua - uha) / ua)
            effs.append(float(r["estimated_error"]) / true)
        print("Lame effectivities (8, 32, 128 elements): %s" % ", ".join("%.3f" % e for e in effs))
        # issue 23's band: effectivity in [0.7, 1.5] at every level past the coarsest (measured
        # 0.98 and 1.00 there: the bound fails an estimate off by 30 % below or 50 % above).  The
        # coarsest mesh, two Q8 across the wall, is exempt (a recovery patch spans the whole wall,
        # not the asymptotic range: measured 1.68); it is reported, and only held to a factor 3
        # (an estimate off by an order of magnitude there is still a fault)
        self.assertTrue(1.0 / 3.0 < effs[0] < 3.0, "coarsest effectivity %.3f" % effs[0])
        for k, eff in enumerate(effs[1:], 1):
            with self.subTest(level=k):
                self.assertTrue(0.7 <= eff <= 1.5, "effectivity %.3f" % eff)
        # and it approaches 1 under refinement (asymptotic exactness of the recovery)
        self.assertLess(abs(effs[-1] - 1.0), abs(effs[1] - 1.0) + 0.02)
        # the true error of tools/adapt_validation.py, ||sigma_ref - sigma_h|| integrated by the
        # mesh's Gauss rules (k2d.adapt.reference_error), needs no Galerkin orthogonality; with the
        # closed-form stresses as the reference it is the exact error above: measured to 3e-4,
        # 8e-5, 1e-5 (the Gauss rules on the 1/r^2 field); 1 % fails a wrong volume weight (2 pi r,
        # the Jacobian), a wrong compliance or a stress column mixed up by far more
        mats = ad.deck_materials(LAME)

        def lame_stress(points, material):
            r = points[:, 0]
            return np.stack([A - B / r ** 2, np.full(len(r), 2 * nu * A), np.zeros(len(r)), A + B / r ** 2], 1)
        results = [Result(os.path.join(out, "steps_uniform", "lame_cylinder_%02d.h5" % int(r["step"]))) for r in rows]
        trues = []
        for res in results:
            xy, u = res.mesh.coordinates, res.last.field("displacement")
            true = math.sqrt((ua - u[np.abs(xy[:, 0] - a) < 1e-9, 0].mean()) / ua)
            trues.append(true)
            with self.subTest(elements=len(res.mesh.element_nodes)):
                self.assertAlmostEqual(ad.reference_error(res, mats, lame_stress)[0] / true, 1.0, delta=0.01)
        # against the finest mesh as an overkill reference (its Gauss-point stresses fitted
        # locally): the coarsest mesh's error within the reference's own error, 6 % of it here
        # (measured 1.008)
        field = ad.ReferenceField(results[-1])
        self.assertAlmostEqual(ad.reference_error(results[0], mats, field)[0] / trues[0], 1.0, delta=0.08)
        # Richardson on the largest von Mises stress (at the Gauss points nearest the bore,
        # 0.113 h from it): extrapolated to h = 0 it is the closed form at the bore
        s_r, s_t, s_z = A - B / a ** 2, A + B / a ** 2, 2 * nu * A
        vm = math.sqrt(0.5 * ((s_r - s_t) ** 2 + (s_t - s_z) ** 2 + (s_z - s_r) ** 2))
        with open(os.path.join(out, "lame_cylinder_adapt.md")) as f:
            md = f.read()
        m = re.search(r"\| largest von Mises stress \| ([-\d.]+) \| ([-\d.]+) \| ([-\d.]+) \| ([-\d.e+]+) \|", md)
        self.assertIsNotNone(m, md)
        finest, order, ext, err = (float(v) for v in m.groups())
        self.assertAlmostEqual(order, 1.0, delta=0.1)          # the distance of the Gauss point: O(h)
        # the finest mesh errs by 1.6 N/mm2; the extrapolation must remove at least 80 % of it
        self.assertLess(abs(ext - vm), 0.2 * abs(finest - vm))
        # and the error it states for the finest mesh is that mesh's error within 20 %
        self.assertAlmostEqual(err / abs(finest - vm), 1.0, delta=0.2)

    def test_tied_plate_survives_splitting(self):
        # V2: a block pressed by a force on its tied top face (TIES 01: a rigid plate) and sheared
        # by a prescribed displacement; p_n = 1 and p_T = -0.1 at every pair after splitting (the
        # splitting keeps the deck's restraints, loads, surfaces and ties consistent).  The block
        # is so stiff that new top nodes left out of the tie would not show in p_n: the tie's
        # members are counted below.
        decks = [os.path.join(CONTACT, "v2_tangential.dat")]
        for level in (1, 2):
            decks.append(os.path.join(self.work, "v2_tangential_%d.dat" % level))
            refine_file(decks[-2], decks[-1])
        for k, deck in enumerate(decks):
            r = self.solve(deck)
            with self.subTest(level=k):
                self.assertEqual(r.contact.npair, 2 ** k * 4 + 1)
                # the coarse deck is off by 3e-10; the stiff block (E = 1e9 on springs of
                # 100 N/mm3) magnifies round-off with the number of equations (measured 6e-9 on
                # the finest): 1e-7
                np.testing.assert_allclose(r.last.contact("pressure"), 1.0, rtol=1e-7)
                np.testing.assert_allclose(r.last.contact("shear"), -0.1, rtol=1e-7)
        d = read_card_deck(decks[2])
        tied = set()
        for code, ids in d.ties:
            self.assertEqual(code, "01")
            tied.update(ids)
        self.assertEqual(len(tied), 17)        # the 5 nodes of the top face, 17 after two splittings

    def test_pairs_refused(self):
        deck = os.path.join(ROOT, "tests", "decks", "bad", "bad_contact_pair_no_area.dat")
        rc, text = run_tool(deck, "--target", "0.1", "-o", os.path.join(self.work, "pairs"), "--exe", self.exe)
        self.assertEqual(rc, 2, text)
        self.assertRegex(text, r"bad_contact_pair_no_area\.dat:\d+: contact PAIRS cards are not supported")
        self.assertNotIn("level 0", text)      # refused before any run
        self.assertNotIn("Traceback", text)
        with self.assertRaises(RefineError):
            read_card_deck(deck)


class Sizes(unittest.TestCase):
    def test_equidistribution(self):
        rng = np.random.default_rng(7)
        eta = rng.uniform(1e-4, 1e-2, 200)
        h = rng.uniform(0.5, 2.0, 200)
        for order in (1, 2):
            hnew, n = ad.new_sizes(eta, h, np.full(200, order), 0.01, shrink=(1e-9, 1e9), safety=1.0)
            s = hnew / h
            per_element = eta ** 2 * s ** (2 * order + 2)      # the error^2 of one new element
            np.testing.assert_allclose(per_element, per_element[0], rtol=1e-10)
            self.assertAlmostEqual(np.sum(eta ** 2 * s ** (2 * order)), 0.01 ** 2, delta=1e-15)
            self.assertAlmostEqual(n, np.sum(1 / s ** 2), delta=1e-9 * n)

    def test_budget(self):
        eta = np.full(100, 0.01)
        hnew, n = ad.new_sizes(eta, np.ones(100), np.ones(100), 1e-4, max_elements=400)
        self.assertAlmostEqual(n, 400.0, delta=1e-9)

    def test_growth_limit(self):
        # a long way to the target (eta 0.1 -> 0.001) without a limit asks for many times the
        # elements;
        # with max_growth = 4 the step aims at a larger target of the same equidistributed shape
        rng = np.random.default_rng(3)
        eta = rng.uniform(1e-3, 3e-2, 300)
        h = np.ones(300)
        free, n_free = ad.new_sizes(eta, h, np.ones(300), 1e-3, shrink=(1e-9, 1e9))
        self.assertGreater(n_free, 20 * 300)
        lim, n_lim = ad.new_sizes(eta, h, np.ones(300), 1e-3, shrink=(1e-9, 1e9), max_growth=4.0)
        self.assertAlmostEqual(n_lim, 4.0 * 300, delta=1e-6 * n_lim)
        self.assertAlmostEqual(n_lim, np.sum(1 / lim ** 2), delta=1e-9 * n_lim)
        ratio = lim / free                # one factor for every element: the same shape
        np.testing.assert_allclose(ratio, ratio[0], rtol=1e-10)
        self.assertGreater(ratio[0], 1.5)
        # a mesh within the growth allowed is not touched by the limit
        near, _ = ad.new_sizes(eta, h, np.ones(300), 0.5, shrink=(1e-9, 1e9))
        near_lim, _ = ad.new_sizes(eta, h, np.ones(300), 0.5, shrink=(1e-9, 1e9), max_growth=4.0)
        np.testing.assert_array_equal(near, near_lim)

    def test_singular_rate(self):
        # an element at a singular point (rate lambda = 1/2) keeps eta^2 s^(2 lambda) in its
        # child at the point: its size makes that equal to the new elements' common error^2
        eta = np.full(50, 1e-3)
        eta[7] = 5e-2
        rate = np.zeros(50)
        rate[7] = 0.5
        h = np.ones(50)
        smooth, _ = ad.new_sizes(eta, h, np.ones(50), 0.01, shrink=(1e-9, 1e9), safety=1.0)
        sing, _ = ad.new_sizes(eta, h, np.ones(50), 0.01, shrink=(1e-9, 1e9), safety=1.0, rate=rate)
        per_element = eta[0] ** 2 * sing[0] ** 4          # a smooth Q4 element: eta^2 s^(2p+2)
        self.assertAlmostEqual(eta[7] ** 2 * sing[7] ** 1, per_element, delta=1e-10 * per_element)
        self.assertLess(sing[7], 0.1 * smooth[7])
        np.testing.assert_array_equal(np.delete(sing, 7), np.delete(smooth, 7))


class _Contact(dict):
    """A stand-in for a result's /contact group (k2d.results.ContactDefinition): attributes and
    `in`."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name)

    @property
    def npair(self):
        return len(self["node_a"])


class _Step:
    def __init__(self, data):
        self.data, self.attrs, self.number = data, {}, 1

    def contact(self, name):
        return self.data[name]


class _Result:
    """A stand-in for a result with one increment and node-to-node pairs along y = 0: node a of
    pair j is node j, node b node npair + j."""

    def __init__(self, x, gap, pressure, closed):
        n = len(x)
        self.contact = _Contact(node_a=np.arange(1, n + 1), node_b=np.arange(n + 1, 2 * n + 1),
                                position=np.stack([x, np.zeros(n)], axis=1), gap=np.asarray(gap, float),
                                interface=np.ones(n, dtype=int))
        step = _Step({"pressure": np.asarray(pressure, float), "normal_state": np.asarray(closed, int)})
        self.steps, self.last = [step], step


class SingularEdges(unittest.TestCase):
    """The contact's singular edges (k2d.adapt.singular_end), the curved zones whose spacing
    --uniform-contact makes uniform (curved_contact_zones, contact_spacing)."""

    @staticmethod
    def mid_pressures(edges, p):
        """The mean of p over each tributary zone [edges[i], edges[i+1]] (a pair's pressure F/A),
        by a 2000-point midpoint rule."""
        out = []
        for a, b in zip(edges, edges[1:]):
            t = a + (b - a) * (np.arange(2000) + 0.5) / 2000
            out.append(float(np.mean(p(t))))
        return np.array(out)

    def test_punch_edge_singular_hertz_axis_not(self):
        edges = np.linspace(0.0, 1.0, 11)
        mid = 0.5 * (edges[1:] + edges[:-1])
        kc = np.arange(10)
        # a flat punch's half face, p ~ (1 - x^2)^-1/2 (Sadowsky): the outer end is singular,
        # the axis end (the smallest pressure) is not
        punch = self.mid_pressures(edges, lambda x: 1.0 / np.sqrt(np.maximum(1.0 - x * x, 1e-300)))
        self.assertTrue(ad.singular_end(punch, mid, kc, -1))
        self.assertFalse(ad.singular_end(punch, mid, kc, 0))
        # Hertz's half zone, p ~ (1 - x^2)^1/2: neither end -- the axis pair has the largest
        # pressure, above the mean (the old rule's only test, which took it for singular), also
        # with 1 % of noise on it
        hertz = self.mid_pressures(edges, lambda x: np.sqrt(np.maximum(1.0 - x * x, 0.0)))
        self.assertGreater(hertz[0], np.mean(hertz))
        for noise in (1.0, 1.01):
            h = hertz.copy()
            h[0] *= noise
            self.assertFalse(ad.singular_end(h, mid, kc, 0))
            self.assertFalse(ad.singular_end(h, mid, kc, -1))
        # a punch graded towards its edge: still singular
        graded = 1.0 - (1.0 - np.linspace(0.0, 1.0, 11)) ** 2
        self.assertTrue(ad.singular_end(self.mid_pressures(graded, lambda x: 1.0 / np.sqrt(
            np.maximum(1.0 - x * x, 1e-300))), 0.5 * (graded[1:] + graded[:-1]), kc, -1))
        # Hertz's axis on a coarse contact mesh, where the ellipse itself falls by more than
        # SINGULAR_RISE from the axis pair to the next: the slope falls towards the axis
        coarse = np.linspace(0.0, 1.0, 4)
        hc = self.mid_pressures(coarse, lambda x: np.sqrt(np.maximum(1.0 - x * x, 0.0)))
        self.assertGreater(hc[0], ad.SINGULAR_RISE * hc[1])
        self.assertFalse(ad.singular_end(hc, 0.5 * (coarse[1:] + coarse[:-1]), np.arange(3), 0))

    def test_curved_zone_uniform_spacing(self):
        # a cylinder's chords on a graded contact mesh: the zone's gaps are x^2 / (2R), not
        # affine in x, so the zone is curved and every node of it takes the smallest size
        R, a = 15.0, 0.6
        x = np.concatenate([np.linspace(0.0, 0.3, 7), np.linspace(0.35, 2.0, 12)])
        closed = (x <= a).astype(int)
        p = np.where(closed > 0, np.sqrt(np.maximum(1 - (x / a) ** 2, 0.0)) + 0.01, 0.0)
        r = _Result(x, x * x / (2 * R), p, closed)
        zones = ad.curved_contact_zones(r)
        self.assertEqual(len(zones), 1)
        pairs = zones[0][1]
        # the closed pairs and a margin beyond the zone's end, not the far pairs
        xz = x[pairs]
        self.assertTrue(set(np.where(closed > 0)[0]) <= set(pairs.tolist()))
        self.assertGreater(xz.max(), a)
        self.assertLess(xz.max(), a * (1 + ad.CONTACT_MARGIN) + 0.16)
        nodal = np.concatenate([0.05 + x, 0.07 + x])       # graded: small at the axis
        out, changed = ad.contact_spacing(r, nodal)
        zone_nodes = np.concatenate([pairs, pairs + len(x)])
        np.testing.assert_array_equal(out[zone_nodes], np.full(len(zone_nodes), 0.05))
        self.assertEqual(changed, len(zone_nodes) - 1)
        rest = np.setdiff1d(np.arange(2 * len(x)), zone_nodes)
        self.assertTrue(len(rest))
        np.testing.assert_array_equal(out[rest], nodal[rest])
        # a flat surface (gaps 0 or a tilt) has no curved zone, nor has a zone ended by a
        # singular edge
        for gap in (np.zeros(len(x)), 0.01 * x):
            self.assertEqual(ad.curved_contact_zones(_Result(x, gap, p, closed)), [])
        punch = np.where(closed > 0, 1.0 / np.sqrt(np.maximum(1 - (x / (1.001 * a)) ** 2, 1e-12)), 0.0)
        self.assertEqual(ad.curved_contact_zones(_Result(x, x * x / (2 * R), punch, closed)), [])


class KeyOutputConvergence(unittest.TestCase):
    """A key output whose successive differences do not decrease (observed order <= 0) is flagged
    "not converging (singular point?)" in the table and the terminal."""

    def test_note(self):
        hs = (1.0, 0.5, 0.25)
        self.assertEqual(ad.convergence_note([2.0 + h * h for h in hs]), "")
        # a stress at a singular point: sigma ~ h^-1/2 grows, its differences grow
        self.assertEqual(ad.convergence_note([h ** -0.5 for h in hs]), ad.NOT_CONVERGING)
        # differences that stay equal: observed order 0
        self.assertEqual(ad.convergence_note([1.0, 1.5, 2.0]), ad.NOT_CONVERGING)
        # a change below SIGNIFICANT_CHANGE of the value is no singular point's growth
        self.assertEqual(ad.convergence_note([1.0, 1.002, 1.004]), "")
        self.assertEqual(ad.convergence_note([1.0, 1.02, 1.04]), ad.NOT_CONVERGING)
        # oscillating: not this flag's (Richardson's table says "oscillating")
        self.assertEqual(ad.convergence_note([1.0, 1.2, 0.8]), "")
        self.assertEqual(ad.convergence_note([1.0, 1.2, 1.1]), "")
        self.assertEqual(ad.convergence_note([3.0, 3.0, 3.0]), "")
        self.assertEqual(ad.convergence_note([1.0, 2.0]), "")
        self.assertEqual(ad.convergence_note([1.0, float("nan"), 2.0]), "")
        # unequal steps (adaptive meshes): f = 5 + 100 / N converges, though its second
        # difference (a step of 4.5 in N) exceeds its first (a step of 1.1)
        N = [1000.0, 1100.0, 5000.0]
        f = [5.0 + 100.0 / n for n in N]
        self.assertGreater(abs(f[2] - f[1]), abs(f[1] - f[0]))
        self.assertEqual(ad.convergence_note(f, N), "")
        self.assertEqual(ad.convergence_note(f), ad.NOT_CONVERGING)     # taken as equal steps
        # a stress growing like N^(1/4) is flagged on unequal steps too
        self.assertEqual(ad.convergence_note([n ** 0.25 for n in N], N), ad.NOT_CONVERGING)
        # Richardson's note says it as well
        self.assertIn(ad.NOT_CONVERGING, ad.richardson(1.0, 1.1, 1.3)["note"])

    def rows(self):
        N = [1000, 4000, 16000, 64000]
        return [{"method": "adaptive", "step": k, "elements": n // 2, "dofs": n, "estimated_error": 0.1 / (k + 1),
                 "source": "program", "cpu_solve": 0.1, "cpu_mesh": 0.1, "peak_pressure": 221.3 + 50.0 / n,
                 "width": 1.15, "approach": 0.02 - 1.0 / n, "von_mises": 3.0 * n ** 0.25,
                 "slip_share": float("nan"), "law_drift": 0.0, "scheme": "", "exit": 0} for k, n in enumerate(N)]

    def test_table_and_terminal(self):
        rows = ad.cumulate(self.rows())
        flags = ad.convergence_flags(rows)
        self.assertEqual([f[0] for f in flags["adaptive"]], ["largest von Mises stress"])
        self.assertEqual(rows[0]["not_converging"], "")
        self.assertEqual(rows[1]["not_converging"], "")
        for r in rows[2:]:
            self.assertEqual(r["not_converging"], "largest von Mises stress: " + ad.NOT_CONVERGING)
        work = work_dir("k2d_flags_")
        md = ad.write_tables(rows, {}, work, "m", "m.dat", 0.01, 100000)
        with open(md) as f:
            text = f.read()
        self.assertIn("Key outputs that do not converge", text)
        self.assertIn("largest von Mises stress: **%s**" % ad.NOT_CONVERGING, text)
        self.assertNotIn("peak pressure: **", text)
        csv_rows = read_rows(os.path.join(work, "m_adapt.csv"))
        self.assertEqual(len(csv_rows), 4)
        self.assertIn(ad.NOT_CONVERGING, csv_rows[3]["not_converging"])
        self.assertEqual(csv_rows[1]["not_converging"], "")
        lines = []
        ad.print_flags(rows, log=lines.append)
        self.assertEqual(len(lines), 1)
        self.assertIn("largest von Mises stress", lines[0])
        self.assertIn(ad.NOT_CONVERGING, lines[0])
        # a converging von Mises stress: no section, no line
        rows = self.rows()
        for r in rows:
            r["von_mises"] = 4.0 - 100.0 / r["dofs"]
        ad.cumulate(rows)
        md = ad.write_tables(rows, {}, work, "c", "c.dat", 0.01, 100000)
        with open(md) as f:
            self.assertNotIn("do not converge", f.read())
        lines = []
        ad.print_flags(rows, log=lines.append)
        self.assertEqual(lines, [])
        shutil.rmtree(work, ignore_errors=True)


@unittest.skipIf(shutil.which("gmsh") is None, "gmsh not installed")
class QuadraticMeshes(unittest.TestCase):
    def test_no_six_node_triangles(self):
        # a .geo asking for second order without recombination: gmsh alone makes 6-node triangles
        # (gmsh type 9, which kontakt2d does not read); through tools/adapt.py's meshing, with a
        # graded size field too, only 8-node quadrilaterals come out
        work = work_dir("adapt_quad_")
        self.addCleanup(shutil.rmtree, work, ignore_errors=True)
        geo = os.path.join(work, "tri.geo")
        with open(geo, "w") as f:
            f.write("Point(1) = {0, 0, 0, 0.3}; Point(2) = {2, 0, 0, 0.05};\n"
                    "Point(3) = {0, 1.5, 0, 0.3};\n"
                    "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};\n"
                    "Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};\n"
                    'Physical Surface("body") = {1};\n'
                    "Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;\n")
        plain = os.path.join(work, "plain.msh")
        subprocess.run(["gmsh", "-2", "-format", "msh41", geo, "-o", plain], capture_output=True,
                       check=True)
        self.assertGreater(ad.msh_element_types(plain).get(9, 0), 10)
        for factor in (1.0, 0.5):
            msh = os.path.join(work, "adapt_%g.msh" % factor)
            ad.gmsh_mesh(geo, msh, msh + ".log", factor=factor)
            types = ad.msh_element_types(msh)
            self.assertEqual(set(types), {16}, types)
            self.assertGreater(types[16], 10)


def msh_curve_nodes(path, curve):
    """(n, 2) coordinates of the nodes inside gmsh's curve entity `curve` of a .msh 4.1 file."""
    with open(path) as f:
        lines = f.read().split("\n")
    i = lines.index("$Nodes")
    nblocks, j, out = int(lines[i + 1].split()[0]), i + 2, []
    for _ in range(nblocks):
        dim, tag, _par, n = (int(v) for v in lines[j].split())
        j += 1 + n
        if (dim, tag) == (1, curve):
            out += [[float(v) for v in lines[j + k].split()[:2]] for k in range(n)]
        j += n
    return np.array(out).reshape(-1, 2)


@unittest.skipIf(shutil.which("gmsh") is None, "gmsh not installed")
class CurvedContact(unittest.TestCase):
    def test_uniform_meshes_on_the_circle(self):
        # the uniform route remeshes the .geo (Mesh.MeshSizeFactor) rather than splitting
        # elements: the nodes of the cylinder's contact arc of hertz_uniform.geo lie on the circle
        # (centre (0, R), R = 15) at every level, the midside nodes of the Q8 meshes too -- no
        # chord facets in the gap of the curved surface.  1e-9 R: gmsh's coordinates to round-off
        # (a node left at the middle of a chord of the level's spacing h would be h^2 / (8 R),
        # 6e-4 mm at h = 0.29, off it)
        work = work_dir("adapt_curve_")
        self.addCleanup(shutil.rmtree, work, ignore_errors=True)
        R = 15.0
        for geo, factor in (("hertz_uniform.geo", 1.0), ("hertz_uniform.geo", 0.25), ("hertz_ref_q8.geo", 1.0)):
            src = os.path.join(ROOT, "inputs", "adapt", geo)
            msh = os.path.join(work, "%s_%g.msh" % (geo, factor))
            ad.gmsh_mesh(src, msh, msh + ".log", factor=factor)
            xy = msh_curve_nodes(msh, 1)
            with self.subTest(geo=geo, factor=factor):
                self.assertGreater(len(xy), 0)
                np.testing.assert_allclose(np.hypot(xy[:, 0], xy[:, 1] - R), R, rtol=0, atol=1e-9 * R)


class GeoDeck(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = work_dir("adapt_geo_")
        cls.exe = find_or_build(os.environ.get("K2D_EXECUTABLE"))
        for ext in (".dat", ".geo"):
            shutil.copy(PUNCH + ext, cls.work)
        cls.deck = os.path.join(cls.work, "punch_adapt.dat")
        cls.out = os.path.join(cls.work, "out")
        cls.rc, cls.text = run_tool(cls.deck, "--target", "0.05", "--compare", "-o", cls.out, "--exe", cls.exe)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work, ignore_errors=True)

    def test_target_reached_with_fewer_dofs(self):
        self.assertEqual(self.rc, 0, self.text)
        rows = read_rows(os.path.join(self.out, "punch_adapt_adapt.csv"))
        ada = [r for r in rows if r["method"] == "adaptive"]
        uni = [r for r in rows if r["method"] == "uniform"]
        self.assertLessEqual(float(ada[-1]["estimated_error"]), 0.05)
        self.assertGreater(len(ada), 1)                 # the first mesh does not meet the target
        first_uni = [r for r in uni if float(r["estimated_error"]) <= 0.05]
        self.assertTrue(first_uni, "uniform remeshing never reached the target")
        # measured 916 adaptive against 1944 uniform DOFs: at least 1.5 times fewer
        self.assertLess(1.5 * int(ada[-1]["dofs"]), int(first_uni[0]["dofs"]))
        # the estimate falls, and its source is named
        self.assertLess(float(ada[-1]["estimated_error"]), float(ada[0]["estimated_error"]))
        self.assertIn(ada[0]["source"], ("program", "stress recovery"))
        for name in ("punch_adapt_adapt.md", "punch_adapt_adapt.png", "punch_adapt.h5", "punch_adapt.png"):
            self.assertTrue(os.path.isfile(os.path.join(self.out, name)), name)
        self.assertFalse(os.path.exists(os.path.join(self.work, "punch_adapt.msh")))   # nothing beside the deck

    def test_refined_at_the_punch_corner(self):
        r = Result(os.path.join(self.out, "steps_adaptive", "punch_adapt_01.h5"))
        h, _ = ad.element_sizes(r)
        xy = r.mesh.coordinates
        centre = np.array([xy[c[:4] - 1].mean(axis=0) for c in r.mesh.connectivity])
        dist = np.hypot(centre[:, 0] - 25.0, centre[:, 1])
        # the stress singularity at the punch's edge (25, 0) gets the smallest elements
        self.assertLess(np.median(h[dist < 3.0]), 0.5 * np.median(h[dist > 20.0]))

    def test_traction_sizes(self):
        r = Result(os.path.join(self.out, "steps_adaptive", "punch_adapt_01.h5"))
        want = ad.traction_sizes(r, 0.01)
        self.assertTrue(want)
        punch = set(int(n) - 1 for n in r.contact.node_a)
        node = min((n for n in want if n in punch), key=want.get)
        x, y = r.mesh.coordinates[node]
        # the pressure bends most towards the edge of the punch (x = 25): the punch node asking
        # for the smallest size lies in the punch's outer quarter (measured: x = 22.0)
        self.assertGreater(x, 18.75)
        self.assertAlmostEqual(y, 0.0, delta=1e-9)
        # h ~ sqrt(target): a target four times larger allows twice the size, at every node
        want4 = ad.traction_sizes(r, 0.04)
        for n, v in want.items():
            self.assertAlmostEqual(want4[n] / v, 2.0, delta=1e-12)
        h, p = ad.element_sizes(r)
        limited, count = ad.limit_by_tractions(r, np.full(len(h), 1e9), h, 0.01)
        self.assertGreater(count, 0)
        self.assertTrue(np.all(limited >= 0.2 * h - 1e-12))

    def test_program_indicator_used(self):
        # the program writes its estimate into every increment: the tool must take it
        r = Result(os.path.join(self.out, "steps_adaptive", "punch_adapt_00.h5"))
        n = len(r.mesh.element_nodes)
        last = r.last
        self.assertIsNotNone(last.error_indicator)
        eta, est, source = ad.indicator(r, ad.deck_materials(self.deck))
        self.assertEqual(source, "program")
        np.testing.assert_array_equal(eta, np.ravel(last.error_indicator))
        self.assertEqual(eta.shape, (n,))
        self.assertEqual(est, last.estimated_error)
        # the model's estimate is the root sum of squares of the element indicators
        self.assertAlmostEqual(est, math.sqrt(np.sum(eta ** 2)), delta=1e-6 * est)
        # the size field follows the indicator: the element with the largest eta_e shrinks most
        h, p = ad.element_sizes(r)
        hnew, _ = ad.new_sizes(eta, h, p, 0.05, shrink=(1e-9, 1e9))
        self.assertEqual(int(np.argmin(hnew / h)), int(np.argmax(eta)))

    def test_fallback_without_program_indicator(self):
        # a result without the dataset (a file written before the program estimated its error):
        # the stress-recovery estimate of k2d.adapt
        r = Result(os.path.join(self.out, "steps_adaptive", "punch_adapt_00.h5"))
        last = r.last

        class WithoutIndicator:
            """The last increment as a result file without `error_indicator` reads."""
            name, number, attrs = last.name, last.number, last.attrs
            error_indicator = estimated_error = None

            def field(self, key):
                return last.field(key)

        eta, est, source = ad.indicator(r, ad.deck_materials(self.deck), WithoutIndicator())
        self.assertEqual(source, "stress recovery")
        self.assertEqual(eta.shape, (len(r.mesh.element_nodes),))
        self.assertAlmostEqual(est, math.sqrt(np.sum(eta ** 2)), delta=1e-12)
        # both are Zienkiewicz-Zhu recovery estimates of the same solution: they agree within a
        # factor 2 (the recovered stresses differ; a wrong energy weighting or a missing
        # normalisation would be off by far more: thickness 10, E = 4000)
        prog = last.estimated_error
        self.assertTrue(0.5 < est / prog < 2.0, "recovery %.4g against the program's %.4g" % (est, prog))

    def test_budget(self):
        out = os.path.join(self.work, "budget")
        rc, text = run_tool(self.deck, "--target", "0.001", "--max-dofs", "3000", "-o", out, "--exe", self.exe)
        self.assertEqual(rc, 1, text)            # the budget ends it before the target
        rows = read_rows(os.path.join(out, "punch_adapt_adapt.csv"))
        self.assertGreater(len(rows), 1)
        self.assertTrue(all(int(r["dofs"]) <= 3000 for r in rows), [r["dofs"] for r in rows])
        with open(os.path.join(out, "punch_adapt_adapt.md")) as f:
            self.assertIn("**Not reached**", f.read())

    def test_interface_sizes(self):
        # surface A is made the finer side of each contact: node a at most FINER_A times the
        # sizes of the nodes of B it is coupled with; surface B and the other nodes unchanged
        r = Result(os.path.join(self.out, "steps_adaptive", "punch_adapt_01.h5"))
        c = r.contact
        self.assertGreater(c.npair, 0)
        nodal = np.ones(len(r.mesh.coordinates))
        under = {j: [int(v) - 1 for v, w in zip(c.master_nodes[j], c.master_weights[j]) if v > 0 and w != 0]
                 for j in range(c.npair)}
        bnodes = sorted(set(k for b in under.values() for k in b))
        self.assertTrue(bnodes)
        nodal[bnodes] = 0.3                 # surface B asks for the finer mesh
        out = ad.interface_sizes(r, nodal)
        anodes = set(int(n) - 1 for n in c.node_a)
        for j in range(c.npair):
            self.assertLessEqual(out[int(c.node_a[j]) - 1], ad.FINER_A * min(nodal[under[j]]) + 1e-15)
        np.testing.assert_array_equal(out[bnodes], nodal[bnodes])
        rest = [k for k in range(len(nodal)) if k not in anodes]
        np.testing.assert_array_equal(out[rest], nodal[rest])
        # where A is already finer nothing changes
        nodal = np.ones(len(r.mesh.coordinates))
        nodal[list(anodes)] = 0.1
        np.testing.assert_array_equal(ad.interface_sizes(r, nodal), nodal)

    def test_quadratic_contact_remeshed(self):
        # the second adaptive mesh of a Q8 Hertz model: before the interface rule surface B came
        # out 2.5 times as fine as surface A beside the contact zone and the program stopped
        # with E-SEGMENT-SIDE (exit code 3 of the tool); now both meshes solve (exit code 1: the
        # step limit ends the refinement short of the target)
        work = os.path.join(self.work, "hertz_q8")
        os.makedirs(work, exist_ok=True)
        for name in ("hertz_ref_q8.dat", "hertz_ref_q8.geo", "hertz_adapt.geo"):
            shutil.copy(os.path.join(ROOT, "inputs", "adapt", name), work)
        out = os.path.join(work, "out")
        rc, text = run_tool(os.path.join(work, "hertz_ref_q8.dat"), "--target", "0.002", "--max-steps", "2",
                            "-o", out, "--exe", self.exe)
        self.assertEqual(rc, 1, text)
        rows = read_rows(os.path.join(out, "hertz_ref_q8_adapt.csv"))
        self.assertEqual(len(rows), 2)
        self.assertGreater(int(rows[1]["dofs"]), int(rows[0]["dofs"]))

    def test_mesh_deck_without_geo(self):
        d = os.path.join(self.work, "nogeo")
        os.makedirs(d, exist_ok=True)
        shutil.copy(self.deck, d)
        rc, text = run_tool(os.path.join(d, "punch_adapt.dat"), "--target", "0.05", "--exe", self.exe,
                            "-o", os.path.join(d, "out"))
        self.assertEqual(rc, 2, text)
        self.assertIn("has no .geo beside it", text)


if __name__ == "__main__":
    unittest.main()
