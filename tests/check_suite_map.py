#!/usr/bin/env python3
"""The module-suite map: every module of src/ with logic has its unit suite at the path a newcomer
would look for it, tests/unit/<layer>/test_<module>.pf, or is named below with a reason.

A module is src/<layer>/<module>.f90 (or .F90) holding `module <module>`; a submodule file
(`submodule (<module>) <name>` in <name>.f90) is tested through its module's suite, which must
exist; src/main.f90 is the program, not a module, and is left out. A module *has logic* when it defines at least one
procedure body: a `subroutine` or `function` statement outside an `interface ... end interface`
block. So modules of kinds and parameters (kinds, version), of type declarations without
type-bound procedures (records), and of interface blocks only (bindings to C or Fortran libraries
declared with `interface`) need no suite; a module with a single procedure does.

The check fails when
  * a module with logic has no suite and no exemption;
  * an exemption names a module that has its suite now, no logic, or does not exist (stale);
  * a suite in tests/unit/<layer>/ is named after no module of src/<layer>/ (misplaced or
    misnamed), unless SUITE_OF below maps a module to it.

Standard library only. Usage: python3 tests/check_suite_map.py [--root <repository root>]
[--list] (--list prints the whole map)."""
import argparse
import os
import re
import sys

# A module whose suite has another name than test_<module>.pf: module -> suite file name.
SUITE_OF = {
    # the METIS ordering is reached through MUMPS's ICNTL(7), and the suite is named test_mumps_*
    # so that tests/CMakeLists.txt leaves it out of builds without MUMPS
    "metis_ordering": "test_mumps_metis_ordering.pf",
}

# Modules with logic and no suite of their own: module -> reason. "TODO: suite missing" marks the
# ones that should have one; the others are covered where the reason says.
EXEMPT = {
    # core
    "errors": "covered by test_deck_lexer (printable, the error list and its records) and by "
              "every suite that checks an error code, line or status (test_deck_reader, "
              "test_gmsh_reader, test_solver_factory ...)",
    # assembly
    "body_fields": "covered by test_error_estimator, which builds the fields it estimates from",
    "error_estimate": "covered by test_error_estimator and tests/validation "
                      "(test_validation_error_estimate)",
    # solvers
    "linear_solver": "covered by test_skyline_solver, test_dense_solver, test_umfpack_solver and "
                     "test_mumps_solver: the abstract solver and the checks the solvers share",
    "full_system": "covered by test_contact_system (one of the contact systems it compares)",
    "condensed_system": "covered by test_contact_system (one of the contact systems it compares)",
    "contact_dense": "covered by test_contact_system (the dense contact block it solves)",
    "contact_system_factory": "covered by test_contact_system, which makes its systems through it",
    "kept_factor_system": "covered by test_contact_system (test_kept_factor_iterates, "
                          "test_kept_factor_inactive_below_limit, and the factory's full system)",
    "heap_policy": "one call of glibc's mallopt: its effect is system CPU time, measured by the "
                   "scaling benchmark (docs/performance.md), not by a unit test",
    # driver
    "equation_numbering": "covered by test_renumber, which numbers the equations through it",
    "model_input": "covered by test_incremental and the validation suites, which read their "
                   "decks through it",
}

PROC_RE = re.compile(
    r"^\s*(?:(?:pure|elemental|recursive|impure|non_recursive|module)\s+)*"
    r"(?:(?:integer|real|logical|character|complex|double\s+precision|type|class)\b[^!]*?\s+)?"
    r"(subroutine|function)\s+(\w+)", re.I)
INTERFACE_START = re.compile(r"^\s*(?:abstract\s+)?interface\b", re.I)
INTERFACE_END = re.compile(r"^\s*end\s+interface\b", re.I)
MODULE_RE = re.compile(r"^\s*module\s+(\w+)\s*$", re.I)
# `submodule (ancestor[:parent]) name`: its procedures are the ancestor module's, tested by its suite
SUBMODULE_RE = re.compile(r"^\s*submodule\s*\(\s*(\w+)\s*(?::\s*\w+\s*)?\)\s*(\w+)\s*$", re.I)


def strip_comment(line):
    """The line without its `!` comment (a `!` inside a string literal is rare enough in
    declarations to be ignored: at worst the rest of that line is not read)."""
    return line.split("!", 1)[0]


def has_logic(path):
    """True when the file defines a procedure body outside interface blocks."""
    depth = 0
    with open(path, errors="replace") as f:
        for raw in f:
            code = strip_comment(raw)
            if INTERFACE_END.match(code):
                depth = max(depth - 1, 0)
                continue
            if INTERFACE_START.match(code):
                depth += 1
                continue
            if depth == 0 and PROC_RE.match(code) and not re.match(r"^\s*end\b", code, re.I):
                return True
    return False


