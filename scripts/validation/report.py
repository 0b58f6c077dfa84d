#!/usr/bin/env python3
"""The validation report (scripts/validate.sh): per run, the comparison with the test
(RUN/compare.json, scripts/validation/compare.py) and the run's own figures (RUN/summary.json), as
markdown tables on stdout and OUT/summary.json, the rows of docs/validation.md it generates in
OUT/docs-rows.md (DOC_ROWS below); OUT/den.png and OUT/lpanel.png overlay the runs on
the tests' curves (gnuplot; the scripts beside them, .gp), each run's legend saying what it
measures and a run that did not complete crossed where it stopped; each target's verdict is
printed after its table and kept in OUT/summary.json ("targets"). Usage: report.py OUT_DIR. Units: mm, N, s."""
import json
import math
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


def fmt(v, f="{:.3g}"):
    return "-" if v is None else f.format(v)


# The targets of docs/validation.md, judged per run: (name, the figure, met?) from its comparison.
def den_verdicts(c):
    out = [("peak within 10 % of the test's", f"{c['peak_ratio'] - 1:+.1%}", abs(c["peak_ratio"] - 1) <= 0.10)]
    d = c.get("post_peak_distance")
    full = c.get("compared_up_to_mm", 0) >= 0.0985
    out.append(("post-peak within 15 % of the test's peak to delta = 0.1 mm",
                ("-" if d is None else f"{d:.0%}") + ("" if full else f" (compared to {c['compared_up_to_mm']:.3f} mm only)"),
                d is not None and d <= 0.15 and full))
    return out


def lpanel_verdicts(c):
    peak_in = 6700 <= c["peak_N"] <= 7600 and 0.15 <= c["u_at_peak_mm"] <= 0.25
    share = c.get("inside_envelope_share")
    full = c.get("compared_up_to_mm", 0) >= 0.985
    return [("peak inside 6.7-7.6 kN at u = 0.15-0.25 mm", f"{c['peak_N'] / 1000:.2f} kN at {c['u_at_peak_mm']:.3f} mm", peak_in),
            ("inside the envelope over 80 % of 0-1 mm",
             ("-" if share is None else f"{share:.0%}") + ("" if full else f" (of 0-{c['compared_up_to_mm']:.2f} mm only)"),
             share is not None and share >= 0.80 and full)]


def mesh_verdict(label, peaks):
    """The same peak within 3 % over the meshes that ran (coarse, medium, fine)."""
    if len(peaks) < 2:
        return None
    spread = (max(peaks.values()) - min(peaks.values())) / max(peaks.values())
    figure = ", ".join(f"{m} {v / 1000:.2f}" for m, v in peaks.items()) + f" kN: {spread:.1%}"
    return (f"{label}: the same peak within 3 % over the meshes", figure, spread <= 0.03 and len(peaks) == 3)


def richardson(coarse, medium, fine, ratio=2.0, safety=1.25):
    """Richardson extrapolation over three meshes refined by `ratio` (Celik et al. 2008, J. Fluids
    Eng. 130:078001, with a constant ratio): the observed order p = ln|e32 / e21| / ln r, the
    extrapolated value, and the fine mesh's grid convergence index GCI = safety |e21 / fine| /
    (r^p - 1); oscillatory when the differences change sign, diverging when they grow with refinement
    (then p is not an order of convergence). None when two meshes agree exactly."""
    e21, e32 = medium - fine, coarse - medium
    if e21 == 0 or e32 == 0:
        return None
    p = abs(math.log(abs(e32 / e21))) / math.log(ratio)
    if p == 0:
        return None
    rp = ratio ** p
    return {"order": p, "extrapolated": (rp * fine - medium) / (rp - 1), "gci_fine": safety * abs(e21 / fine) / (rp - 1),
            "oscillatory": e21 * e32 < 0, "diverging": abs(e21) >= abs(e32)}


