#!/usr/bin/python3
"""Increment count against error for each contact scheme (docs/accuracy-and-stability.md).

For two cases it reruns a deck with N increments (5 % of the load first, then N - 1 equal
increments, as in the paper) under SCHEME INCREMENTAL (the paper), the same with the first
increment iterated (FIRSTINC ITERATE) and SCHEME NEWTON, and measures the error against a
reference:

* V1, the normal patch test (tests/decks/contact/v1_plane_q4.dat): the closed form
  u_n = c_n p0^m;
* the coarse punch of the paper's example 5.1 (tests/decks/stability/
  s2_first_increment_large.dat, Coulomb friction 0.2): a Newton run with 160 increments.

Writes increment_study.csv and increment_study.png into the output folder.  The study is the
package module k2d.increment_study (reading through k2d.results); this is its command line.

    tools/increment_study.py [--exe build/kontakt2d] [--out results/increment_study]
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from k2d import increment_study as st  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "kontakt2d"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "increment_study"))
    args = ap.parse_args(argv)
    if not os.path.exists(args.exe):
        sys.exit(f"no kontakt2d at {args.exe}: build first (tools/run.sh builds)")
    os.makedirs(args.out, exist_ok=True)
    work = os.path.join(args.out, "work")
    os.makedirs(work, exist_ok=True)
    try:
        rows = st.measure(args.exe, work)
    except RuntimeError as e:
        sys.exit(str(e))
    csv_path = os.path.join(args.out, "increment_study.csv")
    st.write_csv(csv_path, rows)
    png = os.path.join(args.out, "increment_study.png")
    st.chart(rows, png)
    print(f"table: {csv_path}\nchart: {png}")


if __name__ == "__main__":
    main()
