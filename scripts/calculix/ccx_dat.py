#!/usr/bin/env python3
"""Reads the element and node tables of a CalculiX .dat file (*EL PRINT, *NODE PRINT).

    blocks = read_dat("job.dat")
    blocks[("stresses", "EALL")]          # [(time, {(element, point): [values]}), ...]
    python3 scripts/calculix/ccx_dat.py job.dat      # lists the tables and their rows

CalculiX prints each table as a title line, "<what> (<columns>) for set <SET> and time <T>", a
blank line, then one row per element and integration point (element tables: two integers, then
the values) or per node (node tables: one integer, then the values; a set's totals, "total force
(fx,fy,fz) for set ...", one row of values alone, key ()), in the format 1p,e13.6:
seven significant digits, so a value read back is within 5e-7 of the computed one, relatively.
Shears in the stress and strain tables are tensor components (sxy, exy = gamma_xy / 2), in the
order xx, yy, zz, xy, xz, yz. `time` is the total time (the steps' periods added up).
"""
import re
import sys

_TITLE = re.compile(r"^\s*(?P<what>[a-z][a-z .]*?)\s*\((?P<columns>[^)]*)\)\s*for set\s+(?P<set>\S+)"
                    r"\s+and time\s+(?P<time>\S+)\s*$")

ELEMENT_TABLES = ("stresses", "strains", "internal state variables", "equivalent plastic strain",
                  "internal energy density")


def read_dat(path):
    """{(what, set): [(time, {key: [values]})]}; key is (element, point), (node,) or () for totals."""
    blocks = {}
    rows = None
    key_width = 2
    with open(path) as f:
        for number, line in enumerate(f, 1):
            title = _TITLE.match(line)
            if title:
                what = title["what"].strip()
                # a set's totals (*NODE PRINT, TOTALS=YES or ONLY: "total force (fx,fy,fz) ...") are one
                # row of values with no node number: its key is ()
                key_width = 0 if what.startswith("total ") else 2 if what in ELEMENT_TABLES else 1
                rows = {}
                blocks.setdefault((what, title["set"]), []).append((float(title["time"]), rows))
                continue
            fields = line.split()
            if not fields or rows is None:
                continue
            try:
                key = tuple(int(v) for v in fields[:key_width])
                values = [float(v) for v in fields[key_width:]]
            except ValueError:
                rows = None  # a line of another kind ends the table
                continue
            if key in rows:
                raise ValueError(f"{path}:{number}: {key} appears twice in one table")
            rows[key] = values
    return blocks


def main(argv):
    if len(argv) != 2:
        print("usage: ccx_dat.py JOB.dat", file=sys.stderr)
        return 2
    for (what, name), tables in read_dat(argv[1]).items():
        print(f"{what} (set {name}): {len(tables)} times, {len(tables[-1][1])} rows at time {tables[-1][0]:g}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
