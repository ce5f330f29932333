#!/usr/bin/env python3
"""The result file records everything the listing's closing summary says.

Usage: check_summary.py RESULTS.h5 LISTING.lis

Every line of the listing from its closing lines (doubts, failure) to its end -- the summary of
the run, the energy dissipated, the load cycles, the pretension sections -- is parsed and each
figure compared with the group /summary (and /cycles, the status) of the result file, read with
tools/k2d/results.py. A line that no rule knows fails the check: a new line of the summary needs
its figures in the result file (docs/results-format.md "Run summary").

Tolerances: the listing prints es12.4 (5 significant digits: a printed value is within half a
unit of its last digit, 5e-5 of the value) and es13.3 (5e-4) and f0.2 / f0.1 per cent (half a
unit of the last digit); the figures of /summary are the doubles those lines were printed from.
"""

import re
import sys

from k2d.results import Result

# a Fortran real as printed: also 1.7140+298 (an E edit descriptor drops the E of a
# three-digit exponent)
NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[Ee][-+]?\d+|[-+]\d{3})?"
failures = []
checked = 0


def close(name, printed, value, rel=6e-5, abs_=0.0):
    """printed (text from the listing) against value (from the result file)."""
    global checked
    checked += 1
    p = float(re.sub(r"(\d)([-+]\d{3})$", r"\1E\2", printed))
    if not abs(p - float(value)) <= rel * abs(float(value)) + abs_ + 1e-300:
        failures.append(f"{name}: listing {printed}, result file {value!r}")


def equal(name, printed, value):
    global checked
    checked += 1
    if str(printed) != str(value):
        failures.append(f"{name}: listing {printed!r}, result file {value!r}")


def need(s, key):
    if key not in s:
        failures.append(f"/summary has no {key}")
        return None
    return s[key]


def estimate_line(s, t, prefix):
    """The line ' estimated discretization error ...' against /summary's estimated_error and
    zone_* attributes (prefix "peak_": those of the largest strain energy); False if t is not
    such a line."""
    m = re.match(rf" estimated discretization error ({NUM}) % \(energy norm\)(.*)$", t)
    if not m:
        return False
    close(
        prefix + "estimated_error",
        m.group(1),
        100.0 * need(s, prefix + "estimated_error"),
        rel=0,
        abs_=0.0051,
    )
    zones = re.findall(
        rf"contact zone ({NUM}) \S+ wide resolved by (\d+) pairs?, largest pressure "
        rf"jump between neighbouring pairs ({NUM}) %|(no pair closed)",
        m.group(2),
    )
    for k, z in enumerate(zones):
        if z[3]:
            equal(f"{prefix}zone {k + 1} pairs", 0, s[prefix + "zone_pairs"][k])
            continue
        close(f"{prefix}zone {k + 1} width", z[0], s[prefix + "zone_width"][k], rel=6e-4)
        equal(f"{prefix}zone {k + 1} pairs", int(z[1]), s[prefix + "zone_pairs"][k])
        close(
            f"{prefix}zone {k + 1} jump",
            z[2],
            100.0 * s[prefix + "zone_jump"][k],
            rel=0,
            abs_=0.051,
        )
    return True


class PerInterface:
    """/summary as one interface's lines read it: the whole model's keys (peak_pressure,
    force_normal, ...) taken from the interface_* arrays at index i, the units from /summary."""

    SCALARS = (
        "pairs",
        "closed_pairs",
        "slipping_pairs",
        "peak_pair",
        "peak_pressure",
        "contact_width",
        "contact_area",
        "approach",
        "force_normal",
        "force_tangential",
    )

    def __init__(self, summary, i):
        self.summary = summary
        self.i = i

    def __contains__(self, key):
        if key == "peak_position":
            return "interface_peak_x" in self.summary
        if key in self.SCALARS:
            return "interface_" + key in self.summary
        return key in self.summary

    def __getitem__(self, key):
        if key == "peak_position":
            return [
                self.summary["interface_peak_x"][self.i],
                self.summary["interface_peak_y"][self.i],
            ]
        if key in self.SCALARS:
            return self.summary["interface_" + key][self.i]
        return self.summary[key]

    def get(self, key, default=None):
        return self[key] if key in self else default


