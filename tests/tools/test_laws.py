#!/usr/bin/python3
"""tools/k2d/laws.py, the rough interface's laws shared by the Python tools, against closed forms
and the figures of docs/contact.md (unittest; PYTHONPATH=<source>/tools)."""
import math
import unittest

import numpy as np

from k2d import laws


class NormalLaw(unittest.TestCase):
    def test_virgin_curve_and_inverse(self):
        p = np.array([0.0, 0.3, 1.0, 7.5])
        u = laws.virgin_closure(p, 1.3, 0.6)
        self.assertTrue(np.allclose(u, 1.3 * p ** 0.6, rtol=0, atol=0))
        self.assertTrue(np.allclose(laws.virgin_pressure(u, 1.3, 0.6), p, rtol=1e-14, atol=0))
        self.assertEqual(laws.virgin_pressure(-1e-3, 1.3, 0.6), 0.0)
        self.assertEqual(laws.virgin_closure(-2.0, 1.3, 0.6), 0.0)

    def test_tangents_are_derivatives(self):
        # central differences: their error is O(h^2) ~ 1e-8 relative, the tolerance 1e-6
        cn, m, p, h = 0.8, 0.5, 2.0, 1e-4
        du = laws.virgin_closure(p + h, cn, m) - laws.virgin_closure(p - h, cn, m)
        self.assertAlmostEqual(laws.virgin_tangent(p, cn, m) * du / (2 * h), 1.0, delta=1e-6)
        ua, pa, cn2, m2 = laws.virgin_closure(4.0, cn, m), 4.0, 0.3, 0.7
        du = laws.unloading_closure(p + h, ua, pa, cn2, m2) - laws.unloading_closure(p - h, ua, pa, cn2, m2)
        self.assertAlmostEqual(laws.unloading_tangent(p, cn2, m2) * du / (2 * h), 1.0, delta=1e-6)

    def test_unloading_branch(self):
        cn, m, cn2, m2, pa = 1.0, 0.5, 0.5, 0.5, 9.0
        ua = laws.virgin_closure(pa, cn, m)                     # 3
        self.assertEqual(laws.unloading_closure(pa, ua, pa, cn2, m2), ua)
        self.assertEqual(laws.unloading_closure(4.0, ua, pa, cn2, m2), 3.0 - 0.5 * (3.0 - 2.0))
        self.assertEqual(laws.residual_closure(ua, pa, cn2, m2), 1.5)
        self.assertEqual(laws.unloading_constant(ua, pa, cn2, m2), cn2)
        self.assertAlmostEqual(laws.unloading_pressure(2.5, ua, pa, cn2, m2), 4.0, delta=1e-14)
        self.assertEqual(laws.unloading_pressure(1.0, ua, pa, cn2, m2), 0.0)   # below u_res: open

    def test_reversal_limit(self):
        # docs/contact.md: NORMAL 0.5 0.5 0.4 0.6 has p* = (25/24)^10 = 1.504 kgf/cm2
        cn, m, cn2, m2 = 0.5, 0.5, 0.4, 0.6
        pstar = laws.reversal_limit(cn, m, cn2, m2)
        self.assertAlmostEqual(pstar / (25.0 / 24.0) ** 10, 1.0, delta=1e-14)
        # at p* unloading is exactly as stiff as loading; 1 % above it softer, 1 % below stiffer
        for f, softer in ((1.0, None), (1.01, True), (0.99, False)):
            k_load = laws.virgin_tangent(f * pstar, cn, m)
            k_unl = laws.unloading_tangent(f * pstar, cn2, m2)
            if softer is None:
                self.assertAlmostEqual(k_unl / k_load, 1.0, delta=1e-12)
            else:
                self.assertEqual(k_unl < k_load, softer)
        self.assertEqual(laws.admissible_reversals(1.0, 0.5, 0.5, 0.5), (0.0, math.inf))
        self.assertEqual(laws.admissible_reversals(1.0, 0.5, 2.0, 0.5), (math.inf, 0.0))
        lo, hi = laws.admissible_reversals(1.0, 0.5, 0.5, 0.4)      # m2 < m: from (cn2/cn)^(1/(m-m2))
        self.assertAlmostEqual(lo, 0.5 ** 10, delta=1e-16)
        self.assertEqual(hi, math.inf)

    def test_clamp_beyond_residual_zero(self):
        # beyond (cn/cn2)^(1/(m2-m)) = 1.25^10 = 9.31 the bare u_res is negative: the branch through
        # A and the origin, u = u_A (p/p_A)^m2, u_res = 0
        cn, m, cn2, m2, pa = 0.5, 0.5, 0.4, 0.6, 20.0
        ua = laws.virgin_closure(pa, cn, m)
        self.assertLess(ua - cn2 * pa ** m2, 0.0)
        self.assertEqual(laws.residual_closure(ua, pa, cn2, m2), 0.0)
        self.assertAlmostEqual(laws.unloading_constant(ua, pa, cn2, m2), ua / pa ** m2, delta=1e-15)
        for p in (0.0, 3.0, 11.0, pa):
            self.assertAlmostEqual(laws.unloading_closure(p, ua, pa, cn2, m2), ua * (p / pa) ** m2, delta=1e-14)
            self.assertAlmostEqual(laws.unloading_pressure(ua * (p / pa) ** m2, ua, pa, cn2, m2), p, delta=1e-12)
        self.assertAlmostEqual(laws.unloading_closure(3.0, ua, pa, cn2, m2, clamp=False),
                               ua - cn2 * (pa ** m2 - 3.0 ** m2), delta=1e-15)
        # arrays: pairs on either side of the clamp
        c = laws.unloading_constant(np.array([ua, 10.0]), np.array([pa, 1.0]), cn2, m2)
        self.assertTrue(np.allclose(c, [ua / pa ** m2, cn2], rtol=1e-15, atol=0))


