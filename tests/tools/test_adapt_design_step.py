#!/usr/bin/python3
"""The increment whose error estimate drives tools/adapt.py and the run summary's second
estimate line: the one of the largest strain energy (docs/adaptivity.md, results-format.md).

A run unloaded to exactly zero ends at a strain energy of round-off; its relative estimate
(55 % on the deck below, whose stresses are uniform and exact on its mesh at every load) says
nothing about the mesh. The deck tests/decks/robust_law/unload_beyond_range.dat is loaded to
its largest factor at increment 10 and unloaded to zero at increment 20; the checks:

* every increment with an estimate carries `energy_norm`, largest at the largest load factor;
* k2d.adapt.design_step picks that increment (not the last), and k2d.adapt.indicator returns
  its estimate, which is the exact state's round-off (below 1e-6) while the last's is not;
* /summary holds the same increment as `peak_estimate_increment` with its estimate.

Run by ctest with PYTHONPATH=<source>/tools and K2D_EXECUTABLE (tests/tools/CMakeLists.txt).
"""

import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from k2d import adapt as ad
from k2d.build import ROOT, find_or_build
from k2d.results import Result

DECK = os.path.join(ROOT, "tests", "decks", "robust_law", "unload_beyond_range.dat")


class DesignStep(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        exe = os.environ.get("K2D_EXECUTABLE") or find_or_build()
        base = os.environ.get("K2D_TEST_WORK")
        if base:
            os.makedirs(base, exist_ok=True)
        cls.work = tempfile.mkdtemp(prefix="k2d_design_step_", dir=base)
        h5 = os.path.join(cls.work, "unload.h5")
        rc = subprocess.run([exe, DECK, "-o", h5, "-l", os.path.join(cls.work, "unload.lis"), "-q"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT).returncode
        assert rc == 0, "the deck must complete (exit %d)" % rc
        cls.r = Result(h5)

    def test_energy_norm_peaks_at_the_largest_load(self):
        steps = [s for s in self.r.steps if s.estimated_error is not None]
        self.assertGreaterEqual(len(steps), 20)
        energy = np.array([float(np.atleast_1d(s.attrs["energy_norm"])[0]) for s in steps])
        lam = np.array([s.load_factor[0] for s in steps])
        self.assertEqual(steps[int(np.argmax(energy))].number, steps[int(np.argmax(lam))].number)
        # unloaded to zero: the end's strain energy is round-off against the peak's
        self.assertLess(energy[-1], 1e-6 * energy.max())

    def test_design_step_is_the_largest_load(self):
        step = ad.design_step(self.r)
        self.assertEqual(step.number, 10)
        self.assertNotEqual(step.number, self.r.last.number)
        mats = ad.deck_materials(DECK)
        _, est, source = ad.indicator(self.r, mats)
        self.assertEqual(source, "program")
        self.assertEqual(est, step.estimated_error)
        # the uniform state is exact: round-off at the peak, not at the end
        self.assertLess(est, 1e-6)
        self.assertGreater(self.r.last.estimated_error, 0.1)

    def test_summary_names_the_same_increment(self):
        s = self.r.summary
        self.assertEqual(int(s["peak_estimate_increment"]), ad.design_step(self.r).number)
        self.assertAlmostEqual(float(s["peak_estimated_error"]),
                               ad.design_step(self.r).estimated_error, delta=1e-15)
        self.assertLess(float(s["peak_energy_ratio"]), 0.5)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1] + sys.argv[1:])
