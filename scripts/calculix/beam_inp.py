#!/usr/bin/env python3
"""A complete CalculiX input for Gregoire et al.'s (2013) half-notched beam in three-point bending
with ecm's UMAT, the material card written by ecm-calibrate --write-umat and pulled in by
*INCLUDE (docs/fe-codes.md, "A notched beam in CalculiX"). Units: mm, N, MPa.

    ecm-calibrate --E 37000 --nu 0.2 --ft 3.9 --GF 0.1432 --h 0.05 --fit hordijk --name concrete \\
        --write-umat concrete.inp --element-size 1.25,2.5,5
    python3 scripts/calculix/beam_inp.py beam.inp --card concrete.inp --to 0.3
    ccx -i beam

The beam: 175 x 50 mm, 50 mm thick (one C3D8 element through it), a notch 2.5 mm wide to
mid-depth at x = 87.5 mm, supports at x = 25 and 150 mm on the bottom (a line of nodes across
the thickness each: the one at 25 mm held in x and y, the one at 150 mm in y), the load a
prescribed downward displacement of the two top node lines beside x = 87.5 mm (the notch's
width). The mesh is 2.5 mm square over x = 76.25-98.75 mm, where the crack grows, and 5 mm wide
outside, with a 1.25 mm column at each change: each column's elements take the card's material
for their width (H = the element's size across a vertical crack; the card's names end in
_H1p25, _H2p5, _H5). z = 0 is held in z at the two supports.
Outputs (.dat): the load line's reaction and displacement per increment (*NODE PRINT, TOTALS)
and, in .frd, the state variables (SDV 17 = damage).
"""
import argparse
import pathlib
import sys

LENGTH, DEPTH, THICKNESS = 175.0, 50.0, 50.0
NOTCH = (86.25, 88.75, 25.0)  # the notch's faces (x) and its depth (y), mm
SUPPORTS = (25.0, 150.0)      # mm


def x_lines():
    """0, 5, ..., 75, then 76.25, 78.75, ..., 98.75 (2.5 mm, the notch's faces among them), then 100, ..., 175."""
    xs = [5.0 * i for i in range(16)]
    xs += [76.25 + 2.5 * i for i in range(10)]
    xs += [100.0 + 5.0 * i for i in range(16)]
    return xs


def size_tag(width):
    text = ("%g" % width).replace(".", "p")
    return "_H" + text


def beam_input(card, base_name, to, increment):
    xs, ys = x_lines(), [2.5 * j for j in range(21)]
    nx, ny = len(xs), len(ys)
    layer = nx * ny
    node = lambda i, j, k=0: 1 + i + nx * j + k * layer  # noqa: E731
    lines = ["** Gregoire et al.'s half-notched beam (depth 50 mm), three-point bending, ecm's UMAT.",
             "** Units: mm, N, MPa. Written by scripts/calculix/beam_inp.py (docs/fe-codes.md).",
             f"*INCLUDE, INPUT={card}", "*NODE, NSET=NALL"]
    for k, z in enumerate((0.0, THICKNESS)):
        for j, y in enumerate(ys):
            for i, x in enumerate(xs):
                lines.append(f"{node(i, j, k)}, {x:g}, {y:g}, {z:g}")
    sets = {}
    elements = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            if NOTCH[0] <= xs[i] < NOTCH[1] and ys[j] < NOTCH[2]:
                continue  # the notch
            q = [node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)]
            elements.append(q + [n + layer for n in q])
            sets.setdefault(size_tag(xs[i + 1] - xs[i]), []).append(len(elements))
    lines.append("*ELEMENT, TYPE=C3D8")
    lines += [f"{e}, " + ", ".join(map(str, q)) for e, q in enumerate(elements, 1)]
    for tag, members in sorted(sets.items()):
        lines.append(f"*ELSET, ELSET=E{tag}")
        lines += [", ".join(map(str, members[i:i + 12])) for i in range(0, len(members), 12)]
        lines.append(f"*SOLID SECTION, ELSET=E{tag}, MATERIAL={base_name}{tag}")
    column = lambda x: xs.index(x)  # noqa: E731
    pin = [node(column(SUPPORTS[0]), 0, k) for k in (0, 1)]
    roller = [node(column(SUPPORTS[1]), 0, k) for k in (0, 1)]
    load = [node(column(x), ny - 1, k) for x in NOTCH[:2] for k in (0, 1)]
    for name, members in (("PIN", pin), ("ROLLER", roller), ("LOAD", load)):
        lines += [f"*NSET, NSET={name}", ", ".join(map(str, members))]
    lines += ["*BOUNDARY", "PIN, 1, 2, 0.", "ROLLER, 2, 2, 0.", f"{pin[0]}, 3, 3, 0.", f"{roller[0]}, 3, 3, 0.",
              "*STEP, INC=100000", "*STATIC", f"{increment:g}, 1., 1e-6, {increment:g}",
              "*BOUNDARY", f"LOAD, 2, 2, {-to:g}",
              "*NODE PRINT, NSET=LOAD, TOTALS=ONLY", "RF", "*NODE PRINT, NSET=LOAD", "U",
              "*EL FILE", "SDV", "*END STEP"]
    return "\n".join(lines) + "\n"


def card_base_name(card):
    """The card's material name without its size tag (ABAQUS_CONCRETE_H2p5 -> ABAQUS_CONCRETE)."""
    for line in pathlib.Path(card).read_text().splitlines():
        if line.upper().startswith("*MATERIAL"):
            name = line.split("NAME=")[1].strip()
            return name.rsplit("_H", 1)[0]
    raise SystemExit(f"beam_inp: {card} holds no *MATERIAL")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the .inp to write")
    parser.add_argument("--card", required=True, help="the material card (ecm-calibrate --write-umat ... --element-size 1.25,2.5,5)")
    parser.add_argument("--to", type=float, default=0.3, help="the load line's final downward displacement (mm)")
    parser.add_argument("--increment", type=float, default=0.01, help="the step's first and largest increment (fraction)")
    args = parser.parse_args(argv)
    text = pathlib.Path(args.card).read_text()
    base = card_base_name(args.card)
    for tag in ("_H1p25", "_H2p5", "_H5"):
        if f"NAME={base}{tag}" not in text:
            raise SystemExit(f"beam_inp: {args.card} has no material {base}{tag}: write it with --element-size 1.25,2.5,5")
    with open(args.out, "w") as f:
        f.write(beam_input(args.card, base, args.to, args.increment))
    return 0


if __name__ == "__main__":
    sys.exit(main())
