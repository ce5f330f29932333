#!/usr/bin/python3
"""History plots of a Kontakt2D result file with contact (k2d.history_plot is the drawing).

    tools/plot_history.py RESULTS.h5 [--pairs 3,7] [--increments 10,40,60] [--loop-pairs 2,5]
                          [--approach-nodes A,B] [--stages] [--stages-file FILE.md]

Writes RESULTS_approach.png (load factor and total normal force against the approach),
RESULTS_pairs.png (pressure-closure paths of chosen pairs over the law's curves; default the
most and the least loaded pair), RESULTS_interface.png (pressure and shear along the interface
at several increments; default: the turning points of the load history, the peak, the last and
a few between), RESULTS_slip.png (the slip zone against the load), for a history that moves
the interface tangentially RESULTS_loops.png (shear-slip p_T-u_T paths of chosen pairs, default
the pairs with the largest range of u_T, and the interface's total tangential force against the
mean u_T of its closed pairs, drawn along the law), and for a file with periodic histories
(/cycles) RESULTS_energy.png (energy per cycle against the amplitude, log-log; several runs:
tools/plot_energy.py).  A file without contact
pairs or with one increment has no history: the script says so and exits 0.  --stages prints
the figures at the end of every load stage as a Markdown table, --stages-file writes it.
"""
import argparse
import os
import sys

from k2d.history_plot import plot_history, stage_table
from k2d.results import Result


def int_list(text):
    try:
        return [int(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError("expected numbers separated by commas, found %r" % text) from None


def node_pair(text):
    v = int_list(text)
    if len(v) != 2:
        raise argparse.ArgumentTypeError("expected two node numbers A,B, found %r" % text)
    return tuple(v)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("--pairs", type=int_list, default=None, help="pair numbers for the pressure-closure plot")
    ap.add_argument("--increments", type=int_list, default=None, help="increments drawn along the interface")
    ap.add_argument("--loop-pairs", type=int_list, default=None,
                    help="pair numbers for the shear-slip loops (default: the largest range of u_T)")
    ap.add_argument("--approach-nodes", type=node_pair, default=None,
                    help="node of body A and node of body B between which the approach is measured")
    ap.add_argument("--stages", action="store_true", help="print the figures at the end of every load stage")
    ap.add_argument("--stages-file", default=None, help="write them (Markdown) into this file")
    args = ap.parse_args(argv)
    if not os.path.exists(args.results):
        sys.exit(f"{args.results}: no such result file")
    try:
        pngs = plot_history(args.results, args.pairs, args.increments, args.approach_nodes,
                            loop_pairs=args.loop_pairs)
    except ValueError as e:
        sys.exit(str(e))
    if not pngs:
        res = Result(args.results)
        why = "no contact pairs" if res.contact is None else "%d increment(s) kept" % len(res.steps)
        print(f"history plots: none for {args.results} ({why})")
        return
    print("history plots: " + ", ".join(pngs))
    table = stage_table(args.results, args.approach_nodes)
    if args.stages:
        print(table)
    if args.stages_file:
        with open(args.stages_file, "w") as f:
            f.write("# Load stages of %s\n\nThe figures at the end of every load stage (k2d.history).\n\n%s"
                    % (os.path.basename(args.results), table))
        print("load stages: " + args.stages_file)


if __name__ == "__main__":
    main()
