"""The program's terminal output (a run without -q), read once for every tool.

    from k2d.terminal import read_terminal
    t = read_terminal("run.log")     # None when the file cannot be read
    t["nodes"], t["equations"], t["pairs"]      # the header (None where absent)
    t["progress"]                  # [(increment, solutions or None, seconds)], one per progress line
    t["totals"]                    # (solutions, increments) of the summary line, or None
    t["seconds"]                   # the summary's elapsed seconds, or None

The progress lines are those of src/io/listing.f90 (list_progress): with contact
`inc  load factor  max |u|  closed  slip  solves  rep  residual  time [s]`, without
`inc  load factor  max |u|  sum Rx  sum Ry  time [s]` (no solution count); the summary ends with
`N solutions in M increments, T s`.
"""
import re

__all__ = ["parse_terminal", "read_terminal", "progress_solutions", "program_seconds"]

_NUM = r"[-+0-9.Ee]+"
CONTACT_PROGRESS = re.compile(r"^\s*(\d+)\s+[-+0-9.]+\s+\S+\s+\d+\s+\d+\s+(\d+)\s+\d+\s+\S+\s+([0-9.]+)\s*$")
BODY_PROGRESS = re.compile(r"^\s*(\d+)\s+[-+0-9.]+\s+\S+\s+%s\s+%s\s+([0-9.]+)\s*$" % (_NUM, _NUM))
TOTALS = re.compile(r"^\s*(\d+) solutions in (\d+) increments(?:, ([0-9.]+) s)?")
HEADER = {"nodes": re.compile(r"\s*Nodes\s*:\s*(\d+)"), "equations": re.compile(r"\s*Equations\s*:\s*(\d+)"),
          "pairs": re.compile(r"\s*Contact\s*:\s*(\d+) pairs")}


def parse_terminal(text):
    """The figures of one run's terminal output (see the module's text)."""
    out = {"nodes": None, "equations": None, "pairs": None, "progress": [], "totals": None, "seconds": None}
    for line in text.splitlines():
        for key, rx in HEADER.items():
            m = rx.match(line)
            if m:
                out[key] = int(m.group(1))
        m = CONTACT_PROGRESS.match(line)
        if m:
            out["progress"].append((int(m.group(1)), int(m.group(2)), float(m.group(3))))
            continue
        m = BODY_PROGRESS.match(line)
        if m:
            out["progress"].append((int(m.group(1)), None, float(m.group(2))))
            continue
        m = TOTALS.match(line)
        if m:
            out["totals"] = (int(m.group(1)), int(m.group(2)))
            if m.group(3):
                out["seconds"] = float(m.group(3))
    return out


def read_terminal(path):
    """parse_terminal of a log file, or None when it cannot be read."""
    try:
        with open(path, errors="replace") as f:
            return parse_terminal(f.read())
    except OSError:
        return None


def progress_solutions(t):
    """The solutions summed over the progress lines (the result file keeps the last increment
    only); 0 without contact progress lines."""
    return sum(s for _, s, _ in t["progress"] if s is not None)


def program_seconds(t):
    """The program's own elapsed time: its summary's, else that of its last progress line, else None."""
    if t["seconds"] is not None:
        return t["seconds"]
    return t["progress"][-1][2] if t["progress"] else None
