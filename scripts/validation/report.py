#!/usr/bin/env python3
"""The validation report (scripts/validate.sh): per run, the comparison with the test
(RUN/compare.json, scripts/validation/compare.py) and the run's own figures (RUN/summary.json), as
markdown tables on stdout and OUT/summary.json, the rows of docs/validation.md it generates in
OUT/docs-rows.md (DOC_ROWS below); OUT/den.png and OUT/lpanel.png overlay the runs on
the tests' curves (gnuplot). Usage: report.py OUT_DIR. Units: mm, N, s."""
import json
import os
import subprocess
import sys

out = sys.argv[1]
runs = sorted(d for d in os.listdir(out) if os.path.isfile(os.path.join(out, d, "compare.json")))
report = {}
for r in runs:
    c = json.load(open(os.path.join(out, r, "compare.json")))
    s = json.load(open(os.path.join(out, r, "summary.json")))
    c["status"] = s.get("status")
    c["wall_time_s"] = s.get("wall_time_s")
    c["dissipated_N_mm"] = s.get("energies_Nmm", {}).get("dissipated")
    report[r] = c
json.dump(report, open(os.path.join(out, "summary.json"), "w"), indent=1)


def fmt(v, f="{:.3g}"):
    return "-" if v is None else f.format(v)


den = [r for r in runs if r.startswith("den-")]
if den:
    print("| DEN 4b run | status | peak P (kN) | / test | delta at peak (mm) | post-peak distance | work to 0.1 mm (N mm) | slope (kN/um) | dissipated (N mm) | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    t = report[den[0]]
    print(f"| the test | | {t['test_peak_N'] / 1000:.2f} | 1 | {t['test_delta_at_peak_mm']:.4f} | 0 | {t['test_work_N_mm']:.0f} (to 0.1) | {t['test_initial_slope_kN_per_um']:.2f} | | |")
    for r in den:
        c = report[r]
        print(f"| {r} ({c['delta_measured_by']}) | {c['status']} | {c['peak_N'] / 1000:.2f} | {c['peak_ratio']:.3f} | {c['delta_at_peak_mm']:.4f} | "
              f"{fmt(c['post_peak_distance'])} | {c['work_N_mm']:.0f} (to {c['compared_up_to_mm']:.3f}) | {fmt(c['initial_slope_kN_per_um'])} | {fmt(c['dissipated_N_mm'], '{:.0f}')} | {fmt(c['wall_time_s'], '{:.0f}')} |")
    print()
lp = [r for r in runs if r.startswith("lpanel-")]
if lp:
    print("| L-panel run | status | peak F (kN) | u at peak (mm) | inside envelope | post-peak distance (series A) | work to 1 mm (N mm) | slope (kN/mm) | dissipated (N mm) | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    t = report[lp[0]]
    print(f"| the tests | | {t['envelope_peak_N'][0] / 1000:.1f}-{t['envelope_peak_N'][1] / 1000:.1f} (A: {t['series_a_peak_N'] / 1000:.2f}) | 0.20 (A: {t['series_a_u_at_peak_mm']:.3f}) | | | A: {t['series_a_work_N_mm']:.0f} | A: {t['series_a_initial_slope_kN_per_mm']:.1f} | | |")
    for r in lp:
        c = report[r]
        print(f"| {r} | {c['status']} | {c['peak_N'] / 1000:.2f} | {c['u_at_peak_mm']:.3f} | {fmt(c['inside_envelope_share'], '{:.0%}')} | "
              f"{fmt(c['post_peak_distance_to_series_a'])} | {c['work_N_mm']:.0f} (to {c['compared_up_to_mm']:.2f}) | {fmt(c['initial_slope_kN_per_mm'])} | {fmt(c['dissipated_N_mm'], '{:.0f}')} | {fmt(c['wall_time_s'], '{:.0f}')} |")


# The rows of docs/validation.md that this report generates, in the docs' own columns: OUT/docs-rows.md
# holds them for pasting, and scripts/validation/check_doc_rows.py holds the docs to them. Each
# entry: run, its comparison file, the table's columns, the row's label cells (as in the docs).
DEN_RESULTS = ["peak_kN", "ratio", "delta_at_peak", "post_peak_den", "work_den", "slope_den", "dissipated"]
DEN_MESH = ["peak_kN", "ratio", "delta_at_peak", "post_peak_den", "work_den", "dissipated"]
LPANEL = ["peak_kN", "u_at_peak", "inside", "post_peak_lpanel", "work_lpanel", "slope_lpanel", "dissipated"]
DOC_ROWS = [
    ("den-today-coarse", "compare.json", DEN_RESULTS, ["today's scene (`data/den/den-4b-coarse.yaml`), paper's law, delta = top edge"]),
    ("den-rig-coarse-paper-law", "compare-platen.json", DEN_RESULTS, ["rig, paper's law, delta = the frame's travel"]),
    ("den-rig-coarse-paper-law", "compare.json", DEN_RESULTS, ["rig, paper's law, delta = gauges"]),
    ("den-rig-coarse", "compare.json", DEN_RESULTS, ["rig, Hordijk's law, gauges (**the validation scene**, explicit)"]),
    ("den-rig-coarse-implicit", "compare.json", DEN_RESULTS, ["the same, implicit (rate-free)"]),
    ("den-rig-coarse-second-band", "compare.json", DEN_RESULTS, ["the same, explicit, second band"]),
    ("den-rig-coarse", "compare.json", DEN_MESH, ["coarse (2.5 mm)", "explicit, one band"]),
    ("den-rig-coarse-implicit", "compare.json", DEN_MESH, ["coarse", "implicit, one band"]),
    ("den-rig-coarse-second-band", "compare.json", DEN_MESH, ["coarse", "explicit, second band"]),
    ("den-rig-coarse-second-band-implicit", "compare.json", DEN_MESH, ["coarse", "implicit, second band"]),
    ("den-rig-medium", "compare.json", DEN_MESH, ["medium (1.25 mm)", "explicit, one band"]),
    ("den-rig-medium-implicit", "compare.json", DEN_MESH, ["medium", "implicit, one band"]),
    ("den-rig-medium-second-band", "compare.json", DEN_MESH, ["medium", "explicit, second band"]),
    ("den-rig-fine", "compare.json", DEN_MESH, ["fine (0.625 mm)", "explicit, one band"]),
    ("den-rig-fine-second-band", "compare.json", DEN_MESH, ["fine", "explicit, second band"]),
    ("lpanel-coarse", "compare.json", LPANEL, ["coarse (10 mm), explicit"]),
    ("lpanel-coarse-implicit", "compare.json", LPANEL, ["coarse, implicit"]),
    ("lpanel-coarse-paper-n", "compare.json", LPANEL, ["coarse, explicit, the paper's n = 0.128"]),
    ("lpanel-coarse-second-band", "compare.json", LPANEL, ["coarse, explicit, **second band**"]),
    ("lpanel-medium", "compare.json", LPANEL, ["medium (5 mm), explicit"]),
    ("lpanel-medium-second-band", "compare.json", LPANEL, ["medium, explicit, **second band**"]),
    ("lpanel-fine", "compare.json", LPANEL, ["fine (2.5 mm), explicit"]),
    ("lpanel-medium-implicit", "compare.json", LPANEL, ["medium, **implicit** (rate-free)"]),
    ("lpanel-fine-second-band", "compare.json", LPANEL, ["fine, explicit, **second band**"]),
    ("lpanel-coarse-second-band-implicit", "compare.json", LPANEL, ["coarse, **implicit, second band**"]),
    ("lpanel-medium-second-band-implicit", "compare.json", LPANEL, ["medium, **implicit, second band**"]),
]


def cell(column, c):
    """One figure as the docs print it; a run compared over less than its range says how far."""
    den_short = c.get("compared_up_to_mm", 1) < 0.0985
    lp_short = c.get("compared_up_to_mm", 1) < 0.985
    upto = f" (to {c.get('compared_up_to_mm', 0):.2f})"
    if column == "peak_kN":
        return f"{c['peak_N'] / 1000:.2f}"
    if column == "ratio":
        return f"{c['peak_ratio']:.3f}"
    if column == "delta_at_peak":
        return f"{c['delta_at_peak_mm']:.4f}"
    if column == "u_at_peak":
        return f"{c['u_at_peak_mm']:.3f}"
    if column == "post_peak_den":
        return fmt(c["post_peak_distance"], "{:.3f}")
    if column == "post_peak_lpanel":
        return fmt(c["post_peak_distance_to_series_a"], "{:.2f}") + (upto if lp_short else "")
    if column == "inside":
        return fmt(c["inside_envelope_share"] and 100 * c["inside_envelope_share"], "{:.0f} %") + (upto if lp_short else "")
    if column == "work_den":
        return f"{c['work_N_mm']:.0f}" + (f" (to {c['compared_up_to_mm']:.3f})" if den_short else "")
    if column == "work_lpanel":
        return f"{c['work_N_mm']:.0f}" + (upto if lp_short else "")
    if column == "slope_den":
        return fmt(c["initial_slope_kN_per_um"], "{:.2f}")
    if column == "slope_lpanel":
        return fmt(c["initial_slope_kN_per_mm"], "{:.1f}")
    if column == "dissipated":
        return fmt(c["dissipated_N_mm"], "{:.0f}")
    raise KeyError(column)


with open(os.path.join(out, "docs-rows.md"), "w") as f:
    for run, file, columns, label in DOC_ROWS:
        path = os.path.join(out, run, file)
        if not os.path.isfile(path):
            continue
        c = dict(json.load(open(path)), **{k: report[run][k] for k in ("status", "wall_time_s", "dissipated_N_mm")})
        status = "" if c["status"] == "completed" else f" ({c['status']})"
        cells = label + [cell(k, c) for k in columns] + [fmt(c["wall_time_s"], "{:.0f}") + status]
        f.write("| " + " | ".join(cells) + " |\n")


def plot(name, test_cmd, runs_, xcol, ycol, xlabel, ylabel, xmax):
    if not runs_:
        return
    lines = [f"set terminal pngcairo size 1000,650", f"set output '{out}/{name}.png'", "set datafile separator ','",
             f"set xlabel '{xlabel}'", f"set ylabel '{ylabel}'", f"set xrange [0:{xmax}]", "set key top right", "set grid"]
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22",
               "#7f7fff", "#ff7fbf", "#7fbf7f"]  # no black or gray: those are the tests'
    series = test_cmd + [f"'{out}/{r}/compare.csv' every ::1 using {xcol}:(${ycol}/1000) with lines lw 2 lc rgb '{colours[i % len(colours)]}' title '{r}'"
                         for i, r in enumerate(runs_)]
    lines.append("plot " + ", \\\n     ".join(series))
    subprocess.run(["gnuplot"], input="\n".join(lines) + "\n", text=True, check=False)


# The DEN's test curve as CSV (the file is whitespace-separated).
with open(os.path.join(out, "test-4b.csv"), "w") as f:
    for line in open("data/experiments/nooru-mohamed-4b.txt"):
        if line.strip() and not line.startswith("#"):
            f.write(",".join(line.split()) + "\n")
plot("den", [f"'{out}/test-4b.csv' using 1:($2/1000) with linespoints lw 3 lc rgb 'black' pt 7 title 'test (Nooru-Mohamed 4b)'"],
     den, 1, 2, "delta (mm)", "P (kN)", 0.1)
plot("lpanel", ["'data/experiments/winkler-lpanel-envelope.csv' every ::1 using 1:2 with lines lw 3 lc rgb 'gray' title 'test envelope (lower)'",
                "'data/experiments/winkler-lpanel-envelope.csv' every ::1 using 1:3 with lines lw 3 lc rgb 'gray' title 'test envelope (upper)'",
                "'data/experiments/winkler-lpanel-series-a.csv' using 1:($2/1000) with lines lw 2 lc rgb 'black' title 'test series A'"],
     lp, 1, 2, "load-point displacement u (mm)", "F (kN)", 1.0)
