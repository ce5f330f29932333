#!/usr/bin/env python3
"""Every citation of the specification resolves, and docs/ is indexed.

The sources cite docs/specification.md as "SPEC §2.1", "SPEC 6.1", "SPEC section 7", "SPEC D8",
"SPEC V6", "SPEC §7 (V6, V8)", "SPEC §6.1, D11", "SPEC §2.1-2.3", "SPEC V1-V4". Each cited
section, decision (Dn) and reference case (Vn) must be a heading of docs/specification.md; the
section references inside the specification itself ("§4.2") must be headings too. The relative
links of docs/specification.md, docs/README.md and docs/house-style.md must name an existing file and, where they
give one, an existing heading; every document in docs/ must be listed in docs/README.md.

Run from anywhere: python3 tests/tools/test_spec_citations.py (unittest)."""

import os
import re
import sys
import unittest

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SPEC = os.path.join(ROOT, "docs", "specification.md")
INDEX = os.path.join(ROOT, "docs", "README.md")
HOUSE = os.path.join(ROOT, "docs", "house-style.md")
SEARCHED = ("src", "tools", "tests", "docs")
SUFFIXES = (".f90", ".F90", ".pf", ".py", ".md", ".txt", ".dat", ".check", ".cmake", ".expect",
            ".geo", ".sh", ".in")

# one cited item: a section (optionally with §), a decision Dn or a reference case Vn
_ITEM = r"(?:§\s*)?\d+(?:\.\d+)*(?![\w.]*\d)|[DV]\d+\b"
# items after the first: separated by a comma, a slash, "and", a dash (a range) or an opening
# parenthesis; a D or V item may also follow after a space ("SPEC §7 V1-V4")
_MORE = r"(?:\s*(?:,|/|\band\b|-|–|\()\s*(?:" + _ITEM + r")|\s+[DV]\d+\b)"
CITATION = re.compile(r"\bSPEC(?:'s)?\s*\(?\s*(?:section\s+)?((?:" + _ITEM + r")" + _MORE + r"*)")
TOKEN = re.compile(r"§?\s*(\d+(?:\.\d+)*|[DV]\d+)")
RANGE = re.compile(r"([DV]?)(\d+(?:\.\d+)*)\s*[-–]\s*§?\s*([DV]?)(\d+(?:\.\d+)*)")


def headings(text):
    """The labels of the specification's headings: '2', '2.1', 'D8', 'V6', '7.0'."""
    labels = set()
    for line in text.splitlines():
        m = re.match(r"#{1,6}\s+(?:§\s*)?(\d+(?:\.\d+)*|[DV]\d+)\b", line)
        if m:
            labels.add(m.group(1))
    return labels


def cited(text):
    """The labels one text cites, as (label, offset) pairs; a range cites both its ends."""
    out = []
    for m in CITATION.finditer(text):
        group = m.group(1)
        for r in RANGE.finditer(group):
            if r.group(1) != r.group(3):
                continue
            out.append((r.group(1) + r.group(2), m.start()))
            out.append((r.group(3) + r.group(4), m.start()))
        for t in TOKEN.finditer(RANGE.sub(" ", group)):
            out.append((t.group(1), m.start()))
    return out


def unresolved(text, labels):
    """The citations of a text that name no heading: [(label, line number)]."""
    bad = []
    for label, offset in cited(text):
        if label not in labels:
            bad.append((label, text.count("\n", 0, offset) + 1))
    return bad


def source_files():
    for top in SEARCHED:
        for folder, dirs, files in os.walk(os.path.join(ROOT, top)):
            dirs[:] = [d for d in dirs if not d.startswith(".") and d != "__pycache__"]
            for name in files:
                if os.path.join(folder, name) == os.path.abspath(__file__):
                    continue                            # its own examples of bad citations
                if name.endswith(SUFFIXES) or name == "CMakeLists.txt":
                    yield os.path.join(folder, name)