def submodules(root):
    """(layer, submodule, ancestor, path) of every submodule file src/<layer>/<submodule>.f90."""
    out = []
    src = os.path.join(root, "src")
    for layer in sorted(os.listdir(src)):
        ldir = os.path.join(src, layer)
        if not os.path.isdir(ldir):
            continue
        for name in sorted(os.listdir(ldir)):
            stem, ext = os.path.splitext(name)
            if ext.lower() != ".f90":
                continue
            path = os.path.join(ldir, name)
            with open(path, errors="replace") as f:
                for m in map(SUBMODULE_RE.match, f):
                    if m and m.group(2).lower() == stem.lower():
                        out.append((layer, stem.lower(), m.group(1).lower(), path))
                        break
    return out


def modules(root):
    """(layer, module, path) of every module under src/<layer>/."""
    out = []
    src = os.path.join(root, "src")
    for layer in sorted(os.listdir(src)):
        ldir = os.path.join(src, layer)
        if not os.path.isdir(ldir):
            continue
        for name in sorted(os.listdir(ldir)):
            stem, ext = os.path.splitext(name)
            if ext.lower() != ".f90":
                continue
            path = os.path.join(ldir, name)
            with open(path, errors="replace") as f:
                declared = [m.group(1).lower() for m in map(MODULE_RE.match, f) if m]
            declared = [d for d in declared if d != "procedure"]
            if stem.lower() not in declared:
                continue
            out.append((layer, stem.lower(), path))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--list", action="store_true", help="print the whole map")
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    unit = os.path.join(root, "tests", "unit")

    problems = []
    mods = modules(root)
    known = {m for _, m, _ in mods}
    expected_suites = {}                 # (layer, suite file) -> module
    n_logic = n_suite = n_exempt = n_todo = 0
    for layer, mod, path in mods:
        suite = SUITE_OF.get(mod, f"test_{mod}.pf")
        expected_suites[(layer, suite)] = mod
        rel_suite = f"tests/unit/{layer}/{suite}"
        exists = os.path.isfile(os.path.join(unit, layer, suite))
        logic = has_logic(path)
        if logic:
            n_logic += 1
        if exists:
            n_suite += 1
            state = rel_suite
            if mod in EXEMPT:
                problems.append(f"{mod}: {rel_suite} exists; remove its exemption")
        elif mod in EXEMPT:
            if not logic:
                problems.append(f"{mod}: exempted but has no logic; remove its exemption")
            n_exempt += 1
            n_todo += EXEMPT[mod].startswith("TODO")
            state = "exempt: " + EXEMPT[mod]
        elif logic:
            problems.append(f"src/{layer}/{os.path.basename(path)}: module {mod} has logic and no "
                            f"suite: add {rel_suite} or an exemption with its reason in "
                            "tests/check_suite_map.py")
            state = "MISSING"
        else:
            state = "no logic"
        if args.list:
            print(f"src/{layer}/{os.path.basename(path):28s} {state}")
    # a submodule is tested through its ancestor module's suite: that suite must exist
    for layer, sub, anc, path in submodules(root):
        where = [(lay, p) for lay, m, p in mods if m == anc]
        if not where:
            problems.append(f"src/{layer}/{os.path.basename(path)}: submodule {sub} of {anc}, "
                            "which is no module of src/<layer>/")
            continue
        alay = where[0][0]
        suite = SUITE_OF.get(anc, f"test_{anc}.pf")
        if not os.path.isfile(os.path.join(unit, alay, suite)):
            problems.append(f"src/{layer}/{os.path.basename(path)}: submodule {sub} has logic and "
                            f"its module {anc} has no suite tests/unit/{alay}/{suite}")
        elif args.list:
            print(f"src/{layer}/{os.path.basename(path):28s} submodule: tests/unit/{alay}/{suite}")
    for mod in sorted(set(EXEMPT) - known):
        problems.append(f"{mod}: exempted but no such module in src/<layer>/; remove its exemption")
    for mod in sorted(set(SUITE_OF) - known):
        problems.append(f"{mod}: SUITE_OF names no module of src/<layer>/")

    # every suite under tests/unit/<layer>/ belongs to a module of that layer
    for layer in sorted(os.listdir(unit)):
        ldir = os.path.join(unit, layer)
        if not os.path.isdir(ldir):
            continue
        for name in sorted(os.listdir(ldir)):
            if name.endswith(".pf") and (layer, name) not in expected_suites:
                problems.append(f"tests/unit/{layer}/{name}: no module src/{layer}/"
                                f"{name[5:-3] if name.startswith('test_') else name}.f90")

    for p in problems:
        print("suite map:", p)
    print(f"modules {len(mods)}, with logic {n_logic}; suites {n_suite}; exempted {n_exempt} "
          f"(of which 'TODO: suite missing' {n_todo}) -> {'FAIL' if problems else 'PASS'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
