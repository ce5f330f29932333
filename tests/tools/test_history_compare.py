#!/usr/bin/python3
"""Tests of the history figures, the history plots, the run summary and tools/compare.py.

Run by ctest (tests/tools/CMakeLists.txt) with PYTHONPATH=<source>/tools and K2D_EXECUTABLE;
by hand:  PYTHONPATH=tools /usr/bin/python3 tests/tools/test_history_compare.py [-v]

* approach: the V4 cycle is displacement controlled (the top face of A moved by -0.0131933
  lambda, the bottom of B fixed), so the approach of the bodies is 0.0131933 lambda exactly, at
  every increment of loading, unloading and reloading (tolerance 1e-12 relative: a mean of
  equal prescribed numbers);
* the load stages of a load-unload-reload history, and the residual closure after unloading,
  u_A - c_n2 p_A^m2 with (u_A, p_A) on the virgin curve u = c_n p^m (Newton scheme: the pairs
  lie on the law to its tolerance, so 1e-6 relative);
* the run summary of the Fortran program (end of the terminal output) against the same figures
  computed here from the result file -- two implementations of one definition, equal to the
  printed 5 significant digits (5e-5 relative);
* the history plots are written for a cycle and skipped for a single increment;
* vary_deck: LAW on every interface (also when the block starts with INTERFACE), SCHEME
  replacing UPDATE, a deck without CONTACT refused; the varied deck read by the program has
  the law it asks for;
* tools/compare.py: the numbers of its report (six significant digits) agree with the HDF5
  files read here to 1e-5 relative, the mean u_T of the closed pairs among them; a bad --vary
  gives exit code 2 and a message; a run that failed half way is named, exit code 3, and the
  runs are compared at the last state both reached; round-off gets no per cent.
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from k2d import laws, loops
from k2d.build import ROOT, find_or_build
from k2d.compare import CompareError, vary_deck
from k2d.history import History
from k2d.history_plot import plot_history, stage_table
from k2d.results import Result

CYCLE = os.path.join(ROOT, "tests", "decks", "contact", "v4_cycle_return.dat")
TANGENTIAL = os.path.join(ROOT, "tests", "decks", "contact", "v2_tangential.dat")
SPHERE = os.path.join(ROOT, "inputs", "sphere_5_2.dat")
D_TOP = 0.0131933          # the prescribed displacement of the V4 deck's top face at factor 1


class Work(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        base = os.environ.get("K2D_TEST_WORK")
        if base:
            os.makedirs(base, exist_ok=True)
        cls.work = tempfile.mkdtemp(prefix="history_", dir=base)
        cls.exe = find_or_build(os.environ.get("K2D_EXECUTABLE"))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work, ignore_errors=True)

    def run_deck(self, deck, name):
        h5 = os.path.join(self.work, name + ".h5")
        p = subprocess.run([self.exe, deck, "-o", h5], capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        return h5, p.stdout


class TestHistory(Work):
    def test_approach_is_the_prescribed_displacement(self):
        h5, _ = self.run_deck(CYCLE, "cycle")
        h = History(Result(h5))
        self.assertGreaterEqual(len(h.steps), 60)
        np.testing.assert_allclose(h.approach, D_TOP * h.lam, rtol=1e-12, atol=1e-12 * D_TOP)

    def test_stages_and_residual_closure(self):
        h5, out = self.run_deck(CYCLE, "cycle2")
        res = Result(h5)
        h = History(res)
        stages = h.stages()
        self.assertEqual([h.stage_name(a, b) for a, b in stages], ["loading", "unloading", "loading"])
        self.assertEqual([(h.steps[a].number, h.steps[b].number) for a, b in stages], [(1, 20), (21, 40), (41, 70)])
        cn, m, cn2, m2 = res.contact.interfaces[0]["normal_model"][:4]
        pa = h.field(19, "pressure")                   # the reversal point: the end of the first loading
        self.assertTrue(np.all(h.field(19, "normal_state") == 1))
        want = np.max(laws.residual_closure(laws.virgin_closure(pa, cn, m), pa, cn2, m2))
        table = stage_table(h5)
        row = [ln for ln in table.splitlines() if ln.startswith("| 2 | unloading")]
        self.assertEqual(len(row), 1, table)
        got = float(row[0].split("|")[-2])
        self.assertAlmostEqual(got / want, 1.0, delta=5e-3)   # the table prints 3 digits
        # the Fortran summary: same definitions, computed from the pairs' reversal states
        summary = out[out.index("SUMMARY OF THE RUN"):]
        f_res = float(re.search(r"residual closure\s+(\S+) mm", summary).group(1))
        self.assertAlmostEqual(f_res / want, 1.0, delta=1e-6 + 5e-5)
        last = h.figures(len(h.steps) - 1)
        f_app = float(re.search(r"approach\s+(\S+) mm", summary).group(1))
        self.assertAlmostEqual(f_app / last["approach"], 1.0, delta=5e-5)
        f_peak = float(re.search(r"peak pressure\s+(\S+) N/mm2 at pair (\d+)", summary).group(1))
        self.assertAlmostEqual(f_peak / last["peak_pressure"], 1.0, delta=5e-5)
        f_fn = float(re.search(r"total force normal\s+(\S+),", summary).group(1))
        self.assertAlmostEqual(f_fn / last["normal_force"], 1.0, delta=5e-5)
        rows = re.findall(r"^\s+(\d+)\s+(\d+) -\s+(\d+)\s+\S+ ->\s+\S+\s+(loading|unloading)", summary, flags=re.M)
        self.assertEqual([(int(a), int(b), c) for _, a, b, c in rows],
                         [(1, 20, "loading"), (21, 40, "unloading"), (41, 70, "loading")])
        total = int(re.search(r"(\d+) solutions in 70 increments", summary).group(1))
        self.assertEqual(total, int(np.sum(res.history("iterations"))))

    def test_plots_written_for_a_cycle_and_not_for_one_increment(self):
        h5, _ = self.run_deck(CYCLE, "cycle3")
        pngs = plot_history(h5)
        self.assertEqual([os.path.basename(p) for p in pngs],
                         ["cycle3_%s.png" % k for k in ("approach", "pairs", "interface", "slip")])
        for p in pngs:
            self.assertGreater(os.path.getsize(p), 10000)
        with self.assertRaises(ValueError):
            plot_history(h5, pairs=[99])
        with self.assertRaises(ValueError):
            plot_history(h5, increments=[500])
        h1, _ = self.run_deck(SPHERE, "sphere")
        self.assertEqual(plot_history(h1), [])


class TestLoops(Work):
    def test_program_ends_on_the_python_law(self):
        """The tangential cycle +-0.8 mu p (tests/decks/contact/tangential_cycle.dat, Newton: on
        the law to round-off): every increment of every pair is drawn along the law by k2d.loops,
        i.e. its Masing integration reaches the program's force at the increment end within
        ON_LAW; the stages are named by what changes and the loop plot is written."""
        h5, _ = self.run_deck(os.path.join(ROOT, "tests", "decks", "contact", "tangential_cycle.dat"), "tcycle")
        h = History(Result(h5))
        self.assertEqual([h.stage_name(a, b) for a, b in h.stages()],
                         ["loading", "tangential loading (+)", "tangential reversal (-)", "tangential reversal (+)"])
        self.assertGreater(h.npair, 0)
        for j in range(h.npair):
            _, _, on = loops.tangential_path(h, j)
            self.assertTrue(on.all(), "pair %d: increments %s drawn as chords" % (j + 1, np.where(~on)[0] + 1))
        pngs = plot_history(h5)
        self.assertIn("tcycle_loops.png", [os.path.basename(p) for p in pngs])


    def test_joint_cycle_loops_and_energy(self):
        """inputs/joint_cycle.dat: the loop plot is written; every increment of every pair is drawn
        along the law (normal and tangential).  Where the program writes the periodic histories
        (/cycles) the energy plot is written too, and the energy of the last cycle equals the
        areas of the pairs' loops along the law, the integrals of F_T du_T + F_n du_n from the end
        of its first_increment to the end of its last_increment (docs/results-format.md: the
        increments at which the cycle starts and ends): two computations of the work of the laws
        (the program's from its increments, this one by the trapezoidal rule on 24 points per
        increment of the law's curves; 1 %: the branch kinks inside an increment are cut by at
        most one chord of 1/24 of the increment; measured 0.3 %).  Without /cycles (a program
        before them) that part is skipped, said on the output."""
        h5, _ = self.run_deck(os.path.join(ROOT, "inputs", "joint_cycle.dat"), "joint")
        pngs = [os.path.basename(p) for p in plot_history(h5)]
        self.assertIn("joint_loops.png", pngs)
        h = History(Result(h5))
        self.assertEqual(h.npair, 9)
        n = loops.NSUB
        for j in range(h.npair):
            self.assertTrue(loops.tangential_path(h, j)[2].all(), j)
            self.assertTrue(loops.normal_path(h, j)[2].all(), j)
        cyc = h.result.cycles
        if not cyc:
            self.assertNotIn("joint_energy.png", pngs)
            print("\njoint_cycle: no /cycles in the result file: the energy check is skipped")
            return
        self.assertIn("joint_energy.png", pngs)
        first, last = int(cyc["first_increment"][-1]), int(cyc["last_increment"][-1])
        a, b = h.index_of(first), h.index_of(last)
        work = 0.0
        for j in range(h.npair):
            ut, pt, _ = loops.tangential_path(h, j)
            un, pn, _ = loops.normal_path(h, j)
            sl = slice((a + 1) * n, (b + 1) * n + 1)   # from the end of increment `first` to that of `last`
            work += h.area[j] * (np.trapz(pt[sl], ut[sl]) + np.trapz(pn[sl], un[sl]))
        energy = float(np.atleast_2d(cyc["energy"])[-1, 0])
        self.assertGreater(work, 0.0)
        self.assertAlmostEqual(energy / work, 1.0, delta=0.01)


class TestVary(Work):
    DECK = ("TITLE\nt\nCONTACT\n{first}UNITS     KGF_UM\nLAW       ROUGH\nUPDATE    NEWTON\nSURFACE   A\n"
            "    1    2\n{second}SURFACE   B\n    3    4\nINCREMENTS\n    1       1.0\nEND\n")

    def test_law_on_every_interface(self):
        text = self.DECK.format(first="", second="INTERFACE\nFRICTION  NONE\n")
        v = vary_deck(text, "LAW", "IDEAL")
        lines = v.splitlines()
        self.assertEqual(sum(ln.startswith("LAW") for ln in lines), 2)
        self.assertEqual(lines[lines.index("CONTACT") + 1], "LAW       IDEAL")
        self.assertEqual(lines[lines.index("INTERFACE") + 1], "LAW       IDEAL")
        self.assertNotIn("LAW       ROUGH", v)
        # a block that starts with INTERFACE: no card before it (that would open another interface)
        v = vary_deck(self.DECK.format(first="INTERFACE\n", second=""), "LAW", "IDEAL")
        lines = v.splitlines()
        self.assertEqual(lines[lines.index("CONTACT") + 1], "INTERFACE")
        self.assertEqual(sum(ln.startswith("LAW") for ln in lines), 1)

    def test_scheme_replaces_update(self):
        v = vary_deck(self.DECK.format(first="", second=""), "SCHEME", "INCREMENTAL")
        self.assertNotIn("UPDATE", v)
        self.assertEqual(v.count("SCHEME    INCREMENTAL"), 1)
        self.assertIn("INCREMENTS\n    1       1.0\nEND\n", v)

    def test_no_contact_block(self):
        with self.assertRaises(CompareError):
            vary_deck("TITLE\nt\nINCREMENTS\nEND\n", "LAW", "IDEAL")

    def test_varied_deck_runs_with_that_law(self):
        with open(TANGENTIAL) as f:
            text = vary_deck(f.read(), "LAW", "IDEAL")
        deck = os.path.join(os.path.dirname(TANGENTIAL), ".test_vary_%d.dat" % os.getpid())
        with open(deck, "w") as f:
            f.write(text)
        try:
            h5, _ = self.run_deck(deck, "ideal")
        finally:
            os.remove(deck)
        ifaces = Result(h5).contact.interfaces
        self.assertGreater(len(ifaces), 0)
        self.assertTrue(all(i["law"] == "IDEAL" for i in ifaces))


class TestCompare(Work):
    def test_report_numbers_agree_with_the_files(self):
        out = os.path.join(self.work, "cmp")
        p = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "compare.py"), TANGENTIAL,
                            "--vary", "SCHEME=NEWTON", "-o", out, "--exe", self.exe],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        with open(os.path.join(out, "report.md")) as f:
            md = f.read()
        table = {}
        for ln in md.splitlines():
            cells = [c.strip() for c in ln.strip().strip("|").split("|")]
            if len(cells) == 4:
                table[cells[0].split(" [")[0]] = cells[1:]      # the label without its unit
        checked = 0
        for col, h5 in ((0, "as_given.h5"), (1, "SCHEME_NEWTON.h5")):
            res = Result(os.path.join(out, h5))
            # the deck as given runs the paper's explicit scheme, whose normal forces are
            # genuinely off the law (a doubtful run, every increment kept); Newton is on it
            if col == 0:
                self.assertTrue(res.status.startswith("doubtful"), res.status)
            else:
                self.assertEqual(res.status, "completed")
            c = res.last.contact_all()
            closed = c["normal_state"] > 0
            self.assertTrue(closed.any())
            area = res.contact.area[closed]
            want = {
                "mean tangential displacement u_T of the closed pairs": np.sum(area * c["slip"][closed]) / area.sum(),
                "peak pressure": np.max(c["pressure"][closed]),
                "total normal force": np.sum(c["force_normal"]),
                "total tangential force": np.sum(c["force_tangential"]),
                "closed pairs": np.sum(closed),
                "slipping pairs": np.sum(closed & (c["tangential_state"] == 2)),
                "solutions (all increments)": np.sum(res.history("iterations")),   # every increment kept
                "increments": len(res.steps),
            }
            for key, value in want.items():
                self.assertIn(key, table, md)
                got = float(table[key][col])
                self.assertAlmostEqual(got, float(value), delta=1e-5 * max(abs(float(value)), 1e-300), msg=key)
                checked += 1
        self.assertEqual(checked, 16)
        for png in ("compare_last.png", "compare_history.png"):
            self.assertIn("(%s)" % png, md)
            self.assertTrue(os.path.exists(os.path.join(out, png)))

    def test_failed_run_like_states_and_round_off(self):
        """A run that failed half way: named, exit code 3, compared at the last state both runs
        reached (not its last increment against the other's); tangential forces of round-off size
        get no per cent.  The runs are result files built here (test_loops.write_result), handed
        out by a stand-in for the program that copies the file its deck names and exits with the
        deck's code."""
        from test_loops import normal_cycle_steps, write_result
        steps = normal_cycle_steps()
        for s_, ft in zip(steps, (1e-15, -2e-15, 3e-15, 1e-15, -1e-15, 2e-15, 1e-15)):
            s_["shear"] = np.array([ft, 0.0])
        other = [dict(s_, shear=np.array([-8.21e-15, 0.0])) for s_ in steps[:5]]
        good = write_result(os.path.join(self.work, "good_src.h5"), steps)
        bad = write_result(os.path.join(self.work, "bad_src.h5"), other, status="failed at increment 6: no convergence")
        fake = os.path.join(self.work, "fake_kontakt2d")
        with open(fake, "w") as f:
            f.write("#!%s\nimport shutil, sys\nsrc, code = open(sys.argv[1]).read().split()\n"
                    "shutil.copy(src, sys.argv[sys.argv.index('-o') + 1])\nsys.exit(int(code))\n" % sys.executable)
        os.chmod(fake, 0o755)
        decks = []
        for name, src, code in (("full", good, 0), ("cut", bad, 3)):
            decks.append(os.path.join(self.work, name + ".dat"))
            with open(decks[-1], "w") as f:
                f.write("%s %d\n" % (src, code))
        out = os.path.join(self.work, "cmp_failed")
        p = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "compare.py"), decks[0], decks[1],
                            "-o", out, "--exe", fake], capture_output=True, text=True)
        self.assertEqual(p.returncode, 3, p.stdout + p.stderr)
        self.assertIn("the run cut failed", p.stderr)
        with open(os.path.join(out, "report.md")) as f:
            md = f.read()
        self.assertIn("**The run cut failed** (exit code 3, status: failed at increment 6", md)
        self.assertIn("increment 5 of full and 5 of cut (like states: the last state both runs reached)", md)
        rows = {ln.split("|")[1].strip().split(" [")[0]: [c.strip() for c in ln.split("|")[2:5]]
                for ln in md.splitlines() if ln.startswith("| ") and ln.count("|") == 5}
        self.assertEqual(rows["load factor"], ["0.7", "0.7", "equal"])
        self.assertEqual(rows["peak pressure"][2], "equal")
        self.assertEqual(rows["total tangential force"][2], "equal to round-off")
        self.assertIn("mean tangential displacement u_T of the closed pairs", rows)

    def test_bad_vary(self):
        p = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "compare.py"), TANGENTIAL,
                            "--vary", "LAW=SMOOTH", "--exe", self.exe], capture_output=True, text=True)
        self.assertEqual(p.returncode, 2)
        self.assertIn("--vary LAW: unknown value 'SMOOTH'; expected IDEAL or ROUGH", p.stderr)
        p = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "compare.py"), "no_such.dat",
                            "--vary", "LAW=IDEAL", "--exe", self.exe], capture_output=True, text=True)
        self.assertEqual(p.returncode, 2)
        self.assertIn("no_such.dat: no such deck", p.stderr)


if __name__ == "__main__":
    unittest.main()
