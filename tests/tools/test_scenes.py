#!/usr/bin/python3
"""tools/k2d/scenes.py: the generated scenes are reproducible and valid, and the checks of the
campaign fail on results off the law or off the closed form (unittest; tools/scenes.py runs
the campaign itself, registered as tools_scenes_campaign)."""
import math
import os
import tempfile
import unittest

import numpy as np

from k2d import scenes
from k2d.build import find_or_build


class FakeStep:
    def __init__(self, number, lam, data, attrs=None):
        self.number = number
        self.load_factor = np.array([lam])
        self._data = data
        self.attrs = attrs or {}

    def contact(self, name):
        return np.asarray(self._data[name], dtype=float)


class FakeContact:
    def __init__(self, area):
        self.area = np.asarray(area, dtype=float)


class FakeResult:
    def __init__(self, area, steps):
        self.contact = FakeContact(area)
        self.steps = steps


def rough_scene():
    """A uniform rough scene (one material, pressure only, matching meshes)."""
    for seed in range(1, 500):
        sc = scenes.draw(seed)
        if sc.law == "ROUGH" and sc.uniform:
            return sc
    raise AssertionError("no uniform rough scene among the first 500 seeds")


def exact_history(sc, lams, npair=3):
    """The results the law and the closed form give: pressure lambda p0, closure on the branch."""
    steps = []
    pa = 0.0
    for k, lam in enumerate(lams, 1):
        p = lam * sc.p0
        u = scenes.branch_closure(sc, p, pa)
        pa = max(pa, p)
        steps.append(FakeStep(k, lam, {"pressure": [p] * npair, "closure": [u] * npair,
                                       "normal_state": [1 if p >= pa else 2] * npair}))
    return steps


class Draw(unittest.TestCase):
    def test_reproducible(self):
        a, b = scenes.draw(17), scenes.draw(17)
        self.assertEqual(a.__dict__, b.__dict__)
        self.assertNotEqual(scenes.draw(17).__dict__, scenes.draw(18).__dict__)

    def test_ranges(self):
        seen = {"ntype": set(), "nnode": set(), "law": set(), "friction": set(), "history": set(),
                "matching": set()}
        steep = 0
        for seed in range(1, 301):
            sc = scenes.draw(seed)
            for k in seen:
                seen[k].add(getattr(sc, k))
            self.assertTrue(1e3 <= sc.EA <= 1e9 * (1 + 1e-6))
            self.assertTrue(0.0 <= sc.nuA <= 0.45)
            self.assertIn(sc.nstroke, (5, 10, 20, 50, 200))
            if sc.law == "ROUGH":
                # m from the measured surfaces' 0.15 (tools/calibrate.py topography) to 0.8
                self.assertTrue(0.15 <= sc.m <= 0.8)
                steep += sc.m <= 0.22
                self.assertGreaterEqual(sc.m2, sc.m)
                if sc.m2 == sc.m:
                    self.assertLessEqual(sc.cn2, sc.cn)
                else:
                    # the unloading branch admissible to twice the largest pressure (1.2 p0)
                    cn, cn2 = scenes.deck_constants(sc)
                    e = 1.0 / (sc.m2 - sc.m)
                    pstar = min((cn / cn2) ** e, (cn * sc.m / (cn2 * sc.m2)) ** e)
                    pmax = 1.2 * sc.p0 / (scenes.KGF if sc.units == "KGF_UM" else 1.0)
                    self.assertGreater(pstar, 2.0 * pmax)
        # every option of the list is drawn in 300 seeds, the exponents of measured
        # surfaces (m <= 0.22: 0.07/0.65 of the rough scenes, about 25 of the ~225) among them
        self.assertGreater(steep, 5)
        self.assertEqual(seen["ntype"], {1, 2, 3})
        self.assertEqual(seen["nnode"], {3, 4, 8, 9})
        self.assertEqual(seen["law"], {"ROUGH", "IDEAL"})
        self.assertEqual(seen["friction"], {"COULOMB", "FREDRIKSSON", "NONE"})
        self.assertEqual(seen["history"], set(scenes.HISTORIES))
        self.assertEqual(seen["matching"], {"NODE", "SEGMENT"})


class Checks(unittest.TestCase):
    def setUp(self):
        self.sc = rough_scene()
        self.lams = [0.5, 1.0, 0.5, 0.0, 1.0]

    def test_exact_results_pass(self):
        r = FakeResult([1.0, 2.0, 1.0], exact_history(self.sc, self.lams))
        self.assertEqual(scenes.check_law(self.sc, r), [])
        self.assertEqual(scenes.check_uniform(self.sc, r), [])

    def test_closure_off_the_law_fails(self):
        steps = exact_history(self.sc, self.lams)
        u = steps[2]._data["closure"]
        u[1] *= 1.0 + 1e-6             # 1e-6 off its law on the unloading branch
        r = FakeResult([1.0, 2.0, 1.0], steps)
        msgs = scenes.check_law(self.sc, r)
        self.assertEqual(len(msgs), 1, msgs)
        self.assertIn("increment 3: closure of pair 2 off its law", msgs[0])

    def test_zero_force_below_u_res_is_on_the_law(self):
        steps = exact_history(self.sc, self.lams)
        u = steps[3]._data["closure"]   # lambda = 0: at u_res; a pair below it and at zero force is open
        u[0] -= 1e-3 * abs(u[0]) + 1e-12
        self.assertEqual(scenes.check_law(self.sc, FakeResult([1.0, 2.0, 1.0], steps)), [])
        u[0] += 2e-3 * abs(u[0]) + 2e-12   # above u_res at zero force: off the law
        self.assertEqual(len(scenes.check_law(self.sc, FakeResult([1.0, 2.0, 1.0], steps))), 1)

    def test_pressure_off_the_closed_form_fails(self):
        steps = exact_history(self.sc, self.lams)
        steps[1]._data["pressure"][0] *= 1.0 + 1e-6
        msgs = scenes.check_uniform(self.sc, FakeResult([1.0, 2.0, 1.0], steps))
        self.assertEqual(len(msgs), 1, msgs)
        self.assertIn("increment 2", msgs[0])

    def test_no_pair_checked_fails(self):
        r = FakeResult([0.0, 0.0, 0.0], exact_history(self.sc, self.lams))
        self.assertTrue(scenes.check_law(self.sc, r))
        self.assertTrue(scenes.check_uniform(self.sc, r))

    def test_branch_closure(self):
        sc = self.sc
        cn, cn2 = scenes.model_constants(sc)
        self.assertAlmostEqual(scenes.branch_closure(sc, 2.0, 1.0), cn * 2.0 ** sc.m, delta=1e-15)
        ures = cn * 2.0 ** sc.m - cn2 * 2.0 ** sc.m2
        self.assertTrue(math.isclose(scenes.branch_closure(sc, 0.0, 2.0), ures, rel_tol=1e-12))


class Run(unittest.TestCase):
    def test_one_scene_end_to_end(self):
        exe = find_or_build(os.environ.get("K2D_EXECUTABLE"))
        sc = rough_scene()
        with tempfile.TemporaryDirectory(dir=os.environ.get("K2D_TEST_WORK")) as d:
            out = scenes.run_scene(sc, exe, d)
            self.assertEqual(out["exit"], 0, out["message"])
            self.assertEqual(out["checks"], [])
            self.assertTrue(out["passed"])


if __name__ == "__main__":
    unittest.main()
