#!/usr/bin/python3
"""Compare a result file with the expected values of its deck.

    check_deck.py RESULT.h5 DECK.check

The check file sits beside the deck (inputs/lame_cylinder.check beside
inputs/lame_cylinder.dat); docs/DEVELOPERS.md documents its format.  Each
check prints one line (PASS or FAIL, the file and line of the check, what was
measured).  Exit code 0 when every check holds, 1 when one fails, 2 when the
check file is malformed.  Needs tools/k2d on the Python path (ctest sets
PYTHONPATH).
"""
import argparse
import sys

from k2d.checks import CheckFormatError, check_result, parse


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("check")
    args = ap.parse_args()
    try:
        checks = parse(args.check)
    except CheckFormatError as e:
        print("check_deck: %s" % e)
        return 2
    failed = 0
    for c, ok, msg in check_result(args.result, checks):
        print("%s  %s: %s\n        %s" % ("PASS" if ok else "FAIL", c.where, c.label, msg))
        failed += not ok
    print("%d of %d checks hold" % (len(checks) - failed, len(checks)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
