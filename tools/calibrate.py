#!/usr/bin/python3
"""Calibrate the rough interface from measured curves and print the CONTACT cards.

    tools/calibrate.py normal   DATA.csv [--units KGF_UM|N_UM|MODEL] [--replay] ...
    tools/calibrate.py tangent  DATA.csv [--units ...] [--hardening auto|on|off] [--S S] [--replay]
    tools/calibrate.py friction DATA.csv [--units ...]

DATA.csv: a header line naming the columns with their units in brackets, then the rows in the
order they were measured (lines starting with # are comments):
    normal    p [kgf/cm2|N/mm2|MPa], u [um|mm] (closure), optional branch (L, U, R)
    tangent   pn [...], ut [um|mm], pt [...], optional curve (rows of one curve together)
    friction  slip [um|mm] (effective slip), mu [-]  (or pt [...] and pn [...])

The report gives the constants with 95 % confidence intervals, the residuals in the data's
units, warnings where the data does not determine a constant, and the cards, each on a line of
its own, in the deck's columns.  A plot per fit goes to --out (default: the current folder),
named after the data file (DATA.png).
With --replay the cards are run through Kontakt2D on a uniform block that replays the measured
history, and the computed closures (tractions) are compared with the data and plotted.
docs/calibration.md has a worked example.  Exit code 2: the data file cannot be used (the
message names file, line and column); 1: the replay failed.
"""
import argparse
import os
import sys

from k2d import calibration as cal


def parser():
    ap = argparse.ArgumentParser(prog="calibrate.py", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="docs/calibration.md: the format, the fits and a worked example.")
    sub = ap.add_subparsers(dest="law", required=True, metavar="{normal,tangent,friction}")

    def common(p):
        p.add_argument("data", help="CSV file of the measurements")
        p.add_argument("--units", type=str.upper, choices=cal.CARD_UNITS, default="KGF_UM",
                       help="unit convention of the cards (default KGF_UM: um and kgf/cm2)")
        p.add_argument("--model-units", default="mm,N/mm2", metavar="LENGTH,PRESSURE",
                       help="the model's units for --units MODEL (default mm,N/mm2)")
        p.add_argument("--noise", choices=("relative", "absolute"), default="relative",
                       help="measurement error proportional to the value (default) or uniform")
        p.add_argument("--out", default=".", help="folder for the plot and the replay files (default .)")
        p.add_argument("--no-plot", action="store_true", help="write no plot")

    p = sub.add_parser("normal", help="c_n, m (loading) and c_n2, m2 (unloading) from pressure-closure curves")
    common(p)
    p.add_argument("--loading-only", action="store_true",
                   help="fit the loading curve only (CN2, M2 left to the program's defaults)")
    p.add_argument("--same-exponent", action="store_true", help="fit the unloading branch with m2 = m")
    p.add_argument("--replay", action="store_true", help="run the cards through Kontakt2D and compare")
    p.add_argument("--replay-floor", type=float, default=0.0,
                   help="replay unloading rows below this fraction of the peak pressure at it and do not "
                        "compare them (default 0: every row as measured, unloading to zero included)")
    p.add_argument("--exe", help="the kontakt2d program (default: K2D_EXECUTABLE, else build/kontakt2d)")

    p = sub.add_parser("tangent", help="R, S (and mu, kappa) from tangential curves at several normal pressures")
    common(p)
    p.add_argument("--hardening", choices=("auto", "on", "off"), default="auto",
                   help="the hardening branch: from the data (auto), always, never")
    p.add_argument("--S", type=float, dest="s_fixed", help="fix S (e.g. 1 - m) instead of fitting it")
    p.add_argument("--replay", action="store_true", help="run the cards through Kontakt2D and compare")
    p.add_argument("--exe", help="the kontakt2d program (default: K2D_EXECUTABLE, else build/kontakt2d)")

    p = sub.add_parser("friction", help="Fredriksson's mu_m, beta, n from friction against effective slip")
    common(p)
    return ap


def main(argv=None):
    args = parser().parse_args(argv)
    try:
        units = cal.Units(args.units, cal.parse_model_units(args.model_units))
    except ValueError as e:
        print("calibrate.py: error: %s" % e, file=sys.stderr)
        return 2
    try:
        if args.law == "normal":
            fit = cal.fit_normal(args.data, units, loading_only=args.loading_only,
                                 same_exponent=args.same_exponent, noise=args.noise)
        elif args.law == "tangent":
            fit = cal.fit_tangent(args.data, units, hardening=args.hardening, s_fixed=args.s_fixed,
                                  noise=args.noise)
        else:
            fit = cal.fit_friction(args.data, units, noise=args.noise)
    except cal.DataError as e:
        print(str(e), file=sys.stderr)
        return 2
    print(fit.report())
    stem = os.path.splitext(os.path.basename(args.data))[0]
    replay = None
    if getattr(args, "replay", False):
        from k2d import calibration_replay as rep
        work = os.path.join(args.out, stem + "_replay")
        try:
            if args.law == "normal":
                replay = rep.replay_normal(fit, work, exe=args.exe, floor=args.replay_floor)
                print(rep.summary(replay, "closure"))
            else:
                replay = rep.replay_tangent(fit, work, exe=args.exe)
                print(rep.summary(replay, "tangential traction"))
        except rep.ReplayError as e:
            print("calibrate.py: the replay failed: %s" % e, file=sys.stderr)
            return 1
        print("replay decks and results: %s" % work)
    if not args.no_plot:
        from k2d import calibration_plots as plots
        os.makedirs(args.out, exist_ok=True)
        path = os.path.join(args.out, "%s.png" % stem)
        if args.law == "normal":
            plots.plot_normal(fit, path, replay)
        elif args.law == "tangent":
            plots.plot_tangent(fit, path, replay)
        else:
            plots.plot_friction(fit, path)
        print("plot: %s" % path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
