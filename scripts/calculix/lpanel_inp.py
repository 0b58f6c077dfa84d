#!/usr/bin/env python3
"""CalculiX input for Winkler's L-panel with ecm's UMAT, meshed as an ecm-mpm scene's grid cells.

    PYTHONPATH=build/python python3 scripts/calculix/lpanel_inp.py \
        data/validation/lpanel-coarse-implicit.yaml OUT.inp

The scene gives the cell size, the thickness and the material (its `file:`), so that the element
and the MPM cell are the same square. The geometry and the supports are the scene's
(docs/validation.md, section 2): a 500 x 500 mm panel less its lower right 250 x 250 mm quadrant;
the leg's bottom clamped (x, y; z on the face z = 0 only, so that the thickness may change as in
plane stress); the load through a 20 mm plate (a rigid body of the nodes x = 460..480 mm on
y = 250 mm) on a hinge at (470, 250): free in x and in its rotation about z, driven in y to `--to`
mm (the step's time is that displacement).
One C3D8 element through the thickness; H = the cell's edge (the scene's `effective_size: sqrt`,
and the 3D rule of docs/model.md for a band across the thickness). The load point's reaction is
printed every increment (*NODE PRINT of the plate's reference node, in the .dat), and the state
variables go to the .frd (extrapolated to the nodes) every increment: CalculiX 2.20 has one
output frequency for both files, and the comparison needs the curve's every point. A second step
holds the load point for one increment and prints the state variables at every integration point
(the .dat's "internal state variables" at time `--to` + 1). Units: mm, N, MPa.
"""
import argparse
import sys

import ecm
from element_inp import STATE_VARIABLES, field  # docs/fe-codes.md, STATEV; field: 20 characters at most

PANEL, CUT, PLATE = 500.0, 250.0, (460.0, 480.0)


def material_props(material, size):
    """PROPS of docs/fe-codes.md from an ecm material dict; snap_back 1 (release) as ecm-mpm."""
    keys = ("youngs_modulus", "poisson_ratio", "tensile_strength", "softening_modulus", "softening_exponent", "band_width")
    if material.get("model") != "enriched":
        raise SystemExit(f"lpanel_inp: the material is {material.get('model')}; the UMAT is the enriched model")
    if material.get("second_band", "off") != "off":
        print("lpanel_inp: the UMAT carries one band: the material's second band is left out", file=sys.stderr)
    return [1.0] + [float(material[k]) for k in keys] + [size, 1.0]


def panel_cells(size):
    """The panel's cells (i, j) of `size` mm, x from i size to (i + 1) size, in the elements' order
    (element k is the k-th, from 1)."""
    cells = round(PANEL / size)
    if abs(cells * size - PANEL) > 1e-9 or abs(round(CUT / size) * size - CUT) > 1e-9:
        raise SystemExit(f"lpanel_inp: the cell size {size} mm does not divide 250 mm")
    cut = round(CUT / size)
    return [(i, j) for j in range(cells) for i in range(cells) if not (i >= cut and j < cut)]


def lpanel_input(size, thickness, props, to=1.0, increment=0.01, element="C3D8"):
    cut = round(CUT / size)
    elements = panel_cells(size)
    used = sorted({(i + di, j + dj) for i, j in elements for di in (0, 1) for dj in (0, 1)})
    layer = len(used)
    number = {ij: n + 1 for n, ij in enumerate(used)}  # z = 0; z = thickness is + layer
    lines = ["** Winkler's L-panel, ecm's UMAT, one C3D8 element through the thickness. Units: mm, N, MPa.", "*NODE"]
    for (i, j), n in number.items():
        lines.append(f"{n}, {field(i * size)}, {field(j * size)}, 0")
        lines.append(f"{n + layer}, {field(i * size)}, {field(j * size)}, {field(thickness)}")
    ref, rot = 2 * layer + 1, 2 * layer + 2
    lines += [f"{ref}, 470, 250, {field(thickness / 2)}", f"{rot}, 470, 250, {field(thickness / 2)}",
              f"*ELEMENT, TYPE={element}, ELSET=EALL"]
    for e, (i, j) in enumerate(elements, 1):
        q = [number[(i, j)], number[(i + 1, j)], number[(i + 1, j + 1)], number[(i, j + 1)]]
        lines.append(f"{e}, " + ", ".join(str(n) for n in q + [n + layer for n in q]))
    base = [n for (i, j), n in number.items() if j == 0]
    plate = [n for (i, j), n in number.items() if j == cut and PLATE[0] <= i * size <= PLATE[1]]
    lines += ["*NSET, NSET=BASE"] + [f"{n}," for n in base + [n + layer for n in base]]
    lines += ["*NSET, NSET=BASE0"] + [f"{n}," for n in base]
    lines += ["*NSET, NSET=PLATE"] + [f"{n}," for n in plate + [n + layer for n in plate]]
    lines += ["*NSET, NSET=LOAD", f"{ref},"]
    lines += ["*MATERIAL, NAME=ABAQUS_ECM", f"*USER MATERIAL, CONSTANTS={len(props)}",
              ", ".join(f"{field(p)}" for p in props[:8]), ", ".join(f"{field(p)}" for p in props[8:]),
              "*DEPVAR", str(STATE_VARIABLES), "*SOLID SECTION, ELSET=EALL, MATERIAL=ABAQUS_ECM",
              f"*RIGID BODY, NSET=PLATE, REF NODE={ref}, ROT NODE={rot}",
              "*BOUNDARY", "BASE, 1, 2, 0.", "BASE0, 3, 3, 0.", f"{ref}, 3, 3, 0.", f"{rot}, 1, 2, 0.",
              "*STEP, INC=100000", "*STATIC",
              f"{field(increment)}, {field(to)}, 1e-6, {field(increment)}",
              "*BOUNDARY", f"{ref}, 2, 2, {field(to)}",
              "*NODE PRINT, NSET=LOAD", "U, RF",
              "*EL FILE", "SDV",
              "*END STEP",
              # A hold of one increment at the end: the state variables at every integration point.
              "*STEP", "*STATIC", "1., 1.", "*EL PRINT, ELSET=EALL", "SDV", "*END STEP"]
    return "\n".join(lines) + "\n", len(elements)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="an ecm-mpm L-panel scene (data/validation/lpanel-*.yaml)")
    parser.add_argument("out", help="the .inp file to write")
    parser.add_argument("--to", type=float, default=1.0, help="the load point's displacement at the end (mm)")
    parser.add_argument("--increment", type=float, default=0.01, help="the largest increment of the load point (mm)")
    parser.add_argument("--element", choices=["C3D8", "C3D8I"], default="C3D8",
                        help="C3D8 (trilinear, 2 x 2 x 2 Gauss points) or C3D8I (with incompatible bending modes)")
    args = parser.parse_args(argv)
    scene = ecm.load_scene(args.scene)
    size = float(scene["grid"]["cell_size"][0])
    if float(scene["grid"]["cell_size"][1]) != size:
        raise SystemExit("lpanel_inp: the scene's cells are not square")
    material = scene["materials"][0]
    if "file" in material:
        material = ecm.load_scene(material["file"])
    if not (args.to > 0 and 0 < args.increment <= args.to):
        raise SystemExit("lpanel_inp: need --to > 0 and 0 < --increment <= --to")
    text, count = lpanel_input(size, float(scene["thickness"]), material_props(material, size), args.to, args.increment,
                               args.element)
    with open(args.out, "w") as f:
        f.write(text)
    print(f"lpanel_inp: {count} {args.element} elements of {size:g} mm, {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
