#!/usr/bin/env python3
"""Winkler's L-panel in CalculiX (ecm's UMAT, C3D8 on the MPM grid's cells) against ecm-mpm's
implicit run of the same scene: load-displacement curves, peaks and crack paths side by side.

    PYTHONPATH=build/python python3 scripts/calculix/lpanel_compare.py \
        data/validation/lpanel-coarse-implicit.yaml --ccx build/calculix/ccx --to 0.5 --out DIR

CalculiX runs first, to the load point's displacement `--to` (mm) or as far as it converges; ecm-mpm
then runs the scene to the same displacement (its pseudo-time is that displacement), so that both
final damage maps are at one displacement. Writes into DIR: ccx/ (the job), mpm/ (ecm-mpm's
output), curves.csv (solver, u_mm, F_N), cells.csv (the damage per cell of both), summary.json and
lpanel_ccx_vs_mpm.png. The differences and what causes them: docs/fe-codes.md. Units: mm, N.
"""
import argparse
import csv
import json
import os
import pathlib
import subprocess
import sys

import ecm

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import ccx_dat  # noqa: E402
import deck_check  # noqa: E402
import ccx_frd  # noqa: E402
import lpanel_inp  # noqa: E402

DAMAGE = 16  # SDV 17, docs/fe-codes.md


def run_ccx(scene, ccx, to, folder, increment=0.01, element="C3D8"):
    folder.mkdir(parents=True, exist_ok=True)
    args = [str(scene), str(folder / "lpanel.inp"), "--to", repr(to), "--increment", repr(increment), "--element", element]
    lpanel_inp.main(args)
    deck_check.check(folder / "lpanel.inp", ecm=True)  # before ccx reads it (docs/fe-codes.md, "Material cards")
    with open(folder / "ccx.log", "w") as log:
        status = subprocess.run([ccx, "-i", "lpanel"], cwd=folder, stdout=log, stderr=subprocess.STDOUT,
                                env=dict(os.environ, OMP_NUM_THREADS="1")).returncode
    tables = ccx_dat.read_dat(folder / "lpanel.dat")
    loading = lambda key: [(t, rows[min(rows)][1]) for t, rows in tables[(key, "LOAD")] if t <= to * (1 + 1e-12)]
    u, force = [v for _, v in loading("displacements")], [v for _, v in loading("forces")]
    size = float(ecm.load_scene(scene)["grid"]["cell_size"][0])
    points = tables.get(("internal state variables", "EALL"))
    if points:  # the hold step ran: the damage at the integration points, averaged per element
        cells = lpanel_inp.panel_cells(size)
        damage = {}
        for (element, _), values in points[-1][1].items():
            damage.setdefault(cells[element - 1], []).append(values[DAMAGE])
        return {"status": status, "u": [0.0] + u, "F": [0.0] + force, "damage_time": u[-1], "damage_from": "points",
                "cells": {c: sum(v) / len(v) for c, v in damage.items()}}
    # CalculiX stopped before the end: the damage extrapolated to the nodes at its last increment.
    nodes, blocks = ccx_frd.read_frd(folder / "lpanel.frd")
    time, values = blocks["SDV"][-1]
    corners = {}
    for n, (x, y, z) in nodes.items():
        if n in values:
            corners.setdefault((round(x / size), round(y / size)), []).append(values[n][DAMAGE])
    cells = {}
    for i, j in lpanel_inp.panel_cells(size):
        v = [d for di in (0, 1) for dj in (0, 1) for d in corners.get((i + di, j + dj), [])]
        cells[(i, j)] = sum(v) / len(v)
    return {"status": status, "u": [0.0] + u, "F": [0.0] + force, "damage_time": time, "damage_from": "nodes",
            "cells": cells}


def as_the_umat_carries_it(s):
    """The scene's model as ecm's UMAT carries it (docs/fe-codes.md): one band (the UMAT refuses the
    second band) opening wherever an element reaches onset (the free rule: CalculiX has no crack
    paths). The validation scene's second band and tracked paths are left out on both sides."""
    s["solver"]["crack_path"] = "free"
    materials = []
    for m in s["materials"]:
        m = dict(ecm.load_scene(m["file"]) if "file" in m else m)
        m["second_band"] = "off"
        materials.append(m)
    s["materials"] = materials
    return s


def run_mpm(scene, to, folder):
    s = as_the_umat_carries_it(ecm.load_scene(scene))
    s["end_time"] = to
    result = ecm.run_scene(s, folder, snapshots=False, check=False)  # a failed run is compared as far as it got
    with open(folder / "history.csv") as f:
        rows = list(csv.DictReader(f))
    with open(folder / "particles_final.csv") as f:
        particles = [(float(r["x_mm"]), float(r["y_mm"]), float(r["damage"])) for r in csv.DictReader(f)]
    return {"status": result["status"], "u": [0.0] + [float(r["load-plate_uy_mm"]) for r in rows],
            "F": [0.0] + [float(r["load-plate_Fy_N"]) for r in rows], "particles": particles}


def first_peak(u, F, within=0.25):
    """The largest load for u <= within (mm), where the panel's first crack peaks; and the lowest
    load after it up to `within` + 0.1 mm (the dip before the load rises again)."""
    k = max((i for i in range(len(u)) if u[i] <= within), key=lambda i: F[i])
    after = [i for i in range(k, len(u)) if u[i] <= within + 0.1]
    m = min(after, key=lambda i: F[i])
    return {"peak_N": F[k], "u_at_peak_mm": u[k], "dip_N": F[m], "u_at_dip_mm": u[m]}


