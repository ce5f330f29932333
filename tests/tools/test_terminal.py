#!/usr/bin/python3
"""k2d.terminal (the program's terminal output read once) and k2d.deck's BLOCKS and SOLVERS
against the program's own lists (unittest; PYTHONPATH=<source>/tools)."""
import os
import re
import unittest

from k2d import deck, terminal

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

CONTACT_RUN = """ Nodes        : 1378   elements: 420   materials: 2
 Equations    : 2625   restrained dofs: 131   load cases: 1
 Contact      : 25 pairs, Newton (return to the laws, tangent every solution)
------------------------------------------------------------------------------
   inc  load factor     max |u|  closed  slip  solves rep   residual    time [s]
     1      0.05000           -      25     0       5   0  3.997E-16       1.432
     2      0.06203  9.5538E-03      25     3       4   1  4.296E-16       1.552
     3     -0.50000  9.1100E-03      25     9       6   2  5.001E-16       1.690
 SUMMARY OF THE RUN (load stages follow the factor of load case 1)
  stage   increments      load factor from -> to  kind       solutions  worst drift
      1      1 -     3    0.0000E+00 -> -5.0000E-01  loading           15    0.000E+00
 15 solutions in 3 increments, 1.70 s
"""
BODY_RUN = """ Nodes        : 9   elements: 4   materials: 1
   inc  load factor     max |u|        sum Rx        sum Ry    time [s]
     1      1.00000   1.2500E-03  -1.00000E+02   0.00000E+00       0.004
"""


class Terminal(unittest.TestCase):
    def test_contact_run(self):
        t = terminal.parse_terminal(CONTACT_RUN)
        self.assertEqual((t["nodes"], t["equations"], t["pairs"]), (1378, 2625, 25))
        # not the summary's stage row; a negative load factor (a case reversed) is a progress line
        self.assertEqual(t["progress"], [(1, 5, 1.432), (2, 4, 1.552), (3, 6, 1.690)])
        self.assertEqual(t["totals"], (15, 3))
        self.assertEqual(terminal.progress_solutions(t), 15)
        self.assertEqual(terminal.program_seconds(t), 1.70)

    def test_run_without_contact(self):
        t = terminal.parse_terminal(BODY_RUN)
        self.assertEqual((t["nodes"], t["equations"], t["pairs"], t["totals"]), (9, None, None, None))
        self.assertEqual(t["progress"], [(1, None, 0.004)])
        self.assertEqual(terminal.program_seconds(t), 0.004)
        self.assertEqual(terminal.progress_solutions(t), 0)

    def test_unreadable(self):
        self.assertIsNone(terminal.read_terminal(os.path.join(ROOT, "no", "such.log")))


class DeckLists(unittest.TestCase):
    def test_blocks_and_solvers_are_the_readers(self):
        src = ""
        for room in ("deck_blocks.f90", "deck_control_cards.f90"):  # block table, CONTROL card
            with open(os.path.join(ROOT, "src", "io", room)) as f:
                src += f.read()
        blocks = re.search(r"'TITLE', 'CONTROL'.*?\]", src, re.S).group(0)
        self.assertEqual(tuple(re.findall(r"'([A-Z]+)'", blocks)), deck.BLOCKS)
        solvers = re.search(r"character\(len=7\) :: ('SKYLINE'.*?)\]", src).group(1)
        self.assertEqual(tuple(re.findall(r"'([A-Z]+)'", solvers)), deck.SOLVERS)
        self.assertEqual(deck.keyword("contact   # the interface"), "CONTACT")


if __name__ == "__main__":
    unittest.main()
