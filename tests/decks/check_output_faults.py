#!/usr/bin/env python3
"""The result file of a run that an output fault ended (run_output_faults.sh).

    check_output_faults.py RESULT.h5 [--failed] [--exit N]

A file that exists must open and must count as increments_completed exactly
the increment groups that are complete and readable (every field of
results-format.md), and no group that is not must be marked converged.  With
--failed, or --exit 3, the status must say that the run failed and where: at
set-up, or at an increment after the last completed one (or at the last
completed one, or after the last one, when what failed was the listing or the
XDMF file).  With --exit 3 a
missing file passes (the disk had no room even for the run's reserve: the
caller checks the message); without it a missing file fails.  No reserve file
(RESULT.h5.reserve) may be left.  Exit 0 when that holds, 1 otherwise.
"""
import os
import re
import sys

from k2d.results import audit


def main():
    path = sys.argv[1]
    failed = "--failed" in sys.argv
    code = sys.argv[sys.argv.index("--exit") + 1] if "--exit" in sys.argv else None
    failed = failed or code == "3"
    ok = True
    if os.path.exists(path + ".reserve"):
        print(f"{path}.reserve: left behind")
        ok = False
    if not os.path.exists(path):
        if code == "3":
            print(f"{path}: no result file (exit 3)")
            return 0 if ok else 1
        print(f"{path}: missing")
        return 1
    try:
        status, completed, groups = audit(path)
    except Exception as e:   # noqa: BLE001 -- any failure to open is a broken file
        print(f"{path}: cannot be opened ({str(e)[:80]})")
        return 1
    readable = sum(1 for _, good, _ in groups if good)
    marked_broken = [name for name, good, conv in groups if not good and conv is not None]
    if completed != readable:
        print(f"{path}: increments_completed = {completed}, but {readable} groups are complete and readable")
        ok = False
    if marked_broken:
        print(f"{path}: unreadable groups marked converged: {marked_broken}")
        ok = False
    if failed:
        m = re.match(r"failed (?:at (set-up|increment (\d+))|after the last increment \((\d+)\)): \S", status)
        last = max((int(name) for name, good, _ in groups if good), default=0)
        # the listing and the XDMF file are written after the increment's group:
        # when they fail, the group of the increment named is complete
        side_file = re.search(r"cannot write the (listing|XDMF)", status) is not None
        if not m:
            print(f"{path}: status {status!r} does not say where the run failed")
            ok = False
        elif m.group(2) is not None and int(m.group(2)) < last + (0 if side_file else 1):
            print(f"{path}: status {status!r} names an increment not after the last complete one ({last})")
            ok = False
        elif m.group(3) is not None and (int(m.group(3)) != completed or not side_file):
            print(f"{path}: status {status!r}: not the listing or XDMF file after increment {completed}")
            ok = False
        elif m.group(1) == "set-up" and groups:
            print(f"{path}: status {status!r} says set-up, but the file has increment groups")
            ok = False
    elif code in ("0", "4") and not status.startswith(("completed", "doubtful")):
        print(f"{path}: exit {code} with status {status!r}")
        ok = False
    print(f"{path}: status {status[:70]!r}, {completed} completed, {len(groups)} groups, {readable} readable")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
