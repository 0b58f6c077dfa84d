#!/usr/bin/env python3
"""CalculiX input for one C3D8 element of ecm's UMAT driven through a homogeneous strain path.

Every node's displacement is prescribed, u = eps x (eps the target strain of each step, shears
engineering), so each of the eight integration points follows the same strain path as an
`ecm-point` scene whose six strain components are all controlled. Units: mm, N, MPa.

    python3 scripts/calculix/element_inp.py OUT.inp --props 1,32000,0.2,3,8.184,0.128,0.05,10,1 \
        --size 10 --step 200:eps_xx=2e-4 --step 200:eps_xx=2e-4,gamma_xy=1e-3
    python3 scripts/calculix/element_inp.py OUT.inp --props ... --direction 1,2,2 --step 400:e=2e-3
    python3 scripts/calculix/element_inp.py OUT.inp --card concrete.inp --size 2.5 --step 200:eps_xx=2e-4

A step is INCREMENTS:COMPONENT=VALUE,... with the components eps_xx, eps_yy, eps_zz, gamma_yz,
gamma_xz, gamma_xy (absent ones are 0 at the step's end), or with --direction d, `e` for the
uniaxial strain eps = e d (x) d (d normalised). CalculiX ramps each step from the previous one's
end in equal, fixed increments (*STATIC, DIRECT). PROPS and STATEV: docs/fe-codes.md.
"""
import argparse
import math
import pathlib
import sys

COMPONENTS = ("eps_xx", "eps_yy", "eps_zz", "gamma_yz", "gamma_xz", "gamma_xy")
STATE_VARIABLES = 17  # docs/fe-codes.md, STATEV


def field(x):
    """A number as CalculiX reads it: at most 20 characters a field (longer ones are cut, and
    CalculiX stops with rc 201), with as many significant digits as fit (17: round-trip)."""
    for digits in range(17, 0, -1):
        text = f"{x:.{digits}g}"
        if len(text) <= 20:
            return text
    raise ValueError(f"element_inp: {x!r} does not fit in a 20-character field")


def cube_nodes(size):
    """C3D8's node order: the face z = 0 counter-clockwise, then the face z = size."""
    s = size
    return [(0, 0, 0), (s, 0, 0), (s, s, 0), (0, s, 0), (0, 0, s), (s, 0, s), (s, s, s), (0, s, s)]


def strain_tensor(values):
    """The symmetric tensor of six Voigt values (eps_xx, eps_yy, eps_zz, gamma_yz, gamma_xz, gamma_xy)."""
    xx, yy, zz, yz, xz, xy = values
    return [[xx, xy / 2, xz / 2], [xy / 2, yy, yz / 2], [xz / 2, yz / 2, zz]]


def parse_step(text, direction):
    """'200:eps_xx=2e-4,gamma_xy=1e-3' -> (200, six Voigt values)."""
    try:
        count, _, rest = text.partition(":")
        increments = int(count)
        given = {}
        for item in filter(None, rest.split(",")):
            key, value = item.split("=")
            given[key.strip()] = float(value)
    except ValueError:
        raise SystemExit(f"element_inp: step '{text}': expected INCREMENTS:COMPONENT=VALUE,...")
    if increments < 1:
        raise SystemExit(f"element_inp: step '{text}': the increments must be at least 1")
    if direction is not None:
        if set(given) != {"e"}:
            raise SystemExit(f"element_inp: step '{text}': with --direction give only e=VALUE")
        d = direction
        e = given["e"]
        return increments, [e * d[0] * d[0], e * d[1] * d[1], e * d[2] * d[2],
                            2 * e * d[1] * d[2], 2 * e * d[0] * d[2], 2 * e * d[0] * d[1]]
    unknown = set(given) - set(COMPONENTS)
    if unknown:
        raise SystemExit(f"element_inp: step '{text}': unknown component(s) {sorted(unknown)}; "
                         f"known: {', '.join(COMPONENTS)}")
    return increments, [given.get(c, 0.0) for c in COMPONENTS]


def card_material(card):
    """The name of the first *MATERIAL in a card file (as ecm-calibrate --write-umat writes it)."""
    for line in pathlib.Path(card).read_text().splitlines():
        if line.upper().startswith("*MATERIAL"):
            for item in line.split(",")[1:]:
                key, _, value = item.partition("=")
                if key.strip().upper() == "NAME":
                    return value.strip()
    raise SystemExit(f"element_inp: {card} holds no *MATERIAL, NAME=...")


def element_input(props, size, steps, material="ABAQUS_ECM", card=None):
    """The text of the .inp: props (9 or 10 numbers), the cube's edge (mm), steps [(increments, voigt)].
    With `card` (a file with the *MATERIAL block, e.g. from ecm-calibrate --write-umat) the deck
    includes it and the element takes its first material; props are then not used."""
    nodes = cube_nodes(size)
    lines = ["** One C3D8 element of ecm's UMAT under a homogeneous strain path. Units: mm, N, MPa.",
             "*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {field(x)}, {field(y)}, {field(z)}" for i, (x, y, z) in enumerate(nodes)]
    lines += ["*ELEMENT, TYPE=C3D8, ELSET=EALL", "1, 1, 2, 3, 4, 5, 6, 7, 8"]
    if card is not None:
        material = card_material(card)
        lines += [f"*INCLUDE, INPUT={card}"]
    else:
        lines += [f"*MATERIAL, NAME={material}", f"*USER MATERIAL, CONSTANTS={len(props)}"]
        lines += [", ".join(field(p) for p in props[i:i + 8]) for i in range(0, len(props), 8)]
        lines += ["*DEPVAR", str(STATE_VARIABLES)]
    lines += [f"*SOLID SECTION, ELSET=EALL, MATERIAL={material}"]
    for increments, voigt in steps:
        eps = strain_tensor(voigt)
        lines += [f"*STEP, INC={increments + 10}", "*STATIC, DIRECT", f"{field(1.0 / increments)}, 1.", "*BOUNDARY"]
        for n, x in enumerate(nodes):
            for i in range(3):
                u = sum(eps[i][j] * x[j] for j in range(3))
                lines.append(f"{n + 1}, {i + 1}, {i + 1}, {field(u)}")
        lines += ["*EL PRINT, ELSET=EALL", "S, SDV, E", "*END STEP"]
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the .inp file to write")
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("--props", help="PROPS, comma-separated (docs/fe-codes.md)")
    source.add_argument("--card", help="a material card file to include (ecm-calibrate --write-umat)")
    parser.add_argument("--size", type=float, default=10.0, help="the cube's edge (mm)")
    parser.add_argument("--direction", help="d for uniaxial strain e d (x) d, comma-separated")
    parser.add_argument("--step", action="append", required=True, help="INCREMENTS:COMPONENT=VALUE,...")
    args = parser.parse_args(argv)
    props = [float(p) for p in args.props.split(",")] if args.props else []
    if args.props and len(props) not in (9, 10):
        raise SystemExit(f"element_inp: --props has {len(props)} numbers; the UMAT takes 9 or 10")
    direction = None
    if args.direction:
        d = [float(c) for c in args.direction.split(",")]
        norm = math.sqrt(sum(c * c for c in d))
        if len(d) != 3 or norm == 0:
            raise SystemExit("element_inp: --direction needs three numbers, not all zero")
        direction = [c / norm for c in d]
    if not args.size > 0:
        raise SystemExit("element_inp: --size must be positive (mm)")
    steps = [parse_step(s, direction) for s in args.step]
    with open(args.out, "w") as f:
        f.write(element_input(props, args.size, steps, card=args.card))
    return 0


if __name__ == "__main__":
    sys.exit(main())
