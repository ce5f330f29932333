#!/usr/bin/python3
"""Check a run of a steep-law deck: the expected values of its .check file (k2d.checks, as
tests/decks/check_deck.py) and every closed pair on its normal law at every increment end.

    check_branch_law.py RESULT.h5 DECK.check

The deck (DECK.dat beside the check file) has one rough interface; its UNITS and NORMAL cards
are read here (NORMAL c_n m [c_n2 [m2]], c_n2 = c_n/2 and m2 = m when not given,
docs/deck-format.md) and the law replayed independently of the program (docs/contact.md): a
closed pair whose pressure p exceeds every pressure it carried before is on the virgin curve
u = c_n p^m; below its largest pressure so far p_A it is on the unloading branch through A,
u = u_A - c_n2 (p_A^m2 - p^m2); at zero force its closure is at most that branch's zero-force
point u_res = max(u_A - c_n2 p_A^m2, 0).  Tolerance: 1e-8 of the run's largest closure (the
program returns every pair to its law exactly at the closure it converged to; the replay of a
power law differs from it by round-off, about 1e-15 relative).
Exit 0 when everything holds, 1 otherwise, 2 when the check file or the deck is malformed."""
import os
import sys

from k2d import laws
from k2d.checks import CheckFormatError, check_result, parse
from k2d.results import Result

TOL_U = 1.0e-8


def normal_values(line):
    """The numbers of a NORMAL card: free format (separated by blanks) or the deck's ten-column
    fields after the keyword (docs/deck-format.md), which may touch one another."""
    try:
        values = [float(w) for w in line[6:].split()]
        if values and all(w.count(".") <= 1 for w in line[6:].split()):
            return values
    except ValueError:
        pass
    return [float(line[k:k + 10]) for k in range(10, len(line.rstrip()), 10) if line[k:k + 10].strip()]


def read_law(deck):
    """(c_n, m, c_n2, m2) in model units (mm, N/mm2) from the deck's UNITS and NORMAL cards."""
    units, normal = "N_UM", None
    with open(deck) as f:
        for line in f:
            words = line.split("#")[0].split()
            if words and words[0] == "UNITS":
                units = words[1]
            if words and words[0] == "NORMAL":
                normal = normal_values(line.split("#")[0])
    if not normal or len(normal) < 2:
        raise ValueError("%s: no NORMAL card with c_n and m" % deck)
    cn, m = normal[0], normal[1]
    cn2 = normal[2] if len(normal) > 2 else 0.5 * cn
    m2 = normal[3] if len(normal) > 3 else m
    return (laws.model_constant(cn, m, units), m, laws.model_constant(cn2, m2, units), m2)


def law_misfits(result, law):
    """Messages for every increment with a closed pair off its law; also the pairs checked."""
    cn, m, cn2, m2 = law
    r = Result(result)
    area = r.contact.area
    pmax = [0.0] * len(area)
    hist = [(s.number, s.contact("pressure"), s.contact("closure"), s.contact("normal_state"))
            for s in r.steps]
    uscale = max([float(max(u)) for _, _, u, _ in hist] + [0.0])
    msgs, checked = [], 0
    for number, p, u, ns in hist:
        worst, jw = 0.0, -1
        for j in range(len(area)):
            if area[j] > 0.0 and ns[j] != 0:
                checked += 1
                pj = max(float(p[j]), 0.0)
                if pj >= pmax[j]:
                    ulaw = float(laws.virgin_closure(pj, cn, m))
                else:
                    ua = float(laws.virgin_closure(pmax[j], cn, m))
                    ulaw = ua - cn2 * (pmax[j] ** m2 - pj ** m2)
                    if pj <= 0.0:
                        ulaw = max(ulaw, 0.0)
                d = max(u[j] - ulaw, 0.0) if pj <= 0.0 else abs(u[j] - ulaw)
                if d > worst:
                    worst, jw = d, j
            pmax[j] = max(pmax[j], float(p[j]))
        if worst > TOL_U * uscale:
            msgs.append("increment %d: closure of pair %d off its law by %.3e of the largest closure"
                        % (number, jw + 1, worst / uscale))
    return msgs, checked


def main():
    if len(sys.argv) != 3:
        print(__doc__.split("\n\n")[1])
        return 2
    result, check = sys.argv[1], sys.argv[2]
    try:
        checks = parse(check)
        law = read_law(os.path.splitext(check)[0] + ".dat")
    except (CheckFormatError, ValueError, OSError) as e:
        print("check_branch_law: %s" % e)
        return 2
    failed = 0
    for c, ok, msg in check_result(result, checks):
        print("%s  %s: %s\n        %s" % ("PASS" if ok else "FAIL", c.where, c.label, msg))
        failed += not ok
    print("%d of %d checks hold" % (len(checks) - failed, len(checks)))
    msgs, checked = law_misfits(result, law)
    if checked == 0:
        msgs.append("no closed pair was checked against the law")
    for msg in msgs:
        print("FAIL  normal law: " + msg)
    print("normal law: %d closed pair(s) over the increments checked, %d increment(s) off the law"
          % (checked, len(msgs)))
    return 1 if failed or msgs else 0


if __name__ == "__main__":
    sys.exit(main())
