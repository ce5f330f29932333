#!/usr/bin/python3
"""Tests of the calibration tools (tools/k2d/calibration*.py, tools/calibrate.py).

Run by ctest (tests/tools/CMakeLists.txt) with PYTHONPATH=<source>/tools and K2D_EXECUTABLE;
by hand:  PYTHONPATH=tools /usr/bin/python3 tests/tools/test_calibration.py [-v]

* recovery: synthetic curves from known constants with 0.5 % seeded noise (k2d.calibration_data)
  come back within 1 % for every constant; the data sets are sized so that every 95 %
  interval is below 1 % too, so the 1 % does not rest on a lucky seed (that is asserted);
* the SPEC §2.4 table sampled in kgf/cm2 and um comes back as the table's values, and the same
  data in N/mm2 and mm gives the same cards;
* units: the MODEL and N_UM cards agree with the program's own conversion of the KGF_UM cards
  (the `normal_model` attribute and `r_model` dataset of the result file);
* the loop: the written cards run through Kontakt2D reproduce noise-free closures and
  tractions to 1e-6 of the largest value;
* the warnings where the data does not determine a constant, and the admissibility of the
  unloading branch.
The malformed files (exit code 2 and their messages) are separate ctest tests.
"""

import os
import shutil
import sys
import tempfile
import unittest

import numpy as np

from k2d import calibration as cal
from k2d import calibration_data as gen
from k2d import calibration_replay as rep
from k2d.build import find_or_build
from k2d.results import Result

KGF = cal.Units("KGF_UM")


def rel(a, b):
    return abs(a / b - 1.0)


class Work(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        base = os.environ.get("K2D_TEST_WORK")
        if base:
            os.makedirs(base, exist_ok=True)
        cls.work = tempfile.mkdtemp(prefix="calib_", dir=base)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.work, name)

    def exe(self):
        return find_or_build(os.environ.get("K2D_EXECUTABLE"))


class TestRecovery(Work):
    """0.5 % noise: every constant within 1 % of the generating one (SPEC-like values)."""

    def check(self, fit, true):
        for name, value in true.items():
            c = fit.constant(name)
            with self.subTest(constant=name):
                self.assertLess(rel(c.value, value), 0.01, "%s = %.6g, generated with %.6g" % (name, c.value, value))
                # the data determine it to better than 1 % (95 %): the bound is not luck
                self.assertLess(c.relative, 0.01, "%s: 95 %% interval %.3g %%" % (name, 100 * c.relative))
        self.assertFalse([w for w in fit.warnings if "not determined" in w], fit.warnings)

    def test_normal_cycles(self):
        true = {"c_n": 0.8, "m": 0.5, "c_n2": 0.35, "m2": 0.6}
        p, u, b = gen.normal_cycles(0.8, 0.5, 0.35, 0.6, noise=0.005, seed=11)
        gen.write_normal(self.path("n.csv"), p, u)
        fit = cal.fit_normal(self.path("n.csv"), KGF)
        self.check(fit, true)
        self.assertEqual(len(fit.reversal_pressures), 4)

    def test_normal_cycles_branch_column_same_answer(self):
        p, u, b = gen.normal_cycles(0.8, 0.5, 0.35, 0.6, noise=0.005, seed=11)
        gen.write_normal(self.path("n.csv"), p, u)
        gen.write_normal(self.path("nb.csv"), p, u, branch=b)
        a = cal.fit_normal(self.path("n.csv"), KGF)
        c = cal.fit_normal(self.path("nb.csv"), KGF)
        self.assertEqual(a.cards, c.cards)

    def test_normal_same_exponent(self):
        p, u, b = gen.normal_cycles(1.0, 0.5, 0.5, 0.5, noise=0.005, seed=12)
        gen.write_normal(self.path("n.csv"), p, u)
        fit = cal.fit_normal(self.path("n.csv"), KGF, same_exponent=True)
        self.check(fit, {"c_n": 1.0, "m": 0.5, "c_n2": 0.5})
        self.assertEqual(fit.value("m2"), fit.value("m"))

    def test_tangent_three_levels(self):
        pn, ut, pt = gen.tangent_curves(1.3, 0.5, 0.2, 0.045, noise=0.005, seed=21)
        gen.write_tangent(self.path("t.csv"), pn, ut, pt)
        fit = cal.fit_tangent(self.path("t.csv"), KGF)
        self.check(fit, {"R": 1.3, "S": 0.5, "mu": 0.2, "kappa": 0.045})
        self.assertEqual(fit.mode, "hardening")

    def test_friction(self):
        v, mu = gen.friction_curve(0.2, 0.2, 275.0, noise=0.005, seed=31)
        gen.write_friction(self.path("f.csv"), v, mu)
        fit = cal.fit_friction(self.path("f.csv"), KGF)
        self.check(fit, {"mu_m": 0.2, "beta": 0.2, "n": 275.0})
        self.assertTrue(fit.cards[0].startswith("FRICTION  FREDRIKSS"))


