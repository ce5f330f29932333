#!/usr/bin/python3
"""Reproduce the numerical examples of Altenbach & Buczkowski (section 5): run every
deck of k2d.examples (tools/make_examples.py) and turn the HDF5 results into the paper's tables and
figures, each beside the paper's own numbers (CSV + PNG).

    tools/paper_figures.py --all            # build if needed, run every deck, every table and figure
    tools/paper_figures.py --all -j 4       # with 4 runs at a time (default: the number of CPUs)
    tools/paper_figures.py --figures        # only redraw from the results already there
    tools/paper_figures.py --all --only 5.1 # one example (5.1, 5.2 or 5.3)

Output: results/paper/ (git-ignored): decks/, h5/, logs/, the CSV tables, the PNG
figures, tables_5_1.md, tables_5_2.md, tables_5_3.md (every table in Markdown) and
runtimes.csv.  The figures and the
CSV tables are also copied to docs/figures/ (unless --no-docs), which
docs/validation.md shows.  The work is done by the package (k2d.examples writes the decks,
k2d.paper draws, reading through k2d.results); this is its command line.
"""
import argparse
import os
import shutil
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from k2d import paper  # noqa: E402
from k2d.build import find_or_build  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--all", action="store_true", help="run every deck, then draw every table and figure")
    ap.add_argument("--figures", action="store_true", help="only draw, from the results already there")
    ap.add_argument("--only", choices=sorted(paper.EXAMPLES), action="append", help="one example (repeatable)")
    ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 2, help="runs at a time")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "paper"), help="results folder")
    ap.add_argument("--exe", default=None,
                    help="the kontakt2d program (default: $K2D_EXECUTABLE, else build/kontakt2d, built if needed)")
    ap.add_argument("--no-docs", action="store_true", help="do not copy the figures and tables to docs/figures")
    args = ap.parse_args(argv)
    if not (args.all or args.figures):
        ap.error("say --all (run and draw) or --figures (draw only)")
    which = args.only or sorted(paper.EXAMPLES)
    os.makedirs(args.out, exist_ok=True)
    if args.all:
        exe = find_or_build(args.exe)
        names = paper.names_of(which)
        t0 = time.time()
        done = paper.run_examples(exe, args.out, names, max(1, args.jobs))
        # exit code 4: completed with doubts (the paper's explicit scheme drifts off the law)
        bad = [n for n, (rc, dt) in done.items() if rc not in (0, 4)]
        print("%d runs in %.0f s%s" % (len(done), time.time() - t0, ("; failed: " + ", ".join(bad)) if bad else ""))
    for w in which:
        print("example %s ..." % w, flush=True)
        paper.draw(args.out, w)
    if not args.no_docs:
        dst = os.path.join(ROOT, "docs", "figures")
        os.makedirs(dst, exist_ok=True)
        for fn in sorted(os.listdir(args.out)):
            if fn.endswith((".png", ".csv", ".md")) and fn != "runtimes.csv":
                shutil.copy(os.path.join(args.out, fn), os.path.join(dst, fn))
    print("tables and figures in %s%s" % (args.out, "" if args.no_docs else " (copied to docs/figures)"))


if __name__ == "__main__":
    main()
