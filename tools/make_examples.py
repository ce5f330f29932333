#!/usr/bin/python3
"""Write the decks of the paper's three examples (section 5 of Altenbach &
Buczkowski; SPEC §6 is the reconstruction) and of their variants.

    tools/make_examples.py                 # the example decks of inputs/
    tools/make_examples.py --all DIR       # every variant used by tools/paper_figures.py, into DIR
    tools/make_examples.py --list          # the names of the variants

The generators are the package module k2d.examples (tools/k2d/examples.py).
"""
import argparse
import os

from k2d import examples

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--all", metavar="DIR", help="write every variant into DIR")
    ap.add_argument("--list", action="store_true", help="list the variants")
    args = ap.parse_args(argv)
    if args.list:
        for name in examples.variants():
            print(name)
        return
    if args.all:
        paths = examples.write_variants(args.all)
        print("%d decks in %s" % (len(paths), args.all))
        return
    for path in examples.write_inputs(ROOT):
        print(os.path.relpath(path, ROOT))


if __name__ == "__main__":
    main()