class TestSpecTable(Work):
    """SPEC §2.4's table, sampled without noise in kgf/cm2 and um."""

    def test_rows_come_back(self):
        self.assertGreaterEqual(len(gen.SPEC_TABLE), 10)
        for finish, c, m in gen.SPEC_TABLE:
            with self.subTest(finish=finish):
                p, u = gen.loading_curve(c, m)
                gen.write_normal(self.path("row.csv"), p, u)
                fit = cal.fit_normal(self.path("row.csv"), KGF, loading_only=True)
                self.assertLess(rel(fit.value("c_n"), c), 1e-9)
                self.assertLess(rel(fit.value("m"), m), 1e-9)
                # the card carries the table's values, in the deck's columns
                line = fit.normal_card
                self.assertEqual(line[:10], "NORMAL    ")
                self.assertEqual(cal.card_values(line), [c, m])
                self.assertAlmostEqual(fit.rms, 0.0, delta=1e-12)

    def test_cycles_with_the_programs_default_unloading(self):
        # the table has no unloading constants: the program's defaults c_n2 = c_n/2, m2 = m
        for finish, c, m in gen.SPEC_TABLE:
            with self.subTest(finish=finish):
                p, u, b = gen.normal_cycles(c, m, c / 2, m)
                gen.write_normal(self.path("cyc.csv"), p, u)
                fit = cal.fit_normal(self.path("cyc.csv"), KGF)
                self.assertEqual(cal.card_values(fit.normal_card), [c, m, c / 2, m])

    def test_other_data_units_same_cards(self):
        p, u, b = gen.normal_cycles(0.5, 0.5, 0.25, 0.5)
        gen.write_normal(self.path("kgf.csv"), p, u)
        gen.write_normal(self.path("si.csv"), p, u, punit="N/mm2", lunit="mm")
        gen.write_normal(self.path("mpa.csv"), p, u, punit="MPa", lunit="um")
        cards = [cal.fit_normal(self.path(f), KGF).normal_card for f in ("kgf.csv", "si.csv", "mpa.csv")]
        self.assertEqual(cal.card_values(cards[0]), [0.5, 0.5, 0.25, 0.5])
        self.assertEqual(cards[1], cards[0])
        self.assertEqual(cards[2], cards[0])


