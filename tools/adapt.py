#!/usr/bin/python3
"""Refine a model until its estimated error is below a target (docs/adaptivity.md).

    tools/adapt.py DECK --target 0.01 [--max-dofs N] [-o DIR] [--exe KONTAKT2D]
                   [--uniform] [--compare] [--max-steps N] [--max-growth G] [--no-singular]
                   [--uniform-contact] [--contact-layer]

A deck with a MESH block whose .geo lies beside its .msh is remeshed by gmsh: adaptively, from
a size field made of the error indicators of the last run (the program's `error_indicator`
when the result file has it, else the patch-recovery estimate of k2d.adapt; each mesh at most
about G times the elements of the last, default 4; the contact's singular edges refined at
their own rate unless --no-singular), or with --uniform by halving the .geo's sizes; --compare
runs both.  A quadratic .geo is meshed with quadrilaterals only (the program has no 6-node
triangle).  A card deck (ELEMENTS and NODES) is refined
uniformly, every element split into four, for at least three meshes, and the key outputs (peak
pressure, contact width, approach, largest von Mises stress, slip zone) are extrapolated by
Richardson's rule with their estimated error.

DIR (default results/<deck name>_adapt/) gets the final result as tools/run.sh leaves it
(<name>.h5, .xdmf, .lis, .png; with contact the history plots and <name>_stages.md), the
convergence table <name>_adapt.md and .csv (DOFs, estimated error, key outputs, CPU seconds per
step), the chart <name>_adapt.png (error against DOFs and against CPU time) and every step's
deck, mesh and result under steps_*/.
Exit code 0 when the target was reached, 1 when the budget or the step limit ended the
refinement first, 2 for a bad request, 3 when a run failed.
"""
import argparse
import os
import subprocess
import sys

from k2d import adapt as ad
from k2d.build import ROOT, find_or_build


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("deck")
    ap.add_argument("--target", type=float, required=True, help="relative energy-norm error to reach, e.g. 0.01")
    ap.add_argument("--max-dofs", type=int, default=200000, help="largest model to solve (default 200000)")
    ap.add_argument("-o", "--output", default=None, help="directory (default results/<deck name>_adapt)")
    ap.add_argument("--exe", default=None, help="the kontakt2d program (default: build/kontakt2d, built if needed)")
    ap.add_argument("--uniform", action="store_true", help="MESH decks: halve the .geo's sizes instead of adapting")
    ap.add_argument("--compare", action="store_true", help="MESH decks: adaptive and uniform, in one table and chart")
    ap.add_argument("--max-steps", type=int, default=8, help="most meshes per method (default 8)")
    ap.add_argument("--max-growth", type=float, default=ad.MAX_GROWTH,
                    help="adaptive: elements of a mesh over the last one's, at most "
                    "(default %g; 0: no limit)"
                    % ad.MAX_GROWTH)
    ap.add_argument("--uniform-contact", action="store_true",
                    help="adaptive: one size along each curved contact zone, the smallest the "
                    "indicators ask there (docs/adaptivity.md: measured, no gain on Hertz)")
    ap.add_argument("--contact-layer", action="store_true",
                    help="adaptive: a boundary layer of quadrilaterals along curved contact zones, "
                    "its first layer the local size (docs/adaptivity.md)")
    ap.add_argument("--no-singular", action="store_true",
                    help="adaptive: no singular rate at the contact's singular edges "
                    "(docs/adaptivity.md)")
    args = ap.parse_args(argv)
    try:
        if not os.path.isfile(args.deck):
            raise ad.AdaptError("%s: no such deck" % args.deck)
        if not 0.0 < args.target < 1.0:
            raise ad.AdaptError("--target: expected a relative error between 0 and 1, found %g" % args.target)
        if args.max_dofs <= 0:
            raise ad.AdaptError("--max-dofs: expected a positive count, found %d" % args.max_dofs)
        kind, msh, geo = ad.deck_kind(args.deck)
        if kind == "mesh" and geo is None:
            raise ad.AdaptError("%s: its mesh %s has no .geo beside it to remesh" % (args.deck, msh))
        if kind == "cards" and (args.uniform or args.compare):
            raise ad.AdaptError("--uniform and --compare are for MESH decks; a card deck is refined uniformly anyway")
        name = os.path.splitext(os.path.basename(args.deck))[0]
        out = args.output or os.path.join(ROOT, "results", name + "_adapt")
        os.makedirs(out, exist_ok=True)
        exe = find_or_build(args.exe)
        print("adapt: %s (%s deck), target %g, budget %d DOFs" % (args.deck, "gmsh" if kind == "mesh" else "card",
                                                                    args.target, args.max_dofs))
        rich = {}
        if kind == "mesh":
            rows = ad.adapt_mesh_deck(args.deck, args.target, args.max_dofs, out, exe, uniform=args.uniform,
                                      max_steps=args.max_steps, max_growth=args.max_growth or None,
                                      singular=not args.no_singular,
                                      uniform_contact=args.uniform_contact,
                                      contact_layer=args.contact_layer)
            if args.compare and not args.uniform:
                rows += ad.adapt_mesh_deck(args.deck, args.target, args.max_dofs, out, exe, uniform=True,
                                           max_steps=args.max_steps)
        else:
            rows = ad.refine_card_deck(args.deck, args.target, args.max_dofs, out, exe,
                                       max_levels=max(args.max_steps, 3))
            rich = ad.richardson_table(rows)
    except ad.AdaptError as e:
        print("adapt.py: error: %s" % e, file=sys.stderr)
        return 3 if "kontakt2d" in str(e) and "exit code" in str(e) else 2
    ad.cumulate(rows)
    ad.print_flags(rows)
    md = ad.write_tables(rows, rich, out, name, args.deck, args.target, args.max_dofs)
    png = ad.plot_convergence(rows, os.path.join(out, name + "_adapt.png"), args.target)
    first = [r for r in rows if r["method"] == rows[0]["method"]]
    h5 = ad.publish(first[-1]["h5"], out, name)
    tools = os.path.dirname(os.path.abspath(__file__))
    subprocess.call([sys.executable, os.path.join(tools, "plot_results.py"), h5,
                     "-o", os.path.join(out, name + ".png")], stdout=subprocess.DEVNULL)
    subprocess.call([sys.executable, os.path.join(tools, "plot_history.py"), h5, "--stages-file",
                     os.path.join(out, name + "_stages.md")], stdout=subprocess.DEVNULL)
    print("table: %s (and .csv); chart: %s; result: %s" % (md, png, h5))
    return 0 if first[-1]["estimated_error"] <= args.target else 1


if __name__ == "__main__":
    sys.exit(main())
