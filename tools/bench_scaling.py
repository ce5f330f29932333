#!/usr/bin/python3
"""Scaling benchmark: the rough punch on a foundation from 1e4 to 1e6 equations, every solution path.

    tools/bench_scaling.py [--sizes 1e4 3e4 ...] [--paths skyline:on mumps:on ...]
                           [--spheres a5 a10 a20] [--no-linear] [--no-first] [--orderings amd metis]
                           [--pairs 301 1001 ...] [--tied]
                           [--out DIR] [--generate-only] [--exe PATH] [--timeout S]
    tools/bench_scaling.py --report [--out DIR] [--plot FILE]

The model (issue 13's benchmark family): plane strain, an elastic punch (half width 50, height
50) pressed by 1.2 N/mm2 onto an elastic foundation (half width 120, depth 120), E = 4000 N/mm2,
nu = 0.35 for both; a half model, u_x = 0 on x = 0, the foundation's base clamped.  The rough
interface of example 5.1 (c_n = 1.0, m = 0.5, R = 1.3, S = 0.5 in um and kgf/cm2, Coulomb
friction 0.2, no hardening branch, the NEWTON scheme) joins the punch's base to the foundation
under it through 301 node-to-node pairs (1 202 contact equations), whatever the size.  Load:
5 % in the first increment, then 49 equal increments: 50 increments.

The meshes are gmsh's (`.geo` -> `.msh`, Q4 recombined from a frontal-Delaunay triangulation):
both contact lines carry 300 equal segments (element size a/300 there), and the element size
grows linearly with the distance d from the interface, h = min(h_max, h_c + g d); the growth g
is chosen for each size so that the mesh has about the requested number of equations (an
estimate by numerical integration of the node density 1/h^2, checked against the mesh gmsh
makes and corrected once).  The decks use MESH/GROUP cards (docs/deck-format.md) and keep only
every 10th increment in the result file (OPTIONS RESULTS 10: increments 10, 20, ..., 50;
the last is always written), so that the 40 increments in between skip the full field.

A path is SOLVER:CONDENSE -- the solver (skyline, umfpack, mumps; `-s`) and OPTIONS CONDENSE ON
(bodies condensed onto the contact equations once: by n_c solves, or with MUMPS by its Schur
complement) or OFF (the whole system factorized at every solution).  Each run is a separate
process (OPENBLAS_NUM_THREADS=1 unless set); the table (terminal and OUT/scaling.csv) gives per
size and path the DOFs of the mesh (2 per node, before the restraints), the exit code, the
solutions (summed from the run's progress lines, its terminal log beside the result file) of
the run, its CPU time (user + system) and peak resident memory (from the operating system),
and the largest difference of the final displacements from the first path's, relative to the
largest displacement (all paths solve the same equations).  Unless --no-first, every path also
runs the deck cut to its first increment (`_first` decks), so that a later increment costs
(CPU of 50 increments - CPU of the first) / 49.

Unless --no-linear, every size is also measured by bench/bench_contact.F90 (target
bench_contact, built if needed) in the same run: one linear solve of the same mesh (MUMPS
analysis, factorization of K_AB + K_ref, one back-substitution) and the parts of the Schur path
(analysis + factorization with the Schur complement, condensation, expansion, dense Cholesky
and solve of the 1 202 contact equations); OUT/linear.csv.  --orderings runs bench_contact once per
MUMPS ordering (amd: MUMPS's AMD; metis: METIS's nested dissection given as a user ordering), one
after the other on the same mesh, so that the orderings are compared in one sitting; the report then
adds a table of analysis, ordering, factorization and Schur set-up times per ordering.  `--paths`
with no path runs bench_contact alone.

--pairs gives the n_c axis (issue 28): the interface with that many pairs (pairs - 1 equal
segments on both contact lines, 4 contact equations a pair but the 2 held on x = 0), the mesh
growing away from it to keep about the requested equations (a mesh too small for its interface
comes out larger); a size with other than 301 pairs is labelled SIZE_pPAIRS.  --tied runs, per
mesh, the same model with the interface tied (one conforming mesh, GEO_TIED) through one
linear increment with MUMPS: the yardstick of the n_c axis, its CPU time in OUT/scaling.csv with
each path's ratio to it and the path's solutions per increment.  A path SOLVER:AUTO runs the
deck's default, OPTIONS CONDENSE AUTO.

--spheres adds the rough sphere of example 5.2 (P = 200 N, c_n = 0.8, NEWTON, 5 increments) with
contact spacing a_H/5, a_H/10, a_H/20 (tools/k2d/examples.py), run along the same paths.

--report reads OUT/scaling.csv and OUT/linear.csv and prints the tables of docs/performance.md
(set-up, later increment, total and peak memory against DOFs, each also as a ratio to one linear
solve, with least-squares exponents) and draws the log-log plot (--plot, default
docs/bench/scaling.png).

Sizes are 1e4, 3e4, 1e5, 3e5 and 1e6 equations (default: all; the 1e6 mesh takes a few minutes
to make and the skyline solver there hours).  Default OUT: build/bench_scaling.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

import numpy as np  # noqa: E402

from k2d.build import ROOT, build_target, find_or_build  # noqa: E402
from k2d.deck import SOLVERS, f10  # noqa: E402
from k2d.results import Result  # noqa: E402
from k2d.terminal import progress_solutions, read_terminal  # noqa: E402

SIZES = ["1e4", "3e4", "1e5", "3e5", "1e6"]
PATHS = ["skyline:off", "skyline:on", "umfpack:off", "umfpack:on", "mumps:off", "mumps:on"]

# geometry (mm), contact segments, material, load
A_HALF, H_PUNCH, L_HALF, DEPTH = 50.0, 50.0, 120.0, 120.0
N_CONTACT = 300
H_MAX = 20.0
E, NU, P0 = 4000.0, 0.35, 1.2

GEO = """// Scaling benchmark: rough punch on a foundation, about {target} equations (tools/bench_scaling.py).
a = {a}; H = {h}; L = {l}; D = {d};
hc = a/{nc}; g = {g:.8g}; hmax = {hmax};
// the punch
Point(1) = {{0, 0, 0}}; Point(2) = {{a, 0, 0}}; Point(3) = {{a, H, 0}}; Point(4) = {{0, H, 0}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
// the foundation: under the punch and beside it (its own points: the bodies share no node)
Point(11) = {{0, 0, 0}}; Point(12) = {{a, 0, 0}}; Point(13) = {{L, 0, 0}};
Point(14) = {{L, -D, 0}}; Point(15) = {{a, -D, 0}}; Point(16) = {{0, -D, 0}};
Line(11) = {{11, 12}}; Line(12) = {{12, 13}}; Line(13) = {{13, 14}}; Line(14) = {{14, 15}};
Line(15) = {{15, 16}}; Line(16) = {{16, 11}}; Line(17) = {{12, 15}};
Curve Loop(2) = {{11, 17, 15, 16}}; Plane Surface(2) = {{2}};
Curve Loop(3) = {{12, 13, 14, -17}}; Plane Surface(3) = {{3}};
// both contact lines: {nc} equal segments, so that their nodes pair one to one
Transfinite Curve{{1, 11}} = {nc} + 1;
Field[1] = Distance; Field[1].CurvesList = {{1, 11}}; Field[1].NumPointsPerCurve = 400;
Field[2] = MathEval; Field[2].F = Sprintf("Min(%g, %g + %g*F1)", hmax, hc, g);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6; Mesh.RecombineAll = 1; Mesh.RecombinationAlgorithm = 1;
Physical Surface("punch") = {{1}};
Physical Surface("foundation") = {{2, 3}};
Physical Curve("contact_a") = {{1}};
Physical Curve("contact_b") = {{11}};
Physical Curve("top") = {{3}};
Physical Curve("symmetry") = {{4, 16}};
Physical Curve("base") = {{14, 15}};
"""


# The same model with the interface tied (one conforming mesh, the foundation's top under the
# punch the punch's base): its linear solve is the yardstick of the n_c axis ("tied run").
GEO_TIED = """// Scaling benchmark, the interface tied: about {target} equations (tools/bench_scaling.py).
a = {a}; H = {h}; L = {l}; D = {d};
hc = a/{nc}; g = {g:.8g}; hmax = {hmax};
Point(1) = {{0, 0, 0}}; Point(2) = {{a, 0, 0}}; Point(3) = {{a, H, 0}}; Point(4) = {{0, H, 0}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Point(13) = {{L, 0, 0}}; Point(14) = {{L, -D, 0}}; Point(15) = {{a, -D, 0}}; Point(16) = {{0, -D, 0}};
Line(12) = {{2, 13}}; Line(13) = {{13, 14}}; Line(14) = {{14, 15}};
Line(15) = {{15, 16}}; Line(16) = {{16, 1}}; Line(17) = {{2, 15}};
Curve Loop(2) = {{1, 17, 15, 16}}; Plane Surface(2) = {{2}};
Curve Loop(3) = {{12, 13, 14, -17}}; Plane Surface(3) = {{3}};
Transfinite Curve{{1}} = {nc} + 1;
Field[1] = Distance; Field[1].CurvesList = {{1}}; Field[1].NumPointsPerCurve = 400;
Field[2] = MathEval; Field[2].F = Sprintf("Min(%g, %g + %g*F1)", hmax, hc, g);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6; Mesh.RecombineAll = 1; Mesh.RecombinationAlgorithm = 1;
Physical Surface("punch") = {{1}};
Physical Surface("foundation") = {{2, 3}};
Physical Curve("top") = {{3}};
Physical Curve("symmetry") = {{4, 16}};
Physical Curve("base") = {{14, 15}};
"""


def tied_deck(out, name, target, nseg, g):
    """The tied model of a mesh (same sizes and growth g): its .geo, .msh and one-increment linear
    deck; returns the deck's path."""
    geo = os.path.join(out, name + "_tied.geo")
    msh = os.path.join(out, name + "_tied.msh")
    if not os.path.exists(msh):
        with open(geo, "w") as f:
            f.write(GEO_TIED.format(target=target, a=A_HALF, h=H_PUNCH, l=L_HALF, d=DEPTH, nc=nseg, g=g,
                                    hmax=H_MAX))
        r = subprocess.run(["gmsh", "-2", "-format", "msh41", geo, "-o", msh], capture_output=True, text=True)
        if r.returncode != 0 or not os.path.exists(msh):
            raise SystemExit(f"gmsh failed on {geo}:\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
    text = deck_text(name + "_tied", os.path.basename(msh), "AUTO", target, 2 * msh_nodes(msh), pairs=0)
    head, _, _ = text.partition("CONTACT\n")
    deck = os.path.join(out, name + "_tied.dat")
    with open(deck, "w") as f:
        f.write(head.replace(", 50 Newton increments", ", interface tied, one linear increment")
                + "INCREMENTS\n    1       1.0\nEND\n")
    return deck


def geo_growth(geo):
    """The growth g of a .geo file written by make_mesh."""
    with open(geo) as f:
        for line in f:
            if line.startswith("hc = "):
                return float(line.split("g = ")[1].split(";")[0])
    raise ValueError(f"{geo}: no growth")


def deck_text(name, msh, condense, target, neq, first_only=False, pairs=N_CONTACT + 1):
    """The deck of one size and CONDENSE choice (first_only: cut to its first increment)."""
    c = ["# Scaling benchmark (tools/bench_scaling.py): rough punch on a foundation, plane strain,",
         f"# {neq} DOFs (target {target}), {pairs} contact pairs, 50 Newton increments; units N, mm,",
         f"# N/mm2, roughness constants in um and kgf/cm2 (UNITS KGF_UM).  Mesh {msh} from {name}.geo.",
         "TITLE",
         f"Scaling benchmark: rough punch on foundation, {neq} DOFs, CONDENSE {condense}",
         "CONTROL",
         "#NPOI NELE NVFI NTYP NNOD NMAT NGAU SOLVER",
         "              2    2    0    2    0   SKYLINE",
         "OPTIONS",
         f"CONDENSE  {condense}",
         "RESULTS           10                               # every 10th increment (the last is one)" if not first_only
         else "RESULTS            1",
         "MESH",
         f"GMSH      {msh}",
         "MATERIAL  punch                            1",
         "MATERIAL  foundation                       2",
         "RESTRAINTS",
         "#         group               CODE        UX        UY CASE",
         "GROUP     symmetry              10",
         "GROUP     base                  11",
         "MATERIALS",
         "#MAT          E        NU     THICK",
         f"    1{f10(E)}{f10(NU)}{f10(1.0)}",
         f"    2{f10(E)}{f10(NU)}{f10(1.0)}",
         "LOADS",
         "EDGE",
         "#         group                       PN        PT CASE",
         f"GROUP     top                 {f10(P0)}",
         "CONTACT",
         "LAW       ROUGH",
         "UNITS     KGF_UM",
         "NORMAL           1.0       0.5",
         "TANGENT          1.3       0.5",
         "FRICTION  COULOMB         0.2",
         "HARDENING OFF",
         "SCHEME    NEWTON",
         "SURFACE   A         contact_a",
         "SURFACE   B         contact_b",
         "INCREMENTS",
         "    1      0.05"] + ([] if first_only else ["   49       1.0"]) + ["END"]
    return "\n".join(c) + "\n"


def nodes_estimate(g, nseg=N_CONTACT):
    """Nodes of a quadrilateral mesh of size h(d) = min(h_max, h_c + g d): the integral of
    1/h^2 over both bodies (d = distance to the contact line, midpoint rule)."""
    hc = A_HALF / nseg

    def integral(x0, x1, y0, y1, n=400):
        xs = x0 + (np.arange(n) + 0.5) * (x1 - x0) / n
        ys = y0 + (np.arange(n) + 0.5) * (y1 - y0) / n
        x, y = np.meshgrid(xs, ys)
        d = np.hypot(np.maximum(x - A_HALF, 0.0), y)
        h = np.minimum(H_MAX, hc + g * d)
        return float(np.sum(1.0 / h ** 2)) * (x1 - x0) * (y1 - y0) / n ** 2

    return integral(0, A_HALF, 0, H_PUNCH) + integral(0, L_HALF, -DEPTH, 0)


def growth_for(neq_target, nseg=N_CONTACT):
    """The growth g whose estimated mesh has neq_target equations (2 per node), by bisection
    on log g; 0 when even the uniform mesh is smaller."""
    nodes = neq_target / 2.0
    if nodes_estimate(0.0, nseg) <= nodes:
        return 0.0
    lo, hi = 1e-6, 10.0
    for _ in range(60):
        mid = math.sqrt(lo * hi)
        if nodes_estimate(mid, nseg) > nodes:
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)


def msh_nodes(path):
    """Number of nodes in a gmsh 4.1 ASCII file ($Nodes header)."""
    with open(path) as f:
        for line in f:
            if line.startswith("$Nodes"):
                return int(f.readline().split()[1])
    raise ValueError(f"{path}: no $Nodes section")


def make_mesh(out, name, target, nseg=N_CONTACT):
    """Write NAME.geo and mesh it; adjust the growth once if gmsh's mesh is off by > 10 %
    (nseg contact segments: nseg + 1 pairs; a mesh too small for them comes out larger)."""
    neq = float(target)
    g = growth_for(neq, nseg)
    for attempt in range(3):
        geo = os.path.join(out, name + ".geo")
        with open(geo, "w") as f:
            f.write(GEO.format(target=target, a=A_HALF, h=H_PUNCH, l=L_HALF, d=DEPTH, nc=nseg,
                               g=g, hmax=H_MAX))
        msh = os.path.join(out, name + ".msh")
        r = subprocess.run(["gmsh", "-2", "-format", "msh41", geo, "-o", msh], capture_output=True, text=True)
        if r.returncode != 0 or not os.path.exists(msh):
            raise SystemExit(f"gmsh failed on {geo}:\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
        got = 2 * msh_nodes(msh)          # equations, before the restraints
        ratio = got / float(target)
        if abs(ratio - 1.0) <= 0.10 or g == 0.0:
            return msh, got
        neq = neq / ratio                 # aim the estimate so that the mesh lands on the target
        g = growth_for(neq, nseg)
    return msh, got


def solutions(log):
    """Solutions of the whole run, summed over the progress lines of its terminal log (the
    result file keeps the last increment only)."""
    t = read_terminal(log)
    if t is None:
        raise OSError("cannot read %s" % log)
    return progress_solutions(t)


def run(exe, deck, h5, solver, timeout):
    """One run: exit code, CPU seconds (user + system) and peak RSS (MB) of the process."""
    log = os.path.splitext(h5)[0] + ".log"
    with open(log, "w") as f:
        t0 = time.time()
        p = subprocess.Popen([exe, deck, "-o", h5, "-s", solver], stdout=f, stderr=subprocess.STDOUT,
                             cwd=os.path.dirname(deck))
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.time() - t0 > timeout:
                p.kill()
                pid, status, ru = os.wait4(p.pid, 0)
                return "timeout", ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0
            time.sleep(0.2)
    rc = os.waitstatus_to_exitcode(status)
    return rc, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0


def bench_contact(build, deck, ordering=""):
    """bench_contact's CSV line for a deck, as a dict (None on failure)."""
    exe = os.path.join(build, "bench_contact")
    r = subprocess.run([exe, deck] + ([ordering] if ordering else []), capture_output=True, text=True,
                       cwd=os.path.dirname(deck))
    line = r.stdout.strip().splitlines()[-1] if r.stdout.strip() else ""
    parts = line.split(",")
    if r.returncode != 0 or len(parts) != len(LINEAR_FIELDS):
        print(f"bench_contact failed on {deck}:\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}", flush=True)
        return None
    return {k: (int(v) if k in ("neq", "nc", "nnz_factor", "nnz_factor_schur") else v if k == "ordering"
                else float(v)) for k, v in zip(LINEAR_FIELDS, parts)}


LINEAR_FIELDS = ["neq", "nc", "nnz_factor", "analyse_s", "assembly_s", "factorize_s", "solve_s", "schur_s",
                 "condense_s", "expand_s", "dense_factorize_s", "dense_solve_s", "proj_setup_s", "proj_factorize_s",
                 "proj_solve_s", "peak_rss_mb", "max_rel_diff", "ordering", "ordering_s", "schur_analyse_s",
                 "schur_ordering_s", "nnz_factor_schur"]
# the ordering of the solver's default (mumps_solver ORDERING_DEFAULT): the main tables use its rows
DEFAULT_ORDERING = "amd"
SPHERES = {"a5": 5.0, "a10": 10.0, "a20": 20.0}


def sphere_deck(out, tag):
    """Example 5.2's rough sphere with contact spacing a_H/n (5 NEWTON increments)."""
    from k2d import examples
    path = os.path.join(out, f"sphere_{tag}.dat")
    examples.sphere(path, P=200.0, cn=0.8, update="NEWTON", nincs=5, hdiv=SPHERES[tag])
    return path


def run_paths(exe, label, dofs, decks, paths, out, timeout, rows, first_decks=None):
    """Run every path on the decks of one size; append the rows."""
    ref = None
    for path in paths:
        solver, _, cond = path.partition(":")
        cond = cond.upper()
        h5 = os.path.join(out, f"{label}_{solver}_{cond.lower()}.h5")
        rc, cpu, rss = run(exe, decks[cond], h5, solver, timeout)
        row = {"size": label, "dofs": dofs, "path": path, "rc": rc, "cpu_s": round(cpu, 3), "peak_mb": round(rss, 1)}
        if rc == 0:
            r = Result(h5)
            row["solutions"] = solutions(os.path.splitext(h5)[0] + ".log")
            u = r.last.field("displacement")
            if ref is None:
                ref = u
                row["max_rel_diff"] = 0.0
            else:
                row["max_rel_diff"] = float(np.abs(u - ref).max() / np.abs(ref).max())
        if first_decks and rc == 0:
            h5f = os.path.join(out, f"{label}_{solver}_{cond.lower()}_first.h5")
            rcf, cpuf, _ = run(exe, first_decks[cond], h5f, solver, timeout)
            if rcf == 0:
                row["first_cpu_s"] = round(cpuf, 3)
        rows.append(row)
        print(f"{label:>5s} {dofs:9d} {path:>12s} {str(rc):>7s} {str(row.get('solutions', '-')):>9s} "
              f"{cpu:9.2f} {row.get('first_cpu_s', float('nan')):9.2f} {rss:9.1f} "
              f"{row.get('max_rel_diff', float('nan')):12.2e}", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", nargs="*", default=SIZES, choices=SIZES)
    p.add_argument("--paths", nargs="*", default=PATHS,
                   help="SOLVER:ON|OFF (default: all six; none: bench_contact only)")
    p.add_argument("--orderings", nargs="+", default=[""], choices=["amd", "metis"],
                   help="MUMPS orderings for bench_contact (default: the solver's)")
    p.add_argument("--spheres", nargs="*", default=[], choices=sorted(SPHERES))
    p.add_argument("--pairs", nargs="+", type=int, default=[N_CONTACT + 1],
                   help="contact pairs of the punch's interface (the n_c axis; default 301)")
    p.add_argument("--tied", action="store_true",
                   help="also run each mesh's model with the interface tied, one linear increment (the yardstick;"
                        " with --generate-only: write its mesh and deck)")
    p.add_argument("--no-linear", action="store_true", help="skip bench_contact (one linear solve, Schur parts)")
    p.add_argument("--no-first", action="store_true", help="skip the runs cut to the first increment")
    p.add_argument("--out", default=os.path.join(ROOT, "build", "bench_scaling"))
    p.add_argument("--generate-only", action="store_true", help="write the meshes and decks, run nothing")
    p.add_argument("--exe", help="the kontakt2d program (default: K2D_EXECUTABLE or build/kontakt2d)")
    p.add_argument("--timeout", type=float, default=3600.0, help="seconds per run")
    p.add_argument("--append", action="store_true", help="add to OUT/scaling.csv and OUT/linear.csv")
    p.add_argument("--report", action="store_true", help="tables and plot from OUT's CSV files, run nothing")
    p.add_argument("--plot", default=os.path.join(ROOT, "docs", "bench", "scaling.png"))
    args = p.parse_args()
    if args.report:
        return report(args.out, args.plot)
    for path in args.paths:
        s, _, c = path.partition(":")
        if s not in [n.lower() for n in SOLVERS if n != "AUTO"] or c.upper() not in ("ON", "OFF", "AUTO"):
            raise SystemExit(f"bench_scaling: a path is SOLVER:ON, SOLVER:OFF or SOLVER:AUTO, found {path!r}")
    os.makedirs(args.out, exist_ok=True)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    exe = None if args.generate_only else find_or_build(args.exe)
    build = None
    if not (args.generate_only or args.no_linear):
        # bench_contact beside the program, else built in the program's build directory
        build = os.path.dirname(os.path.abspath(exe))
        if not os.path.exists(os.path.join(build, "bench_contact")):
            build = build_target("bench_contact", build if args.exe else None)

    rows, linear = [], []
    print(f"{'size':>5s} {'DOFs':>9s} {'path':>12s} {'rc':>7s} {'solutions':>9s} {'CPU [s]':>9s} "
          f"{'first [s]':>9s} {'peak [MB]':>9s} {'max |du|/|u|':>12s}", flush=True)
    for size, pairs in [(s, q) for q in args.pairs for s in args.sizes]:
        name = f"punch_{size}" if pairs == N_CONTACT + 1 else f"punch_{size}_p{pairs}"
        label = size if pairs == N_CONTACT + 1 else f"{size}_p{pairs}"
        msh = os.path.join(args.out, name + ".msh")
        if os.path.exists(msh) and os.path.exists(os.path.join(args.out, name + ".geo")):
            neq_mesh = 2 * msh_nodes(msh)          # made by an earlier run: kept
        else:
            msh, neq_mesh = make_mesh(args.out, name, float(size), pairs - 1)
        decks, firsts = {}, {}
        for cond in ("ON", "OFF", "AUTO"):
            for first, store in ((False, decks), (True, firsts)):
                deck = os.path.join(args.out, f"{name}_condense_{cond.lower()}{'_first' if first else ''}.dat")
                with open(deck, "w") as f:
                    f.write(deck_text(name, os.path.basename(msh), cond, size, neq_mesh, first_only=first,
                                      pairs=pairs))
                store[cond] = deck
        tied = None
        if args.tied and args.generate_only:
            # (the tied deck written too, to be run by hand beside the others)
            tied_deck(args.out, name, size, pairs - 1, geo_growth(os.path.join(args.out, name + ".geo")))
        if args.tied and not args.generate_only:
            tdeck = tied_deck(args.out, name, size, pairs - 1, geo_growth(os.path.join(args.out, name + ".geo")))
            trc, tcpu, trss = run(exe, tdeck, os.path.splitext(tdeck)[0] + ".h5", "mumps", args.timeout)
            tied = (tcpu, trss) if trc == 0 else None
            print(f"{label:>5s} tied linear run (mumps): rc {trc}, {tcpu:.2f} s, peak {trss:.0f} MB", flush=True)
        print(f"{size:>5s} {neq_mesh:9d} mesh {os.path.basename(msh)}, decks {name}_condense_on/off[_first].dat",
              flush=True)
        if args.generate_only:
            continue
        for ordering in args.orderings if build else []:
            lin = bench_contact(build, decks["ON"], ordering)
            if lin:
                lin["size"] = size
                lin["dofs"] = neq_mesh
                linear.append(lin)
                print(f"{size:>5s} {neq_mesh:9d} one linear solve: factorize {lin['factorize_s']:.3f} s + solve "
                      f"{lin['solve_s']:.4f} s (analysis {lin['analyse_s']:.3f} s); "
                      f"Schur set-up {lin['schur_s']:.3f} s, "
                      f"condense {lin['condense_s']:.4f} s, expand {lin['expand_s']:.4f} s, dense Cholesky "
                      f"{lin['dense_factorize_s']:.4f} s, in the springs' coordinates {lin['proj_factorize_s']:.4f} s "
                      f"[{lin['ordering']}]", flush=True)
        n0 = len(rows)
        run_paths(exe, label, neq_mesh, decks, args.paths, args.out, args.timeout, rows,
                  None if args.no_first else firsts)
        for r in rows[n0:]:
            r["pairs"] = pairs
            if r.get("solutions"):
                r["sol_per_inc"] = round(r["solutions"] / 50.0, 2)
            if tied:
                r["tied_cpu_s"] = round(tied[0], 3)
                r["ratio_tied"] = round(r["cpu_s"] / tied[0], 2)
            print(f"{label:>5s} {r['path']:>12s} pairs {pairs}: {r.get('sol_per_inc', '-')} solutions per increment"
                  + (f", {r['ratio_tied']:.1f} x the tied run" if tied else ""), flush=True)
    for tag in args.spheres:
        if args.generate_only:
            continue
        deck = sphere_deck(args.out, tag)
        dofs = 2 * int(open(deck).read().split("CONTROL")[1].split("\n")[2].split()[0])
        run_paths(exe, f"sphere_{tag}", dofs, {"ON": deck, "OFF": deck, "AUTO": deck}, [q for q in args.paths if
                  q.upper().endswith(":ON")], args.out, args.timeout, rows)
    if rows:
        write_csv(os.path.join(args.out, "scaling.csv"), rows,
                  ["size", "dofs", "path", "rc", "solutions", "cpu_s", "first_cpu_s", "peak_mb", "max_rel_diff",
                   "pairs", "sol_per_inc", "tied_cpu_s", "ratio_tied"],
                  args.append)
    if linear:
        write_csv(os.path.join(args.out, "linear.csv"), linear, ["size", "dofs"] + LINEAR_FIELDS, args.append)
    return 0 if all(r["rc"] == 0 for r in rows) and (linear or args.no_linear or args.generate_only) else 1


def write_csv(path, rows, fields, append):
    new = not (append and os.path.exists(path))
    with open(path, "w" if new else "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        if new:
            w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")


def slope(x, y):
    """Least-squares slope of log y against log x."""
    x, y = np.log(np.asarray(x, float)), np.log(np.asarray(y, float))
    return float(np.polyfit(x, y, 1)[0]) if len(x) >= 2 else float("nan")


def orderings_table(lrows):
    """Analysis, ordering, factorization and Schur set-up per MUMPS ordering, when several were run."""
    by = {}
    for r in lrows:
        if r.get("ordering"):
            by.setdefault(r["ordering"], {})[r["size"]] = r
    if len(by) < 2:
        return
    print()
    print("| DOFs | ordering | analysis [s] | of which METIS [s] | factorize [s] | factor entries "
          "| Schur set-up [s] | of which analysis [s] | of which METIS [s] | factor entries (Schur) |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for size in SIZES:
        for o in sorted(by):
            r = by[o].get(size)
            if r is None:
                continue
            print(f"| {int(r['dofs']):,} | {o} | {float(r['analyse_s']):.3f} | {float(r['ordering_s']):.3f} | "
                  f"{float(r['factorize_s']):.3f} | {int(r['nnz_factor']):,} | {float(r['schur_s']):.3f} | "
                  f"{float(r['schur_analyse_s']):.3f} | {float(r['schur_ordering_s']):.3f} | "
                  f"{int(r['nnz_factor_schur']):,} |")
    print()
    print("Fitted exponents per ordering (least squares of log t against log DOFs):")
    for o in sorted(by):
        sz = [s for s in SIZES if s in by[o]]
        d = [int(by[o][s]["dofs"]) for s in sz]

        def f(key, sz=sz, o=o):
            return [float(by[o][s][key]) for s in sz]
        an_fa = [a + b for a, b in zip(f("analyse_s"), f("factorize_s"))]
        sc_fa = [a / b for a, b in zip(f("schur_s"), f("factorize_s"))]
        print(f"  {o}: factorization {slope(d, f('factorize_s')):.2f}, analysis + factorization "
              f"{slope(d, an_fa):.2f}, Schur set-up {slope(d, f('schur_s')):.2f}, "
              f"analysis {slope(d, f('analyse_s')):.2f}; "
              f"Schur set-up / factorization " + ", ".join(f"{x:.2f}" for x in sc_fa))


def pairs_table(runs):
    """The n_c axis: every run with a tied run beside it, as a ratio to that run (--pairs, --tied)."""
    rows = [r for r in runs if r.get("ratio_tied")]
    if not rows:
        return
    print("| pairs | contact equations (4 a pair, 2 held on x = 0) | DOFs | path | rc | solutions | per increment "
          "| total CPU [s] | tied run [s] | total / tied run | peak [MB] | max |du|/|u| |")
    print("|---:|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        pairs = int(r["pairs"])
        diff = f"{float(r['max_rel_diff']):.1e}" if r.get("max_rel_diff") else "-"
        print(f"| {pairs:,} | {4 * pairs - 2:,} | {int(r['dofs']):,} | {r['path']} | {r['rc']} "
              f"| {r.get('solutions') or '-'} | {r.get('sol_per_inc') or '-'} | {float(r['cpu_s']):.2f} "
              f"| {float(r['tied_cpu_s']):.2f} | {float(r['ratio_tied']):.1f} | {float(r['peak_mb']):.0f} | {diff} |")
    print()


def pairs_plot(runs, plot):
    """Total / tied run against the contact equations, one line per path and mesh size (the n_c axis)."""
    rows = [r for r in runs if r.get("ratio_tied") and r["rc"] == "0"]
    if not rows:
        return
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, ax = plt.subplots(figsize=(7, 4.8))
    series = {}
    for r in rows:
        size = r["size"].split("_p")[0]
        series.setdefault((size, r["path"]), []).append((4 * int(r["pairs"]) - 2, float(r["ratio_tied"])))
    for (size, path), pts in sorted(series.items()):
        pts.sort()
        ax.loglog([q[0] for q in pts], [q[1] for q in pts], "-o", label=f"{path}, {size} DOFs")
    ax.set_xlabel("contact equations")
    ax.set_ylabel("total CPU / tied linear run")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.suptitle("Rough punch, 50 increments: cost against the number of contact equations")
    fig.tight_layout()
    os.makedirs(os.path.dirname(plot) or ".", exist_ok=True)
    fig.savefig(plot, dpi=110)
    print(f"wrote {plot}")


def report(out, plot):
    """The tables of docs/performance.md and the log-log plot, from OUT's CSV files."""
    runs = []
    if os.path.exists(os.path.join(out, "scaling.csv")):
        with open(os.path.join(out, "scaling.csv")) as f:
            runs = list(csv.DictReader(f))
    pairs_table(runs)
    pairs_plot(runs, os.path.splitext(plot)[0] + "_pairs.png")
    if not os.path.exists(os.path.join(out, "linear.csv")):
        return 0
    with open(os.path.join(out, "linear.csv")) as f:
        lrows = list(csv.DictReader(f))
    # the main tables: the default ordering's figures (files of earlier runs have no ordering column)
    lin = {r["size"]: r for r in lrows if r.get("ordering") in (None, "", DEFAULT_ORDERING)}
    sizes = [s for s in SIZES if s in lin]
    print("| DOFs | one linear solve [s] (factorize + solve) | back-substitution [s] | Schur set-up [s] "
          "| Schur set-up / factorize | Schur set-up / (analysis + factorize) | dense Cholesky n_c [s] "
          "| in the springs' coordinates [s] | condense + expand [s] |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for s in sizes:
        r = lin[s]
        one = float(r["factorize_s"]) + float(r["solve_s"])
        print(f"| {int(r['dofs']):,} | {one:.3f} | {float(r['solve_s']):.4f} | {float(r['schur_s']):.3f} | "
              f"{float(r['schur_s']) / float(r['factorize_s']):.2f} | "
              f"{float(r['schur_s']) / (float(r['analyse_s']) + float(r['factorize_s'])):.2f} | "
              f"{float(r['dense_factorize_s']):.4f} | {float(r['proj_factorize_s']):.4f} | "
              f"{float(r['condense_s']) + float(r['expand_s']):.4f} |")
    print()
    print("| DOFs | path | solutions | total CPU [s] | total / one solve | set-up + 1st increment [s] "
          "| later increment [s] | later increment / back-substitution | peak [MB] |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    series = {}
    spheres = [r for r in runs if r["size"].startswith("sphere_")]
    for r in runs:
        if r["size"] not in lin or r["rc"] != "0":
            continue
        L = lin[r["size"]]
        one = float(L["factorize_s"]) + float(L["solve_s"])
        tot = float(r["cpu_s"])
        first = float(r["first_cpu_s"]) if r.get("first_cpu_s") else float("nan")
        later = (tot - first) / 49.0
        print(f"| {int(r['dofs']):,} | {r['path']} | {r['solutions']} | {tot:.2f} | {tot / one:.1f} | {first:.2f} | "
              f"{later:.3f} | {later / float(L['solve_s']):.1f} | {float(r['peak_mb']):.0f} |")
        series.setdefault(r["path"], []).append((int(r["dofs"]), tot, first, later, float(r["peak_mb"]), one))
    if spheres:
        print()
        print("| sphere | DOFs | path | solutions | total CPU [s] | peak [MB] | max |du|/|u| |")
        print("|---|---:|---|---:|---:|---:|---:|")
        for r in spheres:
            print(f"| {r['size']} | {int(r['dofs']):,} | {r['path']} | {r['solutions']} | {float(r['cpu_s']):.2f} | "
                  f"{float(r['peak_mb']):.0f} | {float(r['max_rel_diff'] or 0):.1e} |")
    print()
    dofs = [int(lin[s]["dofs"]) for s in sizes]
    print("Fitted exponents (least squares of log t against log DOFs):")
    print(f"  factorization: {slope(dofs, [float(lin[s]['factorize_s']) for s in sizes]):.2f}, "
          f"Schur set-up: {slope(dofs, [float(lin[s]['schur_s']) for s in sizes]):.2f}, "
          f"back-substitution: {slope(dofs, [float(lin[s]['solve_s']) for s in sizes]):.2f}")
    for path, pts in series.items():
        pts = [q for q in pts if q[0] >= 1e4]
        if len(pts) >= 2:
            d = [q[0] for q in pts]
            print(f"  {path}: total {slope(d, [q[1] for q in pts]):.2f}, set-up + 1st increment "
                  f"{slope(d, [q[2] for q in pts]):.2f}, later increment {slope(d, [q[3] for q in pts]):.2f}, "
                  f"peak memory {slope(d, [q[4] for q in pts]):.2f}")
    orderings_table(lrows)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return 0
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.8))
    ax[0].loglog(dofs, [float(lin[s]["factorize_s"]) + float(lin[s]["solve_s"]) for s in sizes], "k--o",
                 label="one linear solve (MUMPS)")
    ax[0].loglog(dofs, [float(lin[s]["solve_s"]) for s in sizes], "k:o", label="one back-substitution")
    for path, pts in sorted(series.items()):
        d = [q[0] for q in pts]
        ax[0].loglog(d, [q[1] for q in pts], "-o", label=f"{path}: total")
        if path == "mumps:on":
            ax[0].loglog(d, [q[2] for q in pts], "-s", label=f"{path}: set-up + 1st increment")
            ax[0].loglog(d, [q[3] for q in pts], "-^", label=f"{path}: later increment")
        ax[1].loglog(d, [q[4] for q in pts], "-o", label=path)
    ax[0].set_xlabel("DOFs")
    ax[0].set_ylabel("CPU time [s]")
    ax[0].legend(fontsize=7)
    ax[0].grid(True, which="both", alpha=0.3)
    ax[1].set_xlabel("DOFs")
    ax[1].set_ylabel("peak resident memory [MB]")
    ax[1].legend(fontsize=7)
    ax[1].grid(True, which="both", alpha=0.3)
    fig.suptitle("Rough punch on a foundation, 1 202 contact equations, 50 increments (CPU seconds, one core)")
    fig.tight_layout()
    os.makedirs(os.path.dirname(plot), exist_ok=True)
    fig.savefig(plot, dpi=110)
    print(f"wrote {plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