class TestLoop(Work):
    """The written cards run through Kontakt2D (SCHEME NEWTON) reproduce the data."""

    def test_table_closures_reproduced(self):
        worst = 0.0
        rows = 0
        for j, (finish, c, m) in enumerate(gen.SPEC_TABLE):
            with self.subTest(finish=finish):
                p, u, b = gen.normal_cycles(c, m, c / 2, m, peaks=(5.0, 12.0, 25.0), npts=12)
                gen.write_normal(self.path("cyc%d.csv" % j), p, u)
                fit = cal.fit_normal(self.path("cyc%d.csv" % j), KGF)
                rp = rep.replay_normal(fit, self.path("replay%d" % j), exe=self.exe())
                # every row is replayed as measured, the unloadings to exactly p = 0 included
                # (three of them: one per cycle)
                self.assertEqual(int(np.sum(p == 0.0)), 3)
                self.assertEqual(rp.clipped, [])
                self.assertEqual(len(rp.rows), len(p))
                self.assertLessEqual(rp.max_error, 1e-6 * rp.scale)
                # the solver met the measured pressures (to the load factors' ten columns: 8 digits;
                # at p = 0 to the out-of-balance tolerance, 1e-10 of a load increment <= the peak)
                self.assertTrue(np.allclose(rp.pressure[rp.rows], p[rp.rows], rtol=1e-7, atol=1e-10 * p.max()))
                worst = max(worst, rp.max_error / rp.scale)
                rows += len(rp.rows)
        self.assertGreater(rows, 0)
        print("\n  table cycles replayed: %d rows, worst |computed - data| = %.2g of the largest closure"
              % (rows, worst), file=sys.stderr)

    def test_tangent_reproduced(self):
        pn, ut, pt = gen.tangent_curves(1.3, 0.5, 0.2, 0.045, npts=40)
        gen.write_tangent(self.path("t.csv"), pn, ut, pt)
        fit = cal.fit_tangent(self.path("t.csv"), KGF)
        self.assertEqual(fit.cards[1:], ["TANGENT          1.3       0.5", "FRICTION  COULOMB          0.2",
                                         "HARDENING ON             0.045"])
        rp = rep.replay_tangent(fit, self.path("replay_t"), exe=self.exe())
        self.assertEqual(len(rp.rows), len(pt))
        self.assertLessEqual(rp.max_error, 1e-6 * rp.scale)
        # every regime of the law was exercised in the replay
        self.assertEqual(set(fit.states), {0, 1, 2})
        print("\n  tangential curves replayed: %d rows, worst |computed - data| = %.2g of the largest traction"
              % (len(rp.rows), rp.max_error / rp.scale), file=sys.stderr)

    def test_units_as_the_program_converts_them(self):
        """MODEL (mm, N/mm2) and N_UM cards fitted to the same data equal the program's
        conversion of the KGF_UM cards, CN2 included (SPEC §2.4)."""
        p, u, b = gen.normal_cycles(0.8, 0.5, 0.35, 0.6)
        gen.write_normal(self.path("n.csv"), p, u)
        fits = {k: cal.fit_normal(self.path("n.csv"), cal.Units(k)) for k in cal.CARD_UNITS}
        models = {}
        # a ten-column field holds six significant digits below 0.01 (c_n in mm under MODEL):
        # the cards are then good to 5e-6, the closures they give to about that times m
        prec = {"KGF_UM": 1e-12, "N_UM": 5e-7, "MODEL": 5e-6}
        for k, fit in fits.items():
            rp = rep.replay_normal(fit, self.path("units_" + k), exe=self.exe())
            r = Result(rp.decks[0].replace(".dat", ".h5"))
            models[k] = np.asarray(r.contact.interfaces[0]["normal_model"], dtype=float)
            self.assertLessEqual(rp.max_error, max(1e-6, 2 * prec[k]) * rp.scale, k)
        self.assertTrue(np.allclose(models["KGF_UM"], [0.001 * 0.8 * (1 / 0.0980665) ** 0.5, 0.5,
                                                       0.001 * 0.35 * (1 / 0.0980665) ** 0.6, 0.6], rtol=1e-12))
        for k in ("N_UM", "MODEL"):
            self.assertTrue(np.allclose(models[k], models["KGF_UM"], rtol=prec[k], atol=0), (k, models[k]))
        fm = fits["MODEL"]
        self.assertTrue(np.allclose([fm.value(n) for n in ("c_n", "m", "c_n2", "m2")], models["KGF_UM"],
                                    rtol=1e-9, atol=0))
        fn = fits["N_UM"]
        self.assertLess(rel(fn.value("c_n2") * 1e-3, models["KGF_UM"][2]), 1e-9)
        # tangential: R under MODEL equals the program's r_model of the KGF_UM card
        pn, ut, pt = gen.tangent_curves(1.3, 0.5, 0.2, 0.045, npts=20)
        gen.write_tangent(self.path("t.csv"), pn, ut, pt)
        tk = cal.fit_tangent(self.path("t.csv"), KGF)
        tm = cal.fit_tangent(self.path("t.csv"), cal.Units("MODEL"))
        rp = rep.replay_tangent(tk, self.path("units_t"), exe=self.exe())
        r = Result(rp.decks[0].replace(".dat", ".h5"))
        r_model = np.asarray(r.contact.interfaces[0]["r_model"], dtype=float)
        self.assertGreater(r_model.size, 0)
        self.assertTrue(np.allclose(r_model, tm.value("R"), rtol=1e-9, atol=0), (r_model, tm.value("R")))
        self.assertLess(rel(tm.value("mu"), 0.2), 1e-9)
        self.assertLess(rel(tm.value("kappa"), 0.045), 1e-9)