def main(h5, lis):
    r = Result(h5)
    s = summary = r.summary
    iface = None  # the interface whose lines follow (a model with several interfaces)
    checked_ifaces = []
    if r.status.startswith("failed at set-up"):
        # no increment, no summary: the listing ends with the failure
        print(
            f"{h5}: failed at set-up, no /summary"
            if not s
            else "FAIL: /summary after a failed set-up"
        )
        return 1 if s else 0
    if not s:
        print(f"FAIL: {h5} has no /summary")
        return 1
    lines = open(lis).read().splitlines()
    start = next(
        (
            i
            for i, t in enumerate(lines)
            if t.startswith("kontakt2d: completed with doubts")
            or t.startswith("kontakt2d: increment ")
        ),
        None,
    )
    if start is None:
        start = next((i for i, t in enumerate(lines) if "SUMMARY OF THE RUN" in t), None)
        if start is None:
            print("FAIL: no summary in the listing")
            return 1
        start -= 2
    stage = 0
    details = []
    cycles = r.cycles
    ncyc = 0
    in_details = False
    for t in lines[start:]:
        m = None
        if t.strip() == "" or set(t.strip()) <= set("=-"):
            in_details = False
            continue
        if t.startswith("kontakt2d: completed with doubts: "):
            equal("doubts", t[len("kontakt2d: completed with doubts: ") :], need(s, "doubts"))
            equal("status", "doubtful: " + s.get("doubts", ""), r.status)
            in_details = True
            continue
        if t.startswith("  (frozen states, law drift"):
            in_details = False
            continue
        m = re.match(r"  \.\.\. and (\d+) more doubtful increment\(s\)$", t)
        if m and in_details:
            equal(
                "doubtful_increments",
                len(details) + int(m.group(1)),
                need(s, "doubtful_increments"),
            )
            continue
        if in_details and t.startswith("  "):
            details.append(t[2:])
            continue
        m = re.match(r"kontakt2d: increment (\d+) failed: (.*)$", t)
        if m:
            equal("status", f"failed at increment {m.group(1)}: {m.group(2)}", r.status)
            equal("increments", int(m.group(1)) - 1, s["increments"])
            continue
        if re.match(r"kontakt2d: \d+ (completed )?increment", t):
            continue  # where the finished increments are (the file itself)
        m = re.match(
            r" SUMMARY OF THE RUN \(load stages follow the factor of load case (\d+)\)$", t
        )
        if m:
            equal("stage_load_case", int(m.group(1)), s["stage_load_case"])
            continue
        if t.startswith("  stage   increments"):
            continue
        m = re.match(
            rf"\s+(\d+)\s+(\d+) -\s+(\d+)\s+({NUM}) ->\s*({NUM})\s+(loading|unloading|holding)"
            rf"\s+(\d+)\s+({NUM})$",
            t,
        )
        if m:
            k = int(m.group(1)) - 1
            stage = max(stage, k + 1)
            equal(f"stage {k + 1} first", int(m.group(2)), s["stage_first_increment"][k])
            equal(f"stage {k + 1} last", int(m.group(3)), s["stage_last_increment"][k])
            close(f"stage {k + 1} from", m.group(4), s["stage_load_from"][k])
            close(f"stage {k + 1} to", m.group(5), s["stage_load_to"][k])
            equal(
                f"stage {k + 1} kind",
                {"loading": 1, "unloading": -1, "holding": 0}[m.group(6)],
                s["stage_direction"][k],
            )
            equal(f"stage {k + 1} solutions", int(m.group(7)), s["stage_solutions"][k])
            close(f"stage {k + 1} drift", m.group(8), s["stage_law_drift"][k], rel=6e-4)
            equal("stages_by_deck", 1, s["stages_by_deck"])
            continue
        m = re.match(
            rf"\s+(\d+)\s+(\d+) -\s+(\d+)\s+automatic increments: stages not separated\s+(\d+)"
            rf"\s+({NUM})$",
            t,
        )
        if m:
            k = int(m.group(1)) - 1
            stage = max(stage, k + 1)
            equal("stages_by_deck", 0, s["stages_by_deck"])
            equal(f"stage {k + 1} solutions", int(m.group(4)), s["stage_solutions"][k])
            close(f"stage {k + 1} drift", m.group(5), s["stage_law_drift"][k], rel=6e-4)
            continue
        m = re.match(r" The interfaces? at the end \(increment (\d+)\):$", t)
        if m:
            equal("increments", int(m.group(1)), s["increments"])
            several = t.startswith(" The interfaces")
            equal("several interfaces", several, len(need(s, "interface_pairs")) > 1)
            iface = None
            continue
        m = re.match(r"  interface (\d+)$", t)
        if m:
            iface = int(m.group(1)) - 1  # the lines of that interface follow, indented by 4
            checked_ifaces.append(iface)
            continue
        indent = len(t) - len(t.lstrip(" "))
        if iface is not None and indent == 4:
            t = t[2:]  # an interface's line: its figures are the interface_* arrays' entries
            s = PerInterface(summary, iface)
        else:
            if indent < 4:
                iface = None
            s = summary
        m = re.match(rf"  peak pressure\s+({NUM}) (.*) at pair (\d+) \(\s*({NUM}),\s*({NUM})\)$", t)
        if m:
            close("peak_pressure", m.group(1), need(s, "peak_pressure"))
            equal("stress_unit", m.group(2), need(s, "stress_unit"))
            equal("peak_pair", int(m.group(3)), s["peak_pair"])
            close(
                "peak x",
                m.group(4),
                s["peak_position"][0],
                abs_=1e-4 * abs(float(m.group(4))) + 1e-300,
            )
            close("peak y", m.group(5), s["peak_position"][1], abs_=1e-4 * abs(float(m.group(4))))
            continue
        if t.startswith("  peak pressure        none"):
            equal("peak_pair", 0, need(s, "peak_pair"))
            continue
        m = re.match(
            rf"  contact width\s+({NUM}) (\S+) \((\d+) of (\d+) pairs closed\), "
            rf"area\s*({NUM}) \S+$",
            t,
        )
        if m:
            close("contact_width", m.group(1), need(s, "contact_width"))
            equal("length_unit", m.group(2), s["length_unit"])
            equal("closed_pairs", int(m.group(3)), s["closed_pairs"])
            equal("pairs", int(m.group(4)), s["pairs"])
            close("contact_area", m.group(5), s["contact_area"])
            continue
        m = re.match(rf"  approach\s+({NUM}) ", t)
        if m:
            close("approach", m.group(1), need(s, "approach"))
            continue
        m = re.match(rf"  total force normal\s+({NUM}), tangential\s*({NUM}) (.*)$", t)
        if m:
            close("force_normal", m.group(1), need(s, "force_normal"))
            close(
                "force_tangential",
                m.group(2),
                s["force_tangential"],
                abs_=6e-5 * abs(float(m.group(1))),
            )
            equal("force_unit", m.group(3), s["force_unit"])
            continue
        m = re.match(r"  slipping pairs\s+(\d+) of (\d+) closed$", t)
        if m:
            equal("slipping_pairs", int(m.group(1)), need(s, "slipping_pairs"))
            continue
        m = re.match(rf"  residual closure\s+({NUM}) .* of (\d+) pair\(s\)\)$", t)
        if m:
            close("residual_closure", m.group(1), need(s, "residual_closure"))
            equal("unloaded_pairs", int(m.group(2)), s["unloaded_pairs"])
            continue
        m = re.match(
            rf"  unloading law\s+(\d+) pair\(s\) .* pair (\d+), p_A\s*({NUM}) > p\*\s*({NUM}) ", t
        )
        if m:
            equal("beyond_range_pairs", int(m.group(1)), need(s, "beyond_range_pairs"))
            equal("beyond_range_pair", int(m.group(2)), need(s, "beyond_range_pair"))
            close("beyond_range_reversal_pressure", m.group(3), s["beyond_range_reversal_pressure"])
            close("beyond_range_p_star", m.group(4), s["beyond_range_p_star"])
            continue
        m = re.match(rf"  worst law drift\s+({NUM}) \(increment (\d+)\)$", t)
        if m:
            close("worst_law_drift", m.group(1), need(s, "worst_law_drift"))
            equal("worst_law_drift_increment", int(m.group(2)), s["worst_law_drift_increment"])
            continue
        m = re.match(
            rf" at the largest strain energy \(increment (\d+); the end's is ({NUM}) % of it\):"
            rf"( estimated discretization error .*)$",
            t,
        )
        if m:
            equal("peak_estimate_increment", int(m.group(1)), need(s, "peak_estimate_increment"))
            close(
                "peak_energy_ratio",
                m.group(2),
                100.0 * need(s, "peak_energy_ratio"),
                rel=0,
                abs_=0.051,
            )
            estimate_line(s, m.group(3), "peak_")
            continue
        m = re.match(r" at the end \(increment (\d+)\):( estimated discretization error .*)$", t)
        if m:
            equal("increments", int(m.group(1)), s["increments"])
            need(s, "peak_estimate_increment")  # the line only precedes the peak's
            estimate_line(s, m.group(2), "")
            continue
        if estimate_line(s, t, ""):
            continue
        m = re.match(r" (\d+) solutions in (\d+) increments, ([\d.]+) s$", t)
        if m:
            equal("solutions", int(m.group(1)), s["solutions"])
            equal("increments", int(m.group(2)), s["increments"])
            close("wall_seconds", m.group(3), s["wall_seconds"], rel=0, abs_=0.0051)
            continue
        if t.startswith(" Energy dissipated by the contact laws, cumulative"):
            continue
        m = re.match(
            rf"  interface (\d+): total\s+({NUM}), normal hysteresis\s*({NUM}), tangential "
            rf"\(friction\)\s*({NUM})$",
            t,
        )
        if m:
            k = int(m.group(1)) - 1
            close(f"dissipated_energy {k + 1}", m.group(2), need(s, "dissipated_energy")[k])
            close(f"dissipated_normal {k + 1}", m.group(3), s["dissipated_normal"][k])
            close(f"dissipated_tangential {k + 1}", m.group(4), s["dissipated_tangential"][k])
            continue
        m = re.match(r" Load cycles of the history: (\d+) ", t)
        if m:
            ncyc = int(m.group(1))
            equal("cycles", ncyc, len(cycles.get("first_increment", [])))
            continue
        if t.startswith("  cycle  increments"):
            continue
        if t.startswith("  (n/a: the interface's pairs do not move with its total force"):
            continue
        # a cycle's row; its three ratios n/a where not defined (an ideal interface, or an energy
        # beyond the loop's rectangle): 0 in the file, ratios_defined 0
        m = re.match(
            rf"\s+(\d+)\s+(\d+) -\s+(\d+)\s+(\d+)\s+({NUM})\s+({NUM})\s+({NUM})"
            rf"\s+({NUM}|n/a)\s+({NUM}|n/a)\s+({NUM}|n/a)$",
            t,
        )
        if m and ncyc:
            c, i = int(m.group(1)) - 1, int(m.group(4)) - 1
            defined = m.group(8) != "n/a"
            equal(f"cycle {c + 1} first", int(m.group(2)), cycles["first_increment"][c])
            equal(f"cycle {c + 1} last", int(m.group(3)), cycles["last_increment"][c])
            equal(
                f"interface {i + 1} ratios_defined",
                int(defined),
                int(need(cycles, "ratios_defined")[c, i]),
            )
            for g, key in zip(
                range(5, 11),
                [
                    "energy",
                    "force_amplitude",
                    "slip_amplitude",
                    "secant_stiffness",
                    "loss_factor",
                    "damping_ratio",
                ],
            ):
                a = cycles[key]
                value = a[c, i] if a.shape[0] == len(cycles["first_increment"]) else a[i, c]
                if m.group(g) == "n/a":
                    equal(f"cycle {c + 1} {key}", 0.0, float(value))
                else:
                    close(f"cycle {c + 1} {key}", m.group(g), value)
            continue
        m = re.match(
            rf' pretension section "(.*)" at increment (\d+): force\s*({NUM}), '
            rf"shortening\s*({NUM})$",
            t,
        )
        if m:
            if "pretension_force" not in s:
                failures.append("/summary has no pretension_force")
                continue
            equal("pretension_increment", int(m.group(2)), s["pretension_increment"])
            k = sum(1 for d in details if d.startswith("@pret"))
            details.append("@pret")
            close(f"pretension_force {k + 1}", m.group(3), s["pretension_force"][k], rel=6e-11)
            close(
                f"pretension_shortening {k + 1}",
                m.group(4),
                s["pretension_shortening"][k],
                rel=6e-8,
            )
            continue
        failures.append(f"a line of the summary the check does not know: {t!r}")
    if stage:
        equal("stages", stage, len(s["stage_first_increment"]))
    doubt_lines = [d for d in details if d != "@pret"]
    if doubt_lines:
        equal("doubt_details", "\n".join(doubt_lines), s.get("doubt_details", ""))
    ipairs = list(summary.get("interface_pairs", ()))
    if len(ipairs) > 1:
        # several interfaces: each one with pairs has its lines, in the order of the deck
        want = [i for i, n in enumerate(ipairs) if n > 0]
        if checked_ifaces != want:
            failures.append(f"interfaces listed {checked_ifaces}, with pairs {want}")
    if failures:
        for f in failures:
            print("FAIL:", f)
        return 1
    print(f"{h5}: {checked} figures of the listing's summary found in /summary")
    return 0 if checked > 5 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