class Units(unittest.TestCase):
    def test_model_constants(self):
        f = 1.0 / 0.0980665
        self.assertEqual(laws.model_constant(1.0, 0.5, "KGF_UM"), 1e-3 * f ** 0.5)
        self.assertEqual(laws.model_constant(0.4, 0.6, "kgf_um"), 1e-3 * 0.4 * f ** 0.6)
        self.assertEqual(laws.model_constant(2.0, 0.5, "N_UM"), 2e-3)
        self.assertEqual(laws.model_constant(2.0, 0.5, "MODEL"), 2.0)
        with self.assertRaises(ValueError):
            laws.model_constant(1.0, 0.5, "PSI")

    def test_law_is_unit_independent(self):
        # the closure at 1 N/mm2 from KGF_UM constants equals the closure at 10.197 kgf/cm2, in mm
        cn, m = 1.3, 0.45
        self.assertAlmostEqual(laws.virgin_closure(1.0, laws.model_constant(cn, m, "KGF_UM"), m),
                               1e-3 * cn * (1.0 / laws.KGF_CM2) ** m, delta=1e-18)
        # p* moves with the pressure unit: p*_model = p*_kgf * 0.0980665
        cn, m, cn2, m2 = 0.5, 0.5, 0.4, 0.6
        pk = laws.reversal_limit(cn, m, cn2, m2)
        pm = laws.reversal_limit(laws.model_constant(cn, m, "KGF_UM"), m, laws.model_constant(cn2, m2, "KGF_UM"), m2)
        self.assertAlmostEqual(pm / (pk * laws.KGF_CM2), 1.0, delta=1e-12)


class Tangential(unittest.TestCase):
    def test_stiffness(self):
        r = laws.r_literature(1.0, 0.5, 0.3)
        self.assertAlmostEqual(r, 1.3, delta=1e-15)
        self.assertAlmostEqual(laws.tangential_stiffness(4.0, 0.5, r), 2.0 / 1.3, delta=1e-15)
        self.assertEqual(laws.tangential_stiffness(-1.0, 0.5, r), 0.0)


if __name__ == "__main__":
    unittest.main()