def meshes(test, runs_):
    """The peak over the meshes, per family of runs that differ only by their mesh (TEST[-rig]-MESH[-variant]):
    its spread and, over three meshes, Richardson's order and GCI; printed and kept in summary.json (mesh_studies)."""
    families = {}
    for r in runs_:
        parts = r.split("-")
        k = next((i for i, w in enumerate(parts) if w in ("coarse", "medium", "fine")), None)
        if k is None or report[r]["status"] != "completed" or test == "den" and parts[1] != "rig":
            continue
        family = "-".join(parts[:k] + ["MESH"] + parts[k + 1:])
        families.setdefault(family, {})[parts[k]] = report[r]["peak_N"]
    rows = []
    for family, peaks in families.items():
        verdict = mesh_verdict(family, {m: peaks[m] for m in ("coarse", "medium", "fine") if m in peaks})
        if not verdict:
            continue
        study = {"peaks_N": peaks, "met": verdict[2]}
        figure = verdict[1]
        if len(peaks) == 3:
            rich = richardson(peaks["coarse"], peaks["medium"], peaks["fine"])
            if rich:
                study.update(rich)
                kind = ", ".join(k for k in ("oscillatory", "diverging") if rich[k])
                figure += (f"; observed order {rich['order']:.2f}{f' ({kind})' if kind else ''}, "
                           f"GCI {rich['gci_fine']:.1%}, extrapolated {rich['extrapolated'] / 1000:.2f} kN")
        mesh_studies[family] = study
        rows.append((verdict[0], figure, verdict[2]))
    if rows:
        print_verdicts([("meshes", rows)])


mesh_studies = {}


def judge(title, runs_, verdicts):
    """Each run's verdicts: printed under `title` and kept in the report (summary.json's targets)."""
    print(title)
    rows = [(r, verdicts(report[r])) for r in runs_]
    for r, v in rows:
        report[r]["targets"] = [{"target": n, "figure": f, "met": m} for n, f, m in v]
    print_verdicts(rows)


def print_verdicts(rows):
    for run, verdicts in rows:
        for name, figure, met in verdicts:
            print(f"- {run}: {name}: **{'met' if met else 'not met'}** ({figure})")
    print()


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
    judge("DEN 4b targets (docs/validation.md):", den, den_verdicts)
    meshes("den", den)
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
    print()
    judge("L-panel targets (docs/validation.md):", lp, lpanel_verdicts)
    meshes("lpanel", lp)
report["mesh_studies"] = mesh_studies
json.dump(report, open(os.path.join(out, "summary.json"), "w"), indent=1)  # once, with the targets


