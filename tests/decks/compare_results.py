#!/usr/bin/python3
"""Compare the displacements of two Kontakt2D result files.

    compare_results.py A.h5 B.h5 [--rtol 1e-10]

Every increment of A must be in B, with max |u_A - u_B| <= rtol * max |u_A|.
Reads the files through k2d.results (tools/k2d on the Python path; ctest sets
PYTHONPATH).  Exit code 0 when they agree.
"""
import argparse
import sys

import numpy as np

from k2d.results import Result


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--rtol", type=float, default=1.0e-10)
    args = p.parse_args()
    worst = 0.0
    ra, rb = Result(args.a), Result(args.b)
    if not ra.steps:
        print("no increments in", args.a)
        return 1
    for sa in ra.steps:
        try:
            sb = rb.step(sa.number)
        except KeyError:
            print(f"increment {sa.number} missing in {args.b}")
            return 1
        ua = sa.field("displacement")
        ub = sb.field("displacement")
        scale = np.abs(ua).max()
        diff = np.abs(ua - ub).max()
        rel = diff / scale if scale > 0 else diff
        worst = max(worst, rel)
        if not rel <= args.rtol:
            print(f"increment {sa.number}: max |du| / max |u| = {rel:.3e} > {args.rtol:.1e}")
            return 1
    print(f"agree: {len(ra.steps)} increment(s), max |du| / max |u| = {worst:.3e} <= {args.rtol:.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
