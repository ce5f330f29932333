#!/usr/bin/python3
"""Calibrate the rough interface from measured curves and print the CONTACT cards.

    tools/calibrate.py normal   DATA.csv [--units KGF_UM|N_UM|MODEL] [--replay] ...
    tools/calibrate.py tangent  DATA.csv [--units ...] [--hardening auto|on|off] [--S S] [--replay]
    tools/calibrate.py friction DATA.csv [--units ...]
    tools/calibrate.py topography SURFACE [SURFACE2] --E1 E --nu1 NU [--E2 E --nu2 NU] [--hardness H]
                       --pressure-range PMIN PMAX [--units ...] [--size LX [LY] --length-unit U] [--replay]

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

topography: the pressure-closure curve computed from measured surfaces (SurfaceTopography reads
the scan, ContactMechanics solves the rough contact by FFT boundary elements), then fitted as
`normal` data; it runs in its own virtual environment (tools/setup_topography.sh, created on
first use).  Exit code 2 also for a surface that cannot be read, or is too small or too coarse
for the pressure range; 4: the calibration is doubtful (the power law does not hold over the
range, or the constants move with the grid or the sample size); 1: the BEM did not converge.
"""
import argparse
import math
import os
import subprocess
import sys

from k2d import calibration as cal


def parser():
    ap = argparse.ArgumentParser(prog="calibrate.py", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="docs/calibration.md: the format, the fits and a worked example.")
    sub = ap.add_subparsers(dest="law", required=True, metavar="{normal,tangent,friction,topography}")

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

    p = sub.add_parser("topography", help="c_n, m (and c_n2, m2 with --hardness) from measured surfaces, "
                       "by boundary elements")
    p.add_argument("surfaces", nargs="+", metavar="SURFACE", help="one or two height maps (.x3p, .sur, .opd, "
                   ".plu, .datx, .nc, ...); two: the composite roughness of the facing surfaces")
    p.add_argument("--units", type=str.upper, choices=cal.CARD_UNITS, default="KGF_UM",
                   help="unit convention of the cards, and of E, H and the pressures (default KGF_UM: um, kgf/cm2)")
    p.add_argument("--model-units", default="mm,N/mm2", metavar="LENGTH,PRESSURE",
                   help="the model's units for --units MODEL (default mm,N/mm2)")
    p.add_argument("--size", type=float, nargs="+", metavar="L",
                   help="LX [LY]: the sample's physical size, for a height map that does not carry it (a matrix "
                   "of heights as text); in --length-unit; LY defaults to square pixels")
    p.add_argument("--length-unit", help="unit of the heights and of --size, for a height map that does not "
                   "carry one (m, mm, um, nm)")
    p.add_argument("--pressure-unit", help="unit of --E1, --E2, --hardness and --pressure-range "
                   "(kgf/cm2, N/mm2, MPa; default: the cards' pressure unit)")
    p.add_argument("--E1", type=float, required=True, help="Young's modulus of the first body")
    p.add_argument("--nu1", type=float, required=True, help="Poisson's ratio of the first body")
    p.add_argument("--E2", type=float, help="Young's modulus of the second body (default: E1)")
    p.add_argument("--nu2", type=float, help="Poisson's ratio of the second body (default: nu1)")
    p.add_argument("--hardness", type=float, help="penetration hardness: plastic asperities, and the unloading "
                   "branch (c_n2, m2) and residual closure from an unloading to zero")
    p.add_argument("--pressure-range", type=float, nargs=2, required=True, metavar=("PMIN", "PMAX"),
                   help="the nominal pressures to fit over")
    p.add_argument("--points", type=int, default=16, help="pressures from PMIN to PMAX (geometric; default 16)")
    p.add_argument("--same-exponent", action="store_true", help="fit the unloading branch with m2 = m")
    p.add_argument("--no-convergence", action="store_true",
                   help="skip the half-resolution and quarter-sample runs (the BEM's convergence)")
    p.add_argument("--replay", action="store_true", help="run the cards through Kontakt2D and compare")
    p.add_argument("--exe", help="the kontakt2d program (default: K2D_EXECUTABLE, else build/kontakt2d)")
    p.add_argument("--out", default=".", help="folder for the BEM curve (CSV), the plot and the replay (default .)")
    p.add_argument("--no-plot", action="store_true", help="write no plot")
    return ap


def topography_python():
    """None where SurfaceTopography and ContactMechanics import here; else the python of the
    project's topography environment, created by tools/setup_topography.sh on first use."""
    try:
        import ContactMechanics  # noqa: F401
        import SurfaceTopography  # noqa: F401
        return None
    except ImportError:
        pass
    if os.environ.get("K2D_TOPOGRAPHY_ACTIVE"):
        raise RuntimeError("SurfaceTopography or ContactMechanics does not import in %s" % sys.executable)
    here = os.path.dirname(os.path.abspath(__file__))
    out = subprocess.run(["bash", os.path.join(here, "setup_topography.sh")], stdout=subprocess.PIPE, text=True)
    if out.returncode != 0 or not out.stdout.strip():
        raise RuntimeError("the topography environment could not be set up (tools/setup_topography.sh)")
    return out.stdout.strip().splitlines()[-1]