# The rows of docs/validation.md that this report generates, in the docs' own columns: OUT/docs-rows.md
# holds them for pasting, and scripts/validation/check_doc_rows.py holds the docs to them. Each
# entry: run, its comparison file, the table's columns, the row's label cells (as in the docs).
DEN_RESULTS = ["peak_kN", "ratio", "delta_at_peak", "post_peak_den", "work_den", "slope_den", "dissipated"]
DEN_MESH = ["peak_kN", "ratio", "delta_at_peak", "post_peak_den", "work_den", "dissipated"]
LPANEL = ["peak_kN", "u_at_peak", "inside", "post_peak_lpanel", "work_lpanel", "slope_lpanel", "dissipated"]
DOC_ROWS = [
    # Section 1, the coarse DEN (`validate.sh DIR quick`): the gap from the paper's scene to the validation scene.
    ("den-today-coarse", "compare.json", DEN_RESULTS, ["today's scene (`data/den/den-4b-coarse.yaml`), paper's law, free rule, delta = top edge"]),
    ("den-rig-coarse-paper-law-free", "compare-platen.json", DEN_RESULTS, ["rig, paper's law, free rule, delta = the frame's travel"]),
    ("den-rig-coarse-paper-law-free", "compare.json", DEN_RESULTS, ["rig, paper's law, free rule, delta = gauges"]),
    ("den-rig-coarse-one-band-free", "compare.json", DEN_RESULTS, ["rig, Hordijk's law, gauges, free rule (the validation scene until 2026-12-07)"]),
    ("den-rig-coarse-free", "compare.json", DEN_RESULTS, ["the same, second band"]),
    ("den-rig-coarse", "compare.json", DEN_RESULTS, ["the same, tracked crack paths (**the validation scene**, explicit)"]),
    ("den-rig-coarse-implicit", "compare.json", DEN_RESULTS, ["the same, implicit (rate-free)"]),
    ("den-rig-coarse-one-band", "compare.json", DEN_RESULTS, ["the validation scene with one band, explicit"]),
    # Section 1, the DEN's meshes, tracked (`validate.sh DIR quick medium fine`).
    ("den-rig-coarse", "compare.json", DEN_MESH, ["coarse (2.5 mm)", "explicit, second band"]),
    ("den-rig-coarse-implicit", "compare.json", DEN_MESH, ["coarse", "implicit, second band"]),
    ("den-rig-coarse-one-band", "compare.json", DEN_MESH, ["coarse", "explicit, one band"]),
    ("den-rig-coarse-implicit-one-band", "compare.json", DEN_MESH, ["coarse", "implicit, one band"]),
    ("den-rig-medium", "compare.json", DEN_MESH, ["medium (1.25 mm)", "explicit, second band"]),
    ("den-rig-medium-implicit", "compare.json", DEN_MESH, ["medium", "implicit, second band"]),
    ("den-rig-medium-one-band", "compare.json", DEN_MESH, ["medium", "explicit, one band"]),
    ("den-rig-medium-implicit-one-band", "compare.json", DEN_MESH, ["medium", "implicit, one band"]),
    ("den-rig-fine", "compare.json", DEN_MESH, ["fine (0.625 mm)", "explicit, second band"]),
    ("den-rig-fine-implicit", "compare.json", DEN_MESH, ["fine", "implicit, second band"]),
    ("den-rig-fine-one-band", "compare.json", DEN_MESH, ["fine", "explicit, one band"]),
    # Section 2, the L-panel, tracked.
    ("lpanel-coarse", "compare.json", LPANEL, ["coarse (10 mm), explicit (**the validation scene**)"]),
    ("lpanel-coarse-implicit", "compare.json", LPANEL, ["coarse, implicit"]),
    ("lpanel-medium", "compare.json", LPANEL, ["medium (5 mm), explicit"]),
    ("lpanel-medium-implicit", "compare.json", LPANEL, ["medium, implicit"]),
    ("lpanel-fine", "compare.json", LPANEL, ["fine (2.5 mm), explicit"]),
    ("lpanel-fine-implicit", "compare.json", LPANEL, ["fine, implicit"]),
    ("lpanel-coarse-one-band", "compare.json", LPANEL, ["coarse, explicit, one band"]),
    ("lpanel-coarse-implicit-one-band", "compare.json", LPANEL, ["coarse, implicit, one band"]),
    ("lpanel-medium-one-band", "compare.json", LPANEL, ["medium, explicit, one band"]),
    ("lpanel-medium-implicit-one-band", "compare.json", LPANEL, ["medium, implicit, one band"]),
    ("lpanel-fine-one-band", "compare.json", LPANEL, ["fine, explicit, one band"]),
    ("lpanel-coarse-paper-n", "compare.json", LPANEL, ["coarse, explicit, one band, the paper's n = 0.128"]),
    # "Before tracking" (`validate.sh DIR free`): the tables of sections 1 and 2 as the free rule gave them.
    ("den-rig-coarse-one-band-free", "compare.json", DEN_MESH, ["free: coarse (2.5 mm)", "explicit, one band"]),
    ("den-rig-coarse-implicit-one-band-free", "compare.json", DEN_MESH, ["free: coarse", "implicit, one band"]),
    ("den-rig-coarse-free", "compare.json", DEN_MESH, ["free: coarse", "explicit, second band"]),
    ("den-rig-coarse-implicit-free", "compare.json", DEN_MESH, ["free: coarse", "implicit, second band"]),
    ("den-rig-medium-one-band-free", "compare.json", DEN_MESH, ["free: medium (1.25 mm)", "explicit, one band"]),
    ("den-rig-medium-implicit-one-band-free", "compare.json", DEN_MESH, ["free: medium", "implicit, one band"]),
    ("den-rig-medium-free", "compare.json", DEN_MESH, ["free: medium", "explicit, second band"]),
    ("den-rig-fine-one-band-free", "compare.json", DEN_MESH, ["free: fine (0.625 mm)", "explicit, one band"]),
    ("den-rig-fine-free", "compare.json", DEN_MESH, ["free: fine", "explicit, second band"]),
    ("lpanel-coarse-one-band-free", "compare.json", LPANEL, ["free: coarse (10 mm), explicit"]),
    ("lpanel-coarse-implicit-one-band-free", "compare.json", LPANEL, ["free: coarse, implicit"]),
    ("lpanel-coarse-paper-n-free", "compare.json", LPANEL, ["free: coarse, explicit, the paper's n = 0.128"]),
    ("lpanel-coarse-free", "compare.json", LPANEL, ["free: coarse, explicit, **second band**"]),
    ("lpanel-medium-one-band-free", "compare.json", LPANEL, ["free: medium (5 mm), explicit"]),
    ("lpanel-medium-free", "compare.json", LPANEL, ["free: medium, explicit, **second band**"]),
    ("lpanel-fine-one-band-free", "compare.json", LPANEL, ["free: fine (2.5 mm), explicit"]),
    ("lpanel-medium-implicit-one-band-free", "compare.json", LPANEL, ["free: medium, **implicit** (rate-free)"]),
    ("lpanel-fine-free", "compare.json", LPANEL, ["free: fine, explicit, **second band**"]),
    ("lpanel-coarse-implicit-free", "compare.json", LPANEL, ["free: coarse, **implicit, second band**"]),
    ("lpanel-medium-implicit-free", "compare.json", LPANEL, ["free: medium, **implicit, second band**"]),
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


def y_range(runs_, xcol, ycol, xmax, test_values):
    """[low:high] in kN fitted to what the plot shows: the runs' rows with 0 <= x <= xmax and the
    tests' values, with 0 always in it and a margin of 8 %."""
    ys = list(test_values)
    for r in runs_:
        with open(f"{out}/{r}/compare.csv") as f:
            next(f)
            for line in f:
                cells = line.strip().split(",")
                try:
                    x, y = float(cells[xcol - 1]), float(cells[ycol - 1]) / 1000
                except (ValueError, IndexError):
                    continue
                if 0 <= x <= xmax:
                    ys.append(y)
    low, high = min(ys + [0.0]), max(ys + [0.0])
    pad = 0.08 * (high - low or 1.0)
    return f"[{low - pad if low < 0 else 0}:{high + pad}]"


def last_row(r, xcol, ycol):
    with open(f"{out}/{r}/compare.csv") as f:
        rows = [l.strip().split(",") for l in f][1:]
    return float(rows[-1][xcol - 1]), float(rows[-1][ycol - 1]) / 1000


def plot(name, test_cmd, runs_, xcol, ycol, xlabel, ylabel, xmax, measures, test_values):
    """The tests (black and gray) and one coloured curve per run, its legend naming what it
    measures; a run that did not complete ends in a cross where it stopped. The key sits below
    the axes, where it hides no curve."""
    if not runs_:
        return
    lines = ["set terminal pngcairo size 1000,760", f"set output '{out}/{name}.png'", "set datafile separator ','",
             f"set xlabel '{xlabel}'", f"set ylabel '{ylabel}'", f"set xrange [0:{xmax}]",
             f"set yrange {y_range(runs_, xcol, ycol, xmax, test_values)}", "set key below noenhanced",
             "set grid"]
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22",
               "#7f7fff", "#ff7fbf", "#7fbf7f"]  # no black or gray: those are the tests'
    series = list(test_cmd)
    for i, r in enumerate(runs_):
        colour = colours[i % len(colours)]
        title = f"{r} ({measures(r)})"
        status = report[r]["status"]
        if status != "completed":
            title += f", {status} at {last_row(r, xcol, ycol)[0]:.3f} mm"
        series.append(f"'{out}/{r}/compare.csv' every ::1 using {xcol}:(${ycol}/1000) with lines lw 2 lc rgb '{colour}' title \"{title}\"")
        if status != "completed":
            x, y = last_row(r, xcol, ycol)
            series.append(f"'+' using ({x}):({y}) every ::0::0 with points pt 2 ps 3 lw 3 lc rgb '{colour}' notitle")
    lines.append("plot " + ", \\\n     ".join(series))
    script = "\n".join(lines) + "\n"
    with open(f"{out}/{name}.gp", "w") as f:  # beside the PNG, to tweak and rerun by hand
        f.write(script)
    subprocess.run(["gnuplot"], input=script, text=True, check=False)


