#!/usr/bin/python3
"""The arithmetic of tools/adapt_validation.py --scatter (docs/adaptivity.md, "The peak
pressure's scatter"): the tributary mean of Hertz's ellipse each pair is measured against, and
the .geo the study meshes.

* tributary_ellipse: for a pressure that is constant over the zone (a much larger than the
  zone) every pair gets p0 to round-off; on a uniform spacing h inside the zone the hat mean of
  a smooth p is p(x) + p''(x) h^2 / 12 + O(h^4) (the hat's normalised second moment h^2/6,
  times p''/2): the difference from that is below 1e-7 of p0 at h = a/50 within 0.7 a (the
  h^4 remainder measured 2.7e-8), where the h^2 term itself is at least 3.3e-5 -- so the test
  fails for a wrong weight (a box mean gives h^2/6, twice the term) or a wrong zone; the
  one-sided zone of the first pair (the half model's axis) has the mean of the hat over [0, h].
* scatter_geo sets the sizes of the contact curves' end points and the algorithm, and refuses a
  .geo without the lines it changes (exit with a message naming the line).

Run by ctest with PYTHONPATH=<source>/tools (tests/tools/CMakeLists.txt).
"""

import os
import unittest

import numpy as np

import adapt_validation as av
from k2d.build import ROOT


class TributaryEllipse(unittest.TestCase):
    def test_constant_pressure(self):
        x = np.sort(np.random.default_rng(3).uniform(0.0, 1.0, 25))
        got = av.tributary_ellipse(x, 1e6, 7.0)
        self.assertEqual(len(got), 25)
        np.testing.assert_allclose(got, 7.0, rtol=1e-10)

    def test_second_moment_of_the_hat(self):
        a, p0 = 0.5754, 221.29
        h = a / 50.0
        x = np.arange(0.0, 0.7 * a, h)
        got = av.tributary_ellipse(x, a, p0)
        inner = slice(1, len(x) - 1)
        xi = x[inner]
        q = 1.0 - (xi / a) ** 2
        p = p0 * np.sqrt(q)
        p2 = -p0 / a ** 2 * q ** -1.5          # d2p/dx2 of the ellipse
        self.assertGreater(len(xi), 10)
        expected = p + p2 * h ** 2 / 12.0
        self.assertLess(np.max(np.abs(got[inner] - expected)) / p0, 1e-7)
        # the h^2 term is resolved: without it the difference is far above the bound
        self.assertGreater(np.max(np.abs(got[inner] - p)) / p0, 1e-5)

    def test_one_sided_axis_zone(self):
        a, p0, h = 1.0, 1.0, 0.01
        got = av.tributary_ellipse(np.array([0.0, h, 2 * h]), a, p0)
        # hat 1 - s/h on [0, h]: mean of p0 sqrt(1 - s^2) = 1 - s^2/2 + ...: 1 - (h^2/2) (1/6)
        self.assertAlmostEqual(got[0], 1.0 - h ** 2 / 12.0, delta=1e-8)


class ScatterGeo(unittest.TestCase):
    def test_sizes_and_algorithm(self):
        with open(os.path.join(ROOT, "inputs", "adapt", "hertz_adapt.geo")) as f:
            text = f.read()
        geo = av.scatter_geo(text, 0.01, 0.02, 5)
        for line in ("Point(1) = {0, 0, 0, 0.01};", "Point(2) = {c, yc, 0, 0.01};",
                     "Point(11) = {0, 0, 0, 0.02};", "Point(12) = {c, 0, 0, 0.02};", "Mesh.Algorithm = 5;"):
            self.assertIn(line, geo)
        self.assertNotIn("Mesh.Algorithm = 6;", geo)

    def test_boundary_layer(self):
        with open(os.path.join(ROOT, "inputs", "adapt", "hertz_adapt.geo")) as f:
            text = f.read()
        geo = av.scatter_geo(text, 0.01, 0.02, "L")
        self.assertIn("Mesh.Algorithm = 6;", geo)
        self.assertIn("Field[1].CurvesList = {1}; Field[1].Size = 0.01;", geo)
        self.assertIn("Field[2].CurvesList = {11}; Field[2].Size = 0.02;", geo)
        self.assertIn("Field[2].Thickness = 0.16;", geo)
        self.assertEqual(geo.count("BoundaryLayer Field ="), 2)

    def test_missing_line_refused(self):
        with self.assertRaises(SystemExit) as cm:
            av.scatter_geo("Point(1) = {0, 0, 0, h_c};\n", 0.01, 0.02, 5)
        self.assertIn("Point(2)", str(cm.exception))


if __name__ == "__main__":
    unittest.main(verbosity=2)