def topography(args, units):
    from k2d import topography as topo
    try:
        punit = cal.unit_value("pressure", args.pressure_unit) if args.pressure_unit else units.pressure
    except ValueError as e:
        print("calibrate.py: error: %s" % e, file=sys.stderr)
        return 2
    pname = args.pressure_unit or units.pressure_name
    if len(args.surfaces) > 2:
        print("calibrate.py: error: expected one or two surfaces, found %d" % len(args.surfaces), file=sys.stderr)
        return 2
    pmin, pmax = (v * punit for v in args.pressure_range)
    if not (0.0 < pmin < pmax and math.isfinite(pmax)):
        print("calibrate.py: error: --pressure-range %g %g: expected 0 < PMIN < PMAX" % tuple(args.pressure_range),
              file=sys.stderr)
        return 2
    if args.points < 5:
        print("calibrate.py: error: --points %d: expected at least 5" % args.points, file=sys.stderr)
        return 2
    try:
        Es = topo.contact_modulus(args.E1 * punit, args.nu1, None if args.E2 is None else args.E2 * punit, args.nu2)
    except ValueError as e:
        print("calibrate.py: error: %s" % e, file=sys.stderr)
        return 2
    H = args.hardness * punit if args.hardness is not None else None
    if H is not None and not (H > 0.0 and math.isfinite(H)):
        print("calibrate.py: error: --hardness %g: expected a positive pressure" % args.hardness, file=sys.stderr)
        return 2
    path = args.surfaces[0]
    try:
        surfs = [topo.read_surface(f, args.size, args.length_unit) for f in args.surfaces]
        surface = surfs[0] if len(surfs) == 1 else topo.composite(*surfs)
        tf = topo.calibrate(surface, path, Es, pmin, pmax, units, hardness=H, points=args.points, out=args.out,
                            same_exponent=args.same_exponent)
        if not args.no_convergence:
            topo.convergence(tf, path, pmin, pmax, units, points=args.points, out=args.out)
    except cal.DataError as e:
        print(str(e), file=sys.stderr)
        return 2
    except RuntimeError as e:                 # the BEM did not converge
        print("calibrate.py: error: %s" % e, file=sys.stderr)
        return 1
    tf.notes.insert(0, "E* = %.6g %s from E1 = %g, nu1 = %g, E2 = %g, nu2 = %g (%s)"
                    % (Es / punit, pname, args.E1, args.nu1, args.E1 if args.E2 is None else args.E2,
                       args.nu1 if args.nu2 is None else args.nu2, pname))
    print(tf.report())
    print("BEM curve: %s" % tf.csv)
    replay = None
    if args.replay:
        from k2d import calibration_replay as rep
        work = os.path.join(args.out, os.path.splitext(os.path.basename(path))[0] + "_replay")
        try:
            replay = rep.replay_normal(tf.fit, work, exe=args.exe)
        except rep.ReplayError as e:
            print("calibrate.py: the replay failed: %s" % e, file=sys.stderr)
            return 1
        print(rep.summary(replay, "closure").replace("computed - data", "computed - BEM"))
        print("replay decks and results: %s" % work)
    if not args.no_plot:
        from k2d import topography_plots as plots
        os.makedirs(args.out, exist_ok=True)
        png = os.path.join(args.out, "%s.png" % os.path.splitext(os.path.basename(path))[0])
        plots.plot_topography(tf, png, replay)
        print("plot: %s" % png)
    if tf.doubtful:
        print("calibrate.py: the calibration is doubtful (exit 4): %s" % tf.doubtful[0].split(":")[0], file=sys.stderr)
        return 4
    return 0


def main(argv=None):
    args = parser().parse_args(argv)
    try:
        units = cal.Units(args.units, cal.parse_model_units(args.model_units))
    except ValueError as e:
        print("calibrate.py: error: %s" % e, file=sys.stderr)
        return 2
    if args.law == "topography":
        try:
            py = topography_python()
        except RuntimeError as e:
            print("calibrate.py: error: %s" % e, file=sys.stderr)
            return 1
        if py is not None:                # run again in the topography environment
            env = dict(os.environ, K2D_TOPOGRAPHY_ACTIVE="1")
            argv = sys.argv[1:] if argv is None else list(argv)
            return subprocess.run([py, os.path.abspath(__file__)] + argv, env=env).returncode
        return topography(args, units)
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
