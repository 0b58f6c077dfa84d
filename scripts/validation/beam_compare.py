#!/usr/bin/env python3
"""The notched beam's runs against the cohesive reference and the test (docs/validation.md, "3.").

Usage: beam_compare.py OUT_DIR RUN...   (each RUN a folder of ecm-mpm's output under OUT_DIR)
Writes OUT_DIR/beam.csv (one row per run), OUT_DIR/beam.json and OUT_DIR/beam.gp (gnuplot: beam.png
with the runs, the reference and the test's envelope); prints the table. Units: mm, N.
The measures: peak; P at CMOD 0.1 and 0.2 mm; max dP, the largest |P - P_ref| over CMOD 0.002 to
0.2 mm (every 0.002 mm) over the reference's peak; the dissipation at CMOD 0.2 mm against the
reference's 71.76 N mm (ecm-cohesive data/reference/beam-band-node.yaml --cell 0.625). The peak and
max dP are also given against the reference with the traction-opening curve of one enriched point
in uniaxial stress (data/reference/beam-point-node.csv: "pt").
"""
import csv
import json
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
REFERENCE = os.path.join(ROOT, "data", "reference", "beam-band-node.csv")
TEST = os.path.join(ROOT, "data", "experiments", "gregoire-2013-half-notched-d50.csv")
POINT_REFERENCE = os.path.join(ROOT, "data", "reference", "beam-point-node.csv")
REFERENCE_DISSIPATION = 71.76  # N mm at CMOD 0.2 mm


def numeric_rows(path):
    with open(path) as f:
        return [[float(v) for v in line.split(",")] for line in f if line[:1].isdigit()]


def at(xs, ys, x):
    for i in range(1, len(xs)):
        if xs[i] >= x:
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return None


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, runs = sys.argv[1], sys.argv[2:]
    ref = numeric_rows(REFERENCE)
    rc, rp = [r[0] for r in ref], [r[1] for r in ref]
    peak_ref = max(rp)
    pt = numeric_rows(POINT_REFERENCE)
    pc, pp = [r[0] for r in pt], [r[1] for r in pt]
    peak_pt = max(pp)
    results = []
    for run in runs:
        path = os.path.join(out, run, "history.csv")
        if not os.path.exists(path):
            results.append({"run": run, "status": "missing"})
            continue
        with open(path) as f:
            rows = list(csv.DictReader(f))
        c = [float(r["cmod_mm"]) for r in rows]
        p = [-float(r["load_Fy_N"]) for r in rows]
        d = [float(r["dissipated_Nmm"]) for r in rows]
        gaps = [abs(at(c, p, x) - at(rc, rp, x)) for x in [0.002 * k for k in range(1, 101)] if at(c, p, x) is not None]
        gaps_pt = [abs(at(c, p, x) - at(pc, pp, x)) for x in [0.002 * k for k in range(1, 101)] if at(c, p, x) is not None]
        dissipated = at(c, d, 0.2)
        results.append({
            "run": run, "status": "ok", "peak_N": max(p), "peak_vs_reference": max(p) / peak_ref - 1.0,
            "P_at_0.1_N": at(c, p, 0.1), "P_at_0.2_N": at(c, p, 0.2),
            "max_dP_share": max(gaps) / peak_ref if gaps else None,
            "peak_vs_point_reference": max(p) / peak_pt - 1.0,
            "max_dP_share_point_reference": max(gaps_pt) / peak_pt if gaps_pt else None,
            "dissipated_at_0.2_Nmm": dissipated,
            "dissipated_vs_reference": dissipated / REFERENCE_DISSIPATION - 1.0 if dissipated else None,
        })
    with open(os.path.join(out, "beam.json"), "w") as f:
        json.dump({"reference_peak_N": peak_ref, "point_reference_peak_N": peak_pt, "runs": results}, f, indent=2)
    fields = ["run", "status", "peak_N", "peak_vs_reference", "P_at_0.1_N", "P_at_0.2_N", "max_dP_share",
              "dissipated_at_0.2_Nmm", "dissipated_vs_reference", "peak_vs_point_reference", "max_dP_share_point_reference"]
    with open(os.path.join(out, "beam.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in results:
            w.writerow(r)
    print("%-28s %8s %8s %8s %8s %8s %8s %8s %8s" % ("run", "peak", "vs ref", "P(0.1)", "P(0.2)", "max dP", "D(0.2)",
                                                     "vs pt", "dP pt"))
    print("%-28s %8.0f %8s %8.0f %8.0f" % ("reference (cohesive)", peak_ref, "", at(rc, rp, 0.1), at(rc, rp, 0.2)))
    print("%-28s %8.0f %8s %8.0f %8.0f" % ("reference, point law (pt)", peak_pt, "", at(pc, pp, 0.1), at(pc, pp, 0.2)))
    for r in results:
        if r["status"] != "ok":
            print("%-28s %s" % (r["run"], r["status"]))
            continue
        print("%-28s %8.0f %+7.1f%% %8.0f %8.0f %7.1f%% %8.1f %+7.1f%% %7.1f%%" % (
            r["run"], r["peak_N"], 100 * r["peak_vs_reference"], r["P_at_0.1_N"] or 0, r["P_at_0.2_N"] or 0,
            100 * (r["max_dP_share"] or 0), r["dissipated_at_0.2_Nmm"] or 0, 100 * r["peak_vs_point_reference"],
            100 * (r["max_dP_share_point_reference"] or 0)))
    plots = ["'%s' every ::9 using 1:2:3 with filledcurves lc rgb '#dddddd' title 'test (envelope)'" % TEST,
             "'%s' using 1:2 with lines lw 2 lc rgb 'black' title 'cohesive reference'" % REFERENCE,
             "'%s' using 1:2 with lines lw 1 dt 2 lc rgb 'black' title 'cohesive, with the point law'" % POINT_REFERENCE]
    for r in results:
        if r["status"] == "ok":
            plots.append("'%s' using 'cmod_mm':(-column('load_Fy_N')) with lines title '%s'" % (
                os.path.join(out, r["run"], "history.csv"), r["run"]))
    with open(os.path.join(out, "beam.gp"), "w") as f:
        f.write("set terminal pngcairo size 900,600\nset output '%s'\n" % os.path.join(out, "beam.png"))
        f.write("set datafile separator ','\nset xlabel 'CMOD (mm)'\nset ylabel 'P (N)'\nset xrange [0:0.3]\n")
        f.write("set yrange [0:*]\nset key top right\nset title 'Notched beam (Gregoire et al. 2013, D = 50 mm)'\n")
        f.write("plot " + ", \\\n     ".join(plots) + "\n")
    return 1 if any(r["status"] != "ok" for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())