class TestWarningsAndBounds(Work):
    def test_one_pressure_level_fixes_s(self):
        pn, ut, pt = gen.tangent_curves(1.3, 0.5, 0.2, 0.045, levels=(10.0,), npts=40)
        gen.write_tangent(self.path("t.csv"), pn, ut, pt)
        fit = cal.fit_tangent(self.path("t.csv"), KGF)
        self.assertTrue(any("S is not determined" in w for w in fit.warnings), fit.warnings)
        self.assertTrue(fit.constant("S").fixed)
        # with S given, R is exact again
        fit = cal.fit_tangent(self.path("t.csv"), KGF, s_fixed=0.5)
        self.assertLess(rel(fit.value("R"), 1.3), 1e-9)
        self.assertFalse([w for w in fit.warnings if "S is not" in w])

    def test_no_kink_means_hardening_off(self):
        pn, ut, pt = gen.tangent_curves(1.3, 0.5, 0.2, 1.0, npts=40, hardening=False)
        gen.write_tangent(self.path("t.csv"), pn, ut, pt)
        fit = cal.fit_tangent(self.path("t.csv"), KGF)
        self.assertEqual(fit.mode, "slip")
        self.assertIn("HARDENING OFF", fit.cards)
        self.assertTrue(any("no kink" in w for w in fit.warnings), fit.warnings)
        self.assertLess(rel(fit.value("mu"), 0.2), 1e-6)

    def test_elastic_data_gives_tangent_only(self):
        pn, ut, pt = gen.tangent_curves(1.3, 0.5, 0.2, 0.045, npts=20, reach=0.02)
        keep = pt < 0.6 * 0.2 * pn           # below the kink at 0.625 mu p_n
        gen.write_tangent(self.path("t.csv"), pn[keep], ut[keep], pt[keep])
        fit = cal.fit_tangent(self.path("t.csv"), KGF)
        self.assertEqual(fit.mode, "elastic")
        self.assertEqual([c.split()[0] for c in fit.cards], ["UNITS", "TANGENT"])
        self.assertTrue(any("stays elastic" in w for w in fit.warnings), fit.warnings)

    def test_coulomb_friction(self):
        v, mu = gen.friction_curve(0.25, 1.0, 275.0, npts=30, noise=0.005, seed=5)
        gen.write_friction(self.path("f.csv"), v, mu)
        fit = cal.fit_friction(self.path("f.csv"), KGF)
        self.assertTrue(fit.cards[0].startswith("FRICTION  COULOMB"), fit.cards)
        self.assertTrue(any("no slip hardening" in w for w in fit.warnings), fit.warnings)

    def test_short_slip_range_warns(self):
        # slip to 0.3 / n: a quarter of the hardening seen
        v, mu = gen.friction_curve(0.2, 0.2, 275.0, reach=0.3, npts=30, noise=0.005, seed=6)
        gen.write_friction(self.path("f.csv"), v, mu)
        fit = cal.fit_friction(self.path("f.csv"), KGF)
        self.assertTrue(any("extrapolated" in w for w in fit.warnings), fit.warnings)
        self.assertTrue(any("not determined" in w for w in fit.warnings), fit.warnings)

    def test_narrow_loading_range_warns(self):
        p = np.linspace(10.0, 11.0, 8)
        u = 0.8 * p ** 0.5 * (1 + 0.005 * np.random.default_rng(4).standard_normal(p.size))
        gen.write_normal(self.path("n.csv"), p, u)
        fit = cal.fit_normal(self.path("n.csv"), KGF, loading_only=True)
        self.assertTrue(any(w.startswith("m = ") and "not determined" in w for w in fit.warnings), fit.warnings)

    def test_unloading_kept_admissible(self):
        """Data whose unloading is softer than loading (c_n2 > c_n, m2 = m): the fit stays on
        the law's admissible side, which the program accepts (CN2 <= CN with M2 = M)."""
        p, u, b = gen.normal_cycles(0.8, 0.5, 1.2, 0.5, peaks=(10.0, 25.0), low=5.0, npts=10)
        gen.write_normal(self.path("n.csv"), p, u)
        fit = cal.fit_normal(self.path("n.csv"), KGF)
        c, m, c2, m2 = (fit.value(n) for n in ("c_n", "m", "c_n2", "m2"))
        for pa in fit.reversal_pressures:
            self.assertGreaterEqual(c * pa ** m - c2 * pa ** m2, -1e-12 * c * pa ** m)
            self.assertLessEqual(c2 * m2 * pa ** m2, c * m * pa ** m * (1 + 1e-12))
        v = cal.card_values(fit.normal_card)
        if abs(v[3] - v[1]) <= 1e-12 * v[1]:
            self.assertLessEqual(v[2], v[0])
        self.assertTrue(any("softer than the law admits" in w for w in fit.warnings), fit.warnings)
        rp = rep.replay_normal(fit, self.path("replay_adm"), exe=self.exe())
        self.assertLessEqual(rp.max_model_error, 1e-6 * rp.scale)

    def test_unloading_exponent_never_below_loading(self):
        """Data unloaded along a flatter exponent (m2 = 0.35 < m = 0.5, admissible over the
        measured reversal pressures 8-25 kgf/cm2): the program rejects M2 < M (its residual
        closure is negative at small reversal pressures), so the fit keeps m2 >= m and the
        cards it writes are accepted and replayed by the program."""
        p, u, b = gen.normal_cycles(0.8, 0.5, 0.6, 0.35, peaks=(8.0, 16.0, 25.0), npts=12)
        gen.write_normal(self.path("n_m2.csv"), p, u)
        fit = cal.fit_normal(self.path("n_m2.csv"), KGF)
        m, m2 = fit.value("m"), fit.value("m2")
        self.assertGreaterEqual(m2, m * (1 - 1e-12), "m2 = %.6g below m = %.6g" % (m2, m))
        rp = rep.replay_normal(fit, self.path("replay_m2"), exe=self.exe())
        self.assertLessEqual(rp.max_model_error, 1e-6 * rp.scale)


class TestCards(unittest.TestCase):
    def test_fields(self):
        self.assertEqual(cal.card("NORMAL", 0.3, 0.5), "NORMAL           0.3       0.5")
        self.assertEqual(cal.card("FRICTION", "FREDRIKSS", 0.2, 0.2, 275.0),
                         "FRICTION  FREDRIKSS        0.2       0.2      275.")
        self.assertEqual(cal.field(2.5e-4), "   0.00025")
        for x in (0.123456789012, 1.0 / 3.0, 1234.5678901, -1.5):
            s = cal.field(x)
            self.assertEqual(len(s), 10)
            self.assertEqual(s[0], " ")
            self.assertLess(rel(float(s), x), 5e-7, s)
        # below 0.1 a number needs all ten columns, below 0.01 they hold six significant digits
        for x in (0.0123456789, 0.00140979412, 7.123456789e-5):
            s = cal.field(x)
            self.assertEqual(len(s), 10)
            self.assertLess(rel(float(s), x), 5e-6, s)


if __name__ == "__main__":
    unittest.main()
