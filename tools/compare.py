#!/usr/bin/python3
"""Compare two runs of a joint and write a short report (Markdown with PNG figures).

    tools/compare.py DECK --vary LAW=IDEAL          the same joint, rough against ideal contact
    tools/compare.py DECK --vary SCHEME=INCREMENTAL  the deck's scheme against the paper's
    tools/compare.py DECK --vary SCHEME=NEWTON       ... against Newton
    tools/compare.py DECK_A DECK_B                   two decks
        [-o DIR] [--exe KONTAKT2D] [--approach-nodes A,B]

With --vary the deck is run as it is and with the one card changed (LAW on every interface of
the CONTACT block, or SCHEME for the block), each in its own kontakt2d process.  The report
goes to DIR/report.md (default results/compare_<deck>_<card>_<value>/ or
results/compare_<deck a>_<deck b>/) with its figures beside it and the numbers in
DIR/report.json.  The figures are compared at like states (the same load factors along the same
load path), or the report says that none exists.  Exit code 2 for a bad request (message names
what was expected), 3 when a run failed (before writing a result file: no report; after: the
report names the failed run and compares the last state both runs reached).
"""
import argparse
import json
import os
import sys

from k2d.build import ROOT, find_or_build
from k2d.compare import CompareError, compare_runs, parse_vary, vary_deck


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("decks", nargs="+", help="one deck with --vary, or two decks")
    ap.add_argument("--vary", default=None, help="KEY=VALUE: LAW=ROUGH|IDEAL or SCHEME=INCREMENTAL|NEWTON|MODIFIED")
    ap.add_argument("-o", "--output", default=None, help="directory of the report")
    ap.add_argument("--exe", default=None, help="the kontakt2d program (default: build/kontakt2d, built if needed)")
    ap.add_argument("--approach-nodes", default=None, help="node of body A and node of body B, e.g. 120,4")
    args = ap.parse_args(argv)
    try:
        for d in args.decks:
            if not os.path.isfile(d):
                raise CompareError("%s: no such deck" % d)
        approach = None
        if args.approach_nodes:
            try:
                approach = tuple(int(v) for v in args.approach_nodes.split(","))
            except ValueError:
                approach = ()
            if len(approach) != 2:
                raise CompareError("--approach-nodes: expected two node numbers A,B, found %r" % args.approach_nodes)
        name = [os.path.splitext(os.path.basename(d))[0] for d in args.decks]
        if args.vary:
            if len(args.decks) != 1:
                raise CompareError("--vary takes one deck, found %d" % len(args.decks))
            key, value = parse_vary(args.vary)
            out = args.output or os.path.join(ROOT, "results",
                                              "compare_%s_%s_%s" % (name[0], key.lower(), value.lower()))
            os.makedirs(out, exist_ok=True)
            with open(args.decks[0]) as f:
                text = vary_deck(f.read(), key, value, args.decks[0])
            # the variant sits beside the original so that relative paths in the deck (MESH) still hold
            variant = os.path.join(os.path.dirname(os.path.abspath(args.decks[0])),
                                   ".%s_%s_%s.dat" % (name[0], key.lower(), value.lower()))
            with open(variant, "w") as f:
                f.write(text)
            try:
                with open(os.path.join(out, os.path.basename(variant).lstrip(".")), "w") as f:
                    f.write(text)
                runs = [("as given", args.decks[0]), ("%s %s" % (key, value), variant)]
                md = compare_runs(runs, out, find_or_build(args.exe), "%s: %s %s against the deck as given"
                                  % (name[0], key, value), approach)
            finally:
                os.remove(variant)
        else:
            if len(args.decks) != 2:
                raise CompareError("expected two decks (or one deck with --vary), found %d" % len(args.decks))
            out = args.output or os.path.join(ROOT, "results", "compare_%s_%s" % tuple(name))
            runs = [(name[0], args.decks[0]), (name[1] if name[1] != name[0] else name[1] + " (2)", args.decks[1])]
            md = compare_runs(runs, out, find_or_build(args.exe), "%s against %s" % (name[1], name[0]), approach)
    except CompareError as e:
        print("compare.py: error: %s" % e, file=sys.stderr)
        return 3 if "wrote no result file" in str(e) else 2
    print("report: " + md)
    with open(os.path.join(os.path.dirname(md), "report.json")) as f:
        bad = json.load(f)["failed"]
    if bad:
        print("compare.py: error: the run %s failed (see the report)" % " and the run ".join(bad), file=sys.stderr)
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())
