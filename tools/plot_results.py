#!/usr/bin/python3
"""Plot a Kontakt2D result file: deformed mesh coloured by a stress measure.

The drawing is k2d.plot (reading through k2d.results); this is its command line.

    tools/plot_results.py RESULTS.h5 [-o PLOT.png] [--increment N]
                          [--component mises|xx|yy|xy|zz] [--scale S] [--zoom auto|none]

When the file holds contact results (group `contact` in the increment), a
second panel shows the contact pressure and shear along the contact surface
(slipping pairs marked: in slip and carrying a normal force), and the mesh panel zooms on a contact zone that is
small against the model (--zoom none shows the whole model).
"""

import argparse
import sys

from k2d.plot import COMPONENTS, plot_result


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("-o", "--output", default=None, help="PNG file (default: results name with .png)")
    ap.add_argument("--increment", type=int, default=0, help="increment number (default: the last)")
    ap.add_argument("--component", default="mises", choices=["mises"] + list(COMPONENTS))
    ap.add_argument("--scale", type=float, default=None, help="displacement magnification (default: automatic)")
    ap.add_argument("--zoom", default="auto", choices=["auto", "none"],
                    help="auto: show the mesh around a contact zone that is small against the model")
    args = ap.parse_args(argv)
    try:
        out = plot_result(args.results, args.output, args.increment, args.component, args.scale, args.zoom)
    except ValueError as e:
        sys.exit(str(e))
    print(f"plot: {out}")


if __name__ == "__main__":
    main()
