#!/usr/bin/python3
"""Energy dissipated per cycle against the amplitude (log-log) from one or several result files.

    tools/plot_energy.py RUN1.h5 [RUN2.h5 ...] [-o ENERGY.png] [--labels a,b,...]

Reads the periodic histories the program writes (group /cycles: energy, slip_amplitude,
force_amplitude per cycle and interface; docs/results-format.md) of every file, e.g. copies of
one deck with the stroke changed, a tools/sweep.py over mu or kappa, the two runs of
tools/compare.py, and draws the energy per
cycle against the slip amplitude and against the force amplitude (k2d.loops.plot_energy).
Files without /cycles (written before the program wrote them, or a history without a cycle) are
named and skipped; exit code 1 when no file has cycles (no plot), 2 for a missing file.
"""
import argparse
import os
import sys

from k2d.loops import plot_energy


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", nargs="+")
    ap.add_argument("-o", "--output", default=None, help="PNG file (default: the first file's name with _energy.png)")
    ap.add_argument("--labels", default=None, help="legend labels, one per file, separated by commas")
    args = ap.parse_args(argv)
    for p in args.results:
        if not os.path.isfile(p):
            print("plot_energy.py: error: %s: no such result file" % p, file=sys.stderr)
            return 2
    labels = args.labels.split(",") if args.labels else None
    if labels and len(labels) != len(args.results):
        print("plot_energy.py: error: --labels: expected %d labels (one per file), found %d"
              % (len(args.results), len(labels)), file=sys.stderr)
        return 2
    out = args.output or os.path.splitext(args.results[0])[0] + "_energy.png"
    png, skipped = plot_energy(args.results, out, labels)
    for p in skipped:
        print("energy plot: %s has no periodic histories (/cycles): skipped" % p)
    if png is None:
        print("energy plot: none (no file has /cycles)")
        return 1
    print("energy plot: " + png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