def cell_damage(size, ccx, mpm):
    """Per cell (i, j) of `size` mm: ecm-mpm's mean particle damage in the cell, and CalculiX's mean
    over the element's integration points (or, where CalculiX stopped early, over its nodes)."""
    particles = {}
    for x, y, d in mpm["particles"]:
        particles.setdefault((int(x // size), int(y // size)), []).append(d)
    return {c: (sum(v) / len(v), ccx["cells"].get(c, float("nan"))) for c, v in particles.items()}


def crack_overlap(cells, threshold=0.5):
    """Jaccard index of the cells whose damage exceeds `threshold` in each: 1 for the same cells."""
    a = {c for c, (m, _) in cells.items() if m > threshold}
    b = {c for c, (_, k) in cells.items() if k > threshold}
    return len(a & b) / max(len(a | b), 1), len(a), len(b)


def interpolate(u, F, x):
    for i in range(1, len(u)):
        if u[i - 1] <= x <= u[i] and u[i] > u[i - 1]:
            return F[i - 1] + (F[i] - F[i - 1]) * (x - u[i - 1]) / (u[i] - u[i - 1])
    return float("nan")


def compare(scene, ccx_path, to, out, element="C3D8"):
    out = pathlib.Path(out)
    ccx = run_ccx(scene, ccx_path, to, out / "ccx", element=element)
    if len(ccx["u"]) < 2:
        raise SystemExit(f"lpanel_compare: CalculiX converged no increment (status {ccx['status']}, {out}/ccx/ccx.log)")
    reached = ccx["u"][-1]
    mpm = run_mpm(scene, reached, out / "mpm")
    size = float(ecm.load_scene(scene)["grid"]["cell_size"][0])
    cells = cell_damage(size, ccx, mpm)
    overlap, n_mpm, n_ccx = crack_overlap(cells)
    slope = {name: interpolate(r["u"], r["F"], 0.02) / 0.02 for name, r in (("ccx", ccx), ("mpm", mpm))}
    summary = {"scene": os.path.basename(str(scene)), "model": "one band, free rule (what the UMAT carries)", "element": element, "to_mm": to, "ccx_reached_mm": reached,
               "ccx_status": ccx["status"], "mpm_reached_mm": mpm["u"][-1], "mpm_status": mpm["status"],
               "ccx": first_peak(ccx["u"], ccx["F"]), "mpm": first_peak(mpm["u"], mpm["F"]),
               "elastic_slope_N_per_mm": slope,
               "F_N_at": {f"{x:g}": {"ccx": interpolate(ccx["u"], ccx["F"], x), "mpm": interpolate(mpm["u"], mpm["F"], x)}
                          for x in (0.1, 0.2, 0.3, 0.4, 0.5) if x <= reached},
               "damage_ccx": {"at_mm": ccx["damage_time"], "from": ccx["damage_from"]},
               "crack_cells": {"threshold": 0.5, "mpm": n_mpm, "ccx": n_ccx, "jaccard": overlap}}
    with open(out / "curves.csv", "w") as f:
        f.write("solver,u_mm,F_N\n")
        for name, r in (("ccx", ccx), ("mpm", mpm)):
            f.writelines(f"{name},{u:.17g},{F:.17g}\n" for u, F in zip(r["u"], r["F"]))
    with open(out / "cells.csv", "w") as f:
        f.write("x_mm,y_mm,damage_mpm,damage_ccx\n")
        f.writelines(f"{(i + 0.5) * size:g},{(j + 0.5) * size:g},{m:.6g},{k:.6g}\n" for (i, j), (m, k) in sorted(cells.items()))
    with open(out / "summary.json", "w") as f:
        json.dump(summary, f, indent=2)
    plot(out)
    return summary


def plot(out):
    script = f"""set terminal pngcairo size 1500,480 font ',10'
set output '{out}/lpanel_ccx_vs_mpm.png'
set datafile separator ','
set multiplot layout 1,3
set xlabel 'load point displacement u (mm)'; set ylabel 'load F (N)'; set key bottom right
set title 'L-panel: load against displacement'
plot '< grep ^ccx {out}/curves.csv' u 2:3 w l lw 2 t 'CalculiX + ecm UMAT', \\
     '< grep ^mpm {out}/curves.csv' u 2:3 w l lw 2 t 'ecm-mpm implicit'
unset key; set size ratio -1; set xrange [0:500]; set yrange [0:500]; set cbrange [0:1]
set xlabel 'x (mm)'; set ylabel 'y (mm)'; set palette defined (0 '#f0f0f0', 0.5 '#fdae61', 1 '#a50026')
set title 'damage, ecm-mpm (mean per cell)'
plot '{out}/cells.csv' every ::1 u 1:2:3 w p pt 5 ps 0.55 lc palette
set title 'damage, CalculiX (mean per element)'
plot '{out}/cells.csv' every ::1 u 1:2:4 w p pt 5 ps 0.55 lc palette
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=False)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene")
    parser.add_argument("--ccx", default="build/calculix/ccx", help="CalculiX linked with ecm's UMAT")
    parser.add_argument("--to", type=float, default=0.5, help="the load point's displacement to reach (mm)")
    parser.add_argument("--element", choices=["C3D8", "C3D8I"], default="C3D8", help="CalculiX's element")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    summary = compare(args.scene, args.ccx, args.to, args.out, args.element)
    print(json.dumps(summary, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
