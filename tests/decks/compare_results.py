#!/usr/bin/python3
"""Compare the displacements of two Kontakt2D result files.

    compare_results.py A.h5 B.h5 [--rtol 1e-10]

Every increment of A must be in B, with max |u_A - u_B| <= rtol * max |u_A|.
Reads only what docs/results-format.md documents.  Exit code 0 when they agree.
"""
import argparse
import sys

import h5py
import numpy as np


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--rtol", type=float, default=1.0e-10)
    args = p.parse_args()
    worst = 0.0
    with h5py.File(args.a, "r") as fa, h5py.File(args.b, "r") as fb:
        incs = sorted(fa["increments"])
        if not incs:
            print("no increments in", args.a)
            return 1
        for inc in incs:
            if inc not in fb["increments"]:
                print(f"increment {inc} missing in {args.b}")
                return 1
            ua = fa["increments"][inc]["displacement"][...]
            ub = fb["increments"][inc]["displacement"][...]
            scale = np.abs(ua).max()
            diff = np.abs(ua - ub).max()
            rel = diff / scale if scale > 0 else diff
            worst = max(worst, rel)
            if not rel <= args.rtol:
                print(f"increment {inc}: max |du| / max |u| = {rel:.3e} > {args.rtol:.1e}")
                return 1
    print(f"agree: {len(incs)} increment(s), max |du| / max |u| = {worst:.3e} <= {args.rtol:.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
