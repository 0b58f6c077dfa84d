#!/usr/bin/env python3
"""Checks the *USER MATERIAL cards of an Abaqus or CalculiX deck before a solver reads it.

Each card declares CONSTANTS=N and must list exactly N values on its data lines (eight a line).
CalculiX 2.20 does not check it: it drops values past the count, reads constants nobody wrote
below it, or stops (exit 201, or a crash) depending on the layout (docs/fe-codes.md, "Material
cards"), so ecm's scripts run this check before they start ccx. Decks pulled in by
*INCLUDE, INPUT=... are checked too (relative to the including deck). For ecm's own UMAT the
count is 9 or 10 (docs/fe-codes.md, PROPS); `--ecm` checks that as well.

    python3 scripts/calculix/deck_check.py JOB.inp [--ecm]    # exit 1 and FILE:LINE: reason
"""
import argparse
import pathlib
import re
import sys

ECM_CONSTANTS = (9, 10)  # PROPS 1-9 required, 10 optional (umat/umat_layout.hpp)


def _parameters(keyword_line):
    """'*USER MATERIAL, CONSTANTS=9' -> {'CONSTANTS': '9'} (names upper-case)."""
    out = {}
    for item in keyword_line.split(",")[1:]:
        name, _, value = item.partition("=")
        out[name.strip().upper()] = value.strip()
    return out


def user_material_problems(path, ecm=False, _seen=None):
    """Every problem of the deck's *USER MATERIAL cards, as 'FILE:LINE: reason' strings."""
    path = pathlib.Path(path)
    seen = set() if _seen is None else _seen
    if path.resolve() in seen:
        return []
    seen.add(path.resolve())
    try:
        lines = path.read_text().splitlines()
    except OSError as e:
        return [f"{path}: cannot be read ({e.strerror})"]
    problems = []
    card = None  # (line number, declared count, values counted)

    def close():
        if card is None:
            return
        line, declared, counted = card
        if declared is None:
            problems.append(f"{path}:{line}: *USER MATERIAL without CONSTANTS=N")
        elif counted != declared:
            problems.append(f"{path}:{line}: *USER MATERIAL declares CONSTANTS={declared} but lists {counted} "
                            f"value(s): write CONSTANTS={counted} (CalculiX would read other constants than those written)")
        elif ecm and declared not in ECM_CONSTANTS:
            problems.append(f"{path}:{line}: CONSTANTS={declared}: ecm's UMAT takes 9 or 10 (docs/fe-codes.md)")

    for number, raw in enumerate(lines, start=1):
        text = raw.strip()
        if not text or text.startswith("**"):
            continue
        if text.startswith("*"):
            close()
            card = None
            keyword = text[1:].split(",")[0].strip().upper()
            params = _parameters(text)
            if keyword == "USER MATERIAL":
                value = params.get("CONSTANTS")
                declared = int(value) if value and re.fullmatch(r"\d+", value) else None
                card = (number, declared, 0)
            elif keyword == "INCLUDE" and "INPUT" in params:
                problems += user_material_problems(path.parent / params["INPUT"], ecm, seen)
            continue
        if card is not None:
            values = [v for v in text.split(",") if v.strip()]
            card = (card[0], card[1], card[2] + len(values))
    close()
    return problems


def check(path, ecm=False):
    """Raises SystemExit naming every problem (for scripts that are about to start ccx)."""
    problems = user_material_problems(path, ecm)
    if problems:
        raise SystemExit("deck_check: " + "\ndeck_check: ".join(problems))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("deck", help="the .inp file")
    parser.add_argument("--ecm", action="store_true", help="the cards are ecm's UMAT's: 9 or 10 constants")
    args = parser.parse_args(argv)
    problems = user_material_problems(args.deck, args.ecm)
    for p in problems:
        print(p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
