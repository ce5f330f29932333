"""Find (and build if needed) the kontakt2d program; run a deck.

    from k2d.build import find_or_build, run_deck, build_target
    exe = find_or_build()                      # build/kontakt2d, configured and built if needed
    rc = run_deck(exe, "deck.dat", "out/deck.h5", quiet=True)
    build_target("bench_solvers", "build")     # any CMake target; returns the build directory
"""
import os
import subprocess

__all__ = ["ROOT", "build_target", "find_or_build", "run_deck"]

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def build_target(target, build=None, jobs=None):
    """Build the CMake target `target` in the build directory `build` (default build/ of this
    checkout), configuring a Release build there first if there is none; returns the build
    directory."""
    build = build or os.path.join(ROOT, "build")
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release"], check=True,
                       stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build, "-j", str(jobs or os.cpu_count() or 2), "--target", target],
                   check=True, stdout=subprocess.DEVNULL)
    return build


def find_or_build(exe=None, build=None):
    """The kontakt2d program: `exe` if given, else the environment's K2D_EXECUTABLE,
    else build/kontakt2d of this checkout (a Release build configured and built if needed)."""
    if exe:
        return exe
    if os.environ.get("K2D_EXECUTABLE"):
        return os.environ["K2D_EXECUTABLE"]
    return os.path.join(build_target("kontakt2d", build), "kontakt2d")


def run_deck(exe, deck, h5, listing=None, quiet=True, extra=(), log=None, cwd=None):
    """Run one deck; returns the exit code.  `log`: a file for the terminal output
    (stdout and stderr), else it is discarded."""
    cmd = [exe, deck, "-o", h5]
    if listing:
        cmd += ["-l", listing]
    if quiet:
        cmd.append("-q")
    cmd += list(extra)
    if log:
        with open(log, "w") as f:
            return subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=cwd)
    return subprocess.call(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=cwd)
