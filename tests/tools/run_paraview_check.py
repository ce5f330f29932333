#!/usr/bin/python3
"""ctest driver of the ParaView check: solve a deck, then open its XDMF sidecar
in pvpython (tests/tools/check_paraview.py).

    run_paraview_check.py KONTAKT2D DECK WORKDIR

Exit code 77 (ctest SKIP_RETURN_CODE) with a message when pvpython (Debian's
paraview package) is not installed; otherwise the check's exit code.
"""
import os
import shutil
import subprocess
import sys


def main():
    exe, deck, work = sys.argv[1:4]
    pvpython = shutil.which("pvpython")
    if pvpython is None:
        print("SKIPPED: pvpython not found (install Debian's paraview package to run the ParaView check)")
        return 77
    os.makedirs(work, exist_ok=True)
    name = os.path.splitext(os.path.basename(deck))[0]
    h5 = os.path.join(work, "paraview_" + name + ".h5")
    for ext in (".h5", ".xdmf"):
        if os.path.exists(h5[:-3] + ext):
            os.remove(h5[:-3] + ext)
    run = subprocess.run([exe, deck, "-q", "-o", h5, "-l", h5[:-3] + ".lis"], capture_output=True, text=True)
    # exit code 4 (completed with doubts: the paper's explicit scheme off its law) keeps every
    # increment in the file, which is all the check needs
    if run.returncode not in (0, 4):
        print(f"kontakt2d {deck}: exit code {run.returncode}\n{run.stdout}\n{run.stderr}")
        return 1
    check = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_paraview.py")
    out = subprocess.run([pvpython, check, h5[:-3] + ".xdmf"], capture_output=True, text=True)
    # pvpython's own chatter (VTK warnings) goes to stderr; show it only when the check fails
    print(out.stdout)
    if out.returncode != 0:
        print(out.stderr[-4000:])
    return out.returncode


if __name__ == "__main__":
    sys.exit(main())