# The DEN's test curve as CSV (the file is whitespace-separated).
test_4b = []
with open(os.path.join(out, "test-4b.csv"), "w") as f:
    for line in open("data/experiments/nooru-mohamed-4b.txt"):
        if line.strip() and not line.startswith("#"):
            f.write(",".join(line.split()) + "\n")
            test_4b.append(float(line.split()[1]) / 1000)
DELTA = {"gauges": "delta: the gauges, as the test", "platen": "delta: the frame's travel", "top": "delta: the top edge"}
plot("den", [f"'{out}/test-4b.csv' using 1:($2/1000) with linespoints lw 3 lc rgb 'black' pt 7 title 'test (Nooru-Mohamed 4b; delta: gauges)'"],
     den, 1, 2, "delta (mm)", "P (kN)", 0.1, lambda r: DELTA.get(report[r]["delta_measured_by"], report[r]["delta_measured_by"]),
     test_4b)
envelope = [float(v) for line in open("data/experiments/winkler-lpanel-envelope.csv")
            if line.strip() and not line.startswith("#") and line[0].isdigit() for v in line.split(",")[1:3]]
plot("lpanel", ["'data/experiments/winkler-lpanel-envelope.csv' every ::1 using 1:2 with lines lw 3 lc rgb 'gray' title 'test envelope (lower)'",
                "'data/experiments/winkler-lpanel-envelope.csv' every ::1 using 1:3 with lines lw 3 lc rgb 'gray' title 'test envelope (upper)'",
                "'data/experiments/winkler-lpanel-series-a.csv' using 1:($2/1000) with lines lw 2 lc rgb 'black' title 'test series A'"],
     lp, 1, 2, "load-point displacement u (mm)", "F (kN)", 1.0, lambda r: "F, u: the load platen's", envelope)