def slug(heading):
    """The anchor a Markdown renderer (GitHub's rule) gives a heading."""
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r"```.*?```", "", text, flags=re.S)   # '#' lines of code blocks are no headings
    return {slug(m.group(1)) for m in re.finditer(r"^#{1,6}\s+(.*?)\s*$", text, re.M)}


def broken_links(path):
    """Relative links of a Markdown file whose file or heading does not exist."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    bad = []
    for m in re.finditer(r"\]\(([^)\s]+)\)", text):
        target = m.group(1)
        if re.match(r"[a-z]+:", target):
            continue
        file_part, _, anchor = target.partition("#")
        dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
        if not os.path.exists(dest):
            bad.append(target)
        elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
            bad.append(target)
    return bad


class TestSpecCitations(unittest.TestCase):
    def setUp(self):
        with open(SPEC, encoding="utf-8") as f:
            self.spec = f.read()
        self.labels = headings(self.spec)

    def test_parser_finds_each_form(self):
        text = ("SPEC §2.1 and SPEC 6.1, D11; SPEC section 7; SPEC (§6, §7); SPEC §7 (V6, V8)\n"
                "SPEC §7, V1-V4; SPEC V15; SPEC's §4.2; SPEC §2.1-2.3; SPEC eq. (2.1a); SPEC_TABLE")
        got = sorted({label for label, _ in cited(text)})
        self.assertEqual(got, sorted(["2.1", "2.3", "4.2", "6", "6.1", "7", "D11", "V1", "V4",
                                      "V6", "V8", "V15"]))

    def test_fake_citation_fails(self):
        """A section, decision or case the specification lacks is reported, with its line."""
        text = "ok: SPEC §2.1\nbad: SPEC §9.9, D99\nbad too: SPEC V5\n"
        self.assertEqual(unresolved(text, self.labels), [("9.9", 2), ("D99", 2), ("V5", 3)])

    def test_specification_has_the_numbering(self):
        expected = (["0", "1", "2", "3", "4", "5", "6", "7", "8", "2.1", "2.2", "2.3", "2.4",
                     "3.1", "3.2", "3.3", "4.1", "4.2", "4.3", "4.4", "4.5", "6.1", "6.2", "6.3",
                     "7.0"] + ["D%d" % i for i in range(1, 12)]
                    + ["V%d" % i for i in (1, 2, 3, 4, 6, 7, 8, 10, 11, 14, 15, 16)])
        self.assertEqual(sorted(set(expected) - self.labels), [])
        self.assertIn("Global invariants", self.spec)

    def test_every_citation_resolves(self):
        bad, count = [], 0
        for path in source_files():
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            count += len(cited(text))
            for label, line in unresolved(text, self.labels):
                bad.append("%s:%d: SPEC %s" % (os.path.relpath(path, ROOT), line, label))
        # the sources cite the specification a few hundred times: a parser that found none
        # would pass vacuously
        print("%d citations of the specification checked" % count, file=sys.stderr)
        self.assertGreater(count, 200)
        self.assertEqual(bad, [], "citations without a heading in docs/specification.md")

    def test_internal_references_resolve(self):
        refs = re.findall(r"§\s*(\d+(?:\.\d+)*)", self.spec)
        self.assertGreater(len(refs), 10)
        self.assertEqual(sorted(set(refs) - self.labels), [])

    def test_links_resolve(self):
        for path in (SPEC, INDEX, HOUSE):
            self.assertEqual(broken_links(path), [], os.path.relpath(path, ROOT))

    def test_index_lists_every_document(self):
        with open(INDEX, encoding="utf-8") as f:
            index = f.read()
        docs = sorted(n for n in os.listdir(os.path.dirname(INDEX))
                      if n.endswith(".md") and n != "README.md")
        self.assertGreater(len(docs), 15)
        self.assertEqual([d for d in docs if "](%s" % d not in index], [])


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
