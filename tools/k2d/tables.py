"""Tables of the tools: CSV files and Markdown tables, one way of writing numbers.

    from k2d.tables import write_csv, write_dict_csv, read_csv, markdown_table
    write_csv("t.csv", ["x", "p"], [[0.0, 1.25], [1.0, 1.5]])      # floats as %.6g
    write_dict_csv("s.csv", FIELDS, rows)                           # dict rows, unknown keys ignored
    rows = read_csv("s.csv")                                        # list of dicts of strings
    text = markdown_table("title", header, rows, fmt={"p": "%.4f"}) # "### title" and the table
"""
import csv
import math

__all__ = ["write_csv", "write_dict_csv", "read_csv", "markdown_table"]


def _cell(v, fmt):
    return (fmt % v) if fmt and isinstance(v, float) else v


def write_csv(path, header, rows, fmt="%.6g"):
    """A CSV file of a header and rows of values; floats written with `fmt` (None: as Python
    writes them, all digits)."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow([_cell(v, fmt) for v in r])


def write_dict_csv(path, fieldnames, rows, fmt="%.6g"):
    """A CSV file of dict rows in the column order `fieldnames` (other keys are left out);
    floats written with `fmt`."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fieldnames, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: _cell(v, fmt) for k, v in r.items()})


def read_csv(path):
    """The rows of a CSV file with a header, as dicts of strings."""
    with open(path) as f:
        return list(csv.DictReader(f))


def markdown_table(title, header, rows, fmt=None):
    """A Markdown table under a `### title` line, ending in a newline.  Floats are written
    with fmt[column] (default %.3f), NaN as a dash; `|` in texts is escaped."""
    fmt = fmt or {}

    def esc(t):
        return str(t).replace("|", "\\|")
    lines = ["### " + title, "", "| " + " | ".join(esc(h) for h in header) + " |",
             "|" + "|".join("---" for _ in header) + "|"]
    for r in rows:
        cells = []
        for h, v in zip(header, r):
            if isinstance(v, float):
                cells.append("—" if math.isnan(v) else (fmt.get(h, "%.3f") % v))
            else:
                cells.append(esc(v))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
