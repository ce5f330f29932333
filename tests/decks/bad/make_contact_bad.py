#!/usr/bin/python3
"""Malformed CONTACT and TIES blocks, derived from tests/decks/contact/v1_plane_q4.dat.
Each case writes bad_<name>.dat and bad_<name>.expect (a regular expression that the
error message must match).  Rerun after changing the base deck."""
import os

HERE = os.path.dirname(os.path.abspath(__file__))
base = open(os.path.join(HERE, "..", "contact", "v1_plane_q4.dat")).read()


def case(name, old, new, expect):
    assert old in base, (name, old)
    with open(os.path.join(HERE, "bad_" + name + ".dat"), "w") as f:
        f.write(base.replace(old, new, 1))
    with open(os.path.join(HERE, "bad_" + name + ".expect"), "w") as f:
        f.write(expect + "\n")


N = "NORMAL           1.0       0.5\n"
case("contact_cn_zero", N, "NORMAL           0.0       0.5\n",
     r"\[E-CONTACT\]: CONTACT/NORMAL: CN \(columns 11-20\) expected a positive roughness constant c_n, found 0")
case("contact_m_negative", N, "NORMAL           1.0      -0.5\n",
     r"\[E-CONTACT\]: CONTACT/NORMAL: M \(columns 21-30\) expected a positive exponent m, found -5")
case("contact_cn2_softer", N, "NORMAL           1.0       0.5       2.0\n",
     r"\[E-CONTACT\]: CONTACT/NORMAL: CN2 = 2\.0+E\+00 > CN = 1\.0+E\+00 with M2 = M")
case("contact_m2_below_m", N, "NORMAL           1.0       0.5       0.5       0.4\n",
     r"\[E-CONTACT\]: CONTACT/NORMAL: M2 \(columns 41-50\) expected at least M = 5\.0+E-01, found 4\.0+E-01: "
     r"with M2 < M the residual closure")
case("contact_mu_negative", "FRICTION  NONE\n", "FRICTION  COULOMB      -0.1\n",
     r"\[E-CONTACT\]: CONTACT/FRICTION: MU \(columns 21-30\) expected a friction coefficient >= 0, found -1")
case("contact_beta_above_one", "FRICTION  NONE\n", "FRICTION  FREDRIKSS       0.2       1.5     275.0\n",
     r"\[E-CONTACT\]: CONTACT/FRICTION: BETA \(columns 31-40\) expected the initial fraction of mu_m in \(0, 1\], found 1\.5")
case("contact_beta_zero", "FRICTION  NONE\n", "FRICTION  FREDRIKSS       0.2       0.0     275.0\n",
     r"\[E-CONTACT\]: CONTACT/FRICTION: BETA \(columns 31-40\) expected the initial fraction of mu_m in \(0, 1\], found 0")
case("contact_kappa", "FRICTION  NONE\n", "FRICTION  COULOMB       0.2\nHARDENING ON         1.5\n",
     r"\[E-CONTACT\]: CONTACT/HARDENING: KAPPA \(columns 21-30\) expected a ratio k_T\^p/k_T\^e in \(0, 1\], found 1\.5")
case("contact_no_friction", "FRICTION  NONE\n", "",
     r"\[E-CONTACT\]: CONTACT: interface 1 has no FRICTION card")
case("contact_unknown_keyword", "UPDATE    EXPLICIT\n", "UPDATES   EXPLICIT\n",
     r"bad_contact_unknown_keyword\.dat:96:1: error \[E-CONTACT\]: CONTACT: unknown keyword \"UPDATES\"")
case("contact_units", "UNITS     KGF_UM\n", "UNITS     PSI\n",
     r"\[E-CONTACT\]: CONTACT/UNITS \(columns 11-20\) expected KGF_UM, N_UM or MODEL, found \"PSI\"")
case("contact_unmatched", "SURFACE   B\n   29   28   31   33   35\n", "SURFACE   B\n   29   28   31\n",
     r"\[E-UNMATCHED\]: CONTACT: interface 1: 2 node\(s\) of surface A have no partner on surface B .*: 7 9")
case("contact_unknown_set", "SURFACE   B\n   29   28   31   33   35\n", "SURFACE   B         base_top\n",
     r"\[E-SURFACE\]: CONTACT/SURFACE B: no node or edge set called \"base_top\"")
case("contact_node_not_on_surface", "SURFACE   B\n   29   28   31   33   35\n",
     "SURFACE   B\n   29   28   31   33   35   12\n",
     r"\[E-SURFACE\]: CONTACT/SURFACE B: node\(s\) on no boundary edge formed by the listed nodes .*: 12")
case("contact_same_body", "SURFACE   A\n    1    2    5    7    9\nSURFACE   B\n   29   28   31   33   35\n",
     "PAIRS\n    1    3                          1.0\n",
     r"\[E-CONTACT\]: CONTACT: pair 1-3: both nodes belong to the same body")
case("contact_overlap", "SURFACE   B\n   29   28   31   33   35\n",
     "PAIRS\n    2   29                          1.0\nSURFACE   B\n   29   28   31   33   35\n",
     r"\[E-CONTACT\]: CONTACT: node 29 of surface B is the partner of two nodes of surface A")
case("contact_pair_no_area", "SURFACE   A\n    1    2    5    7    9\nSURFACE   B\n   29   28   31   33   35\n",
     "PAIRS\n    1   29\n",
     r"\[E-CONTACT\]: CONTACT/PAIRS: pair 1-29 needs an AREA")
case("contact_data_without_list", "UPDATE    EXPLICIT\n", "UPDATE    EXPLICIT\n    1    2\n",
     r"\[E-CARD\]: CONTACT: a data card must follow a SURFACE or PAIRS card")
case("ties_restrained", "MATERIALS\n", "TIES\n   10    1    2\nMATERIALS\n",
     r"\[E-TIE\]: TIES: node 1 is restrained in x; ties act on free dofs only")
case("ties_code", "MATERIALS\n", "TIES\n   12    3    4\nMATERIALS\n",
     r"\[E-CODE\]: TIES: CODE \(columns 1-5\) expected 10 \(x\), 01 \(y\) or 11 \(both\), found 12")
