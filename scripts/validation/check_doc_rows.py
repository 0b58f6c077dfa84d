#!/usr/bin/env python3
"""Holds docs/validation.md to a validation run: every row of OUT/docs-rows.md (written by
scripts/validation/report.py) must be in the docs, under the same label cells, with the same
figures. Tolerance per figure: half a unit of the docs' last digit plus 0.2 % of the value (a
compiler's contraction of a multiply-add moves the last digits of an explicit run, not its
figures). A cell's first number is its figure (what follows it, "(to 0.59)", is commentary); the
last column, the wall time, is not compared.
Usage: check_doc_rows.py DOCS_MD DOCS_ROWS_MD [--at-least N]. Exit 1 when a figure moved, a row
is missing from the docs or fewer than N rows were compared."""
import re
import sys


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def number(text):
    m = re.match(r"[*]*(-?[0-9]+(?:\.[0-9]+)?)", text)
    return m.group(1) if m else None


def main(argv):
    args = list(argv)
    at_least = 1
    if "--at-least" in args:
        k = args.index("--at-least")
        at_least = int(args[k + 1])
        del args[k:k + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    doc = [cells(l) for l in open(args[0]) if l.startswith("|")]
    generated = [cells(l) for l in open(args[1]) if l.startswith("|")]
    problems, compared = [], 0
    for row in generated:
        n = next((k for k, c in enumerate(row) if number(c) is not None), len(row))  # the label cells lead
        labels = row[:n]
        matches = [d for d in doc if d[:n] == labels and len(d) == len(row)]
        name = " | ".join(labels)
        if len(matches) != 1:
            problems.append(f"{name}: {len(matches)} rows in the docs with these labels and {len(row)} cells (expected 1)")
            continue
        compared += 1
        for k in range(n, len(row) - 1):  # the last column is the wall time
            now, documented = number(row[k]), number(matches[0][k])
            if now is None and documented is None:
                continue
            if now is None or documented is None:
                problems.append(f"{name}, column {k + 1}: documented '{matches[0][k]}', now '{row[k]}'")
                continue
            digits = len(documented.split(".")[1]) if "." in documented else 0
            tolerance = 0.5 * 10 ** -digits + 2e-3 * abs(float(documented))
            verdict = "ok" if abs(float(now) - float(documented)) <= tolerance else "MOVED"
            print(f"{name[:60]:60s} col {k + 1}: documented {documented:>8s}  now {now:>8s}  {verdict}")
            if verdict != "ok":
                problems.append(f"{name}, column {k + 1}: documented {documented}, now {now}")
    if compared < at_least:
        problems.append(f"{compared} rows compared, expected at least {at_least}")
    if problems:
        print("FAIL: docs/validation.md does not hold this run's figures (rerun, then paste OUT/docs-rows.md):")
        for p in problems:
            print("  " + p)
        return 1
    print(f"docs/validation.md: {compared} rows reproduce")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
