#!/usr/bin/env python3
"""The result file of a run that an output fault ended (run_output_faults.sh).

    check_output_faults.py RESULT.h5 [--failed]

A file that cannot be opened at all passes (a disk that filled while HDF5
wrote its first blocks leaves nothing readable; the exit code and the message
are checked by the caller).  A file that can be opened must count as
increments_completed exactly the increment groups that are complete and
readable (every field of results-format.md), and no group that is not must be
marked converged.  With --failed the status must also say that the run failed.
Exit 0 when that holds, 1 otherwise.
"""
import sys

from k2d.results import audit


def main():
    path = sys.argv[1]
    try:
        status, completed, groups = audit(path)
    except Exception as e:   # noqa: BLE001 -- any failure to open is "nothing readable"
        print(f"{path}: cannot be opened ({str(e)[:80]}): nothing to check")
        return 0
    readable = sum(1 for _, ok, _ in groups if ok)
    marked_broken = [name for name, ok, conv in groups if not ok and conv is not None]
    ok = True
    if completed != readable:
        print(f"{path}: increments_completed = {completed}, but {readable} groups are complete and readable")
        ok = False
    if marked_broken:
        print(f"{path}: unreadable groups marked converged: {marked_broken}")
        ok = False
    if "--failed" in sys.argv and not status.startswith("failed"):
        print(f"{path}: status {status!r} does not say that the run failed")
        ok = False
    print(f"{path}: status {status[:70]!r}, {completed} completed, {len(groups)} groups, {readable} readable")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
