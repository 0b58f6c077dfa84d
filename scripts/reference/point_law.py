#!/usr/bin/env python3
"""The traction-opening table of an enriched point (ecm-point's history.csv under opening control)
for ecm-cohesive's `table` law: opening_mm, traction_MPa from the first opening on, after a row
(0, f_t') where the band starts (docs/cohesive.md, "The traction-opening laws").

Usage: scripts/reference/point_law.py HISTORY_CSV TENSILE_STRENGTH > TABLE_CSV
"""
import csv
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = list(csv.DictReader(open(sys.argv[1])))
    ft = float(sys.argv[2])
    print("# the traction-opening curve of one enriched point in uniaxial stress (ecm-point, opening control)")
    print("# made by: ecm-point data/reference/beam-point-law.yaml --out DIR; scripts/reference/point_law.py DIR/history.csv %s" % sys.argv[2])
    print("opening_mm,traction_MPa")
    print("0,%r" % ft)
    last = 0.0
    for r in rows:
        w, t = float(r["jump_n"]), float(r["traction_n"])
        if w <= last:
            continue
        print("%.10g,%.10g" % (w, t))
        last = w


if __name__ == "__main__":
    main()
