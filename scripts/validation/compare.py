#!/usr/bin/env python3
"""Compare an ecm-mpm run with a digitised test curve (docs/validation.md).

compare.py den RUN_DIR TEST_FILE [--t0 T] [--delta gauges|platen|top]
                                      the DEN: P = the upper frame's y force (N) (or the top edge's
                                      reaction) against delta = the mean of the gauges delta-left and
                                      delta-right (or the upper frame's or the top edge's travel)
                                      (mm), zeroed at the first row at t >= T (the tension's start)
compare.py lpanel RUN_DIR ENVELOPE SERIES_A
                                      the L-panel: F = the load platen's y force against its y
                                      displacement (mm)
Prints one JSON object: the peak, the displacement at the peak, the post-peak distance (the largest
|P - P_test| over the compared range, as a fraction of the test's peak), the work of the load over
the compared range (N mm), the share of the L-panel curve inside the envelope, the elastic slope
(a line through the rising branch up to 40 % of the peak, for ecm and the test alike),
and writes
RUN_DIR/compare.csv (displacement, ecm force, test force(s)) for the plots. Units: mm, N.
"""
import csv
import json
import sys


def read_history(run_dir):
    with open(f"{run_dir}/history.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def read_table(path, skip_header_row=False):
    pts = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            parts = line.replace(",", " ").split()
            try:
                pts.append([float(p) for p in parts])
            except ValueError:
                continue  # a header row
    return pts


def interp(xs, ys, x):
    """Linear interpolation on increasing xs; None outside."""
    if x < xs[0] or x > xs[-1]:
        return None
    for i in range(1, len(xs)):
        if x <= xs[i]:
            if xs[i] == xs[i - 1]:
                return ys[i]
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return ys[-1]


def work(xs, ys, upto):
    w = 0.0
    for i in range(1, len(xs)):
        if xs[i - 1] >= upto:
            break
        x1 = min(xs[i], upto)
        y1 = ys[i] if xs[i] <= upto else interp(xs, ys, upto)
        w += 0.5 * (ys[i - 1] + y1) * (x1 - xs[i - 1])
    return w


def elastic_slope(xs, ys):
    """The slope of the rising branch: a least-squares line through the points before the peak whose
    load is at most 40 % of the peak (the elastic part)."""
    top = max(range(len(ys)), key=lambda k: ys[k])
    pts = [(x, y) for x, y in zip(xs[:top + 1], ys[:top + 1]) if 0.0 <= y <= 0.4 * ys[top]]
    if len(pts) < 2:
        return None
    n = len(pts)
    mx, my = sum(p[0] for p in pts) / n, sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else None


def monotone_envelope(xs, ys):
    """The curve as a function of a displacement that may go back (snap-back): keep the points whose
    displacement exceeds every earlier one (the curve a displacement-controlled test would record)."""
    ox, oy, top = [], [], -1e300
    for x, y in zip(xs, ys):
        if x > top:
            ox.append(x), oy.append(y)
            top = x
    return ox, oy


def den(run_dir, test_file, t0, delta_kind):
    h = read_history(run_dir)
    start = next(i for i, t in enumerate(h["time_s"]) if t >= t0 - 1e-12)
    if delta_kind == "gauges":
        d = [0.5 * (a + b) for a, b in zip(h["delta-left_mm"], h["delta-right_mm"])]
    elif delta_kind == "platen":  # the upper frame's travel
        d = h["upper-frame_uy_mm"]
    else:  # a scene without a rig (data/den): the top edge's displacement
        d = h["top_uy_mm"]
    p = h["upper-frame_Fy_N"] if "upper-frame_Fy_N" in h else h["top_ry_N"]
    d = [x - d[start] for x in d[start:]]
    p = p[start:]
    test = read_table(test_file)
    tx, ty = [r[0] for r in test], [r[1] for r in test]
    i = max(range(len(p)), key=lambda k: p[k])
    ti = max(range(len(ty)), key=lambda k: ty[k])
    mx, my = monotone_envelope(d, p)
    upto = min(0.1, tx[-1], mx[-1])
    post = [abs(interp(mx, my, x) - y) for x, y in zip(tx, ty) if tx[ti] <= x <= upto]
    with open(f"{run_dir}/compare.csv", "w") as f:
        f.write("delta_mm,P_ecm_N,P_test_N\n")
        for x, y in zip(d, p):
            t = interp(tx, ty, x)
            f.write(f"{x},{y},{'' if t is None else t}\n")
    return {
        "delta_measured_by": delta_kind,
        "peak_N": p[i], "delta_at_peak_mm": d[i],
        "test_peak_N": ty[ti], "test_delta_at_peak_mm": tx[ti],
        "peak_ratio": p[i] / ty[ti],
        "post_peak_distance": max(post) / ty[ti] if post else None,
        "compared_up_to_mm": upto,
        "work_N_mm": work(mx, my, upto), "test_work_N_mm": work(tx, ty, upto),
        "initial_slope_kN_per_um": (lambda k: None if k is None else k / 1e6)(elastic_slope(d, p)),
        "test_initial_slope_kN_per_um": (lambda k: None if k is None else k / 1e6)(elastic_slope(tx, ty)),
    }


def lpanel(run_dir, envelope_file, series_file):
    h = read_history(run_dir)
    u, f = h["load-plate_uy_mm"], h["load-plate_Fy_N"]
    env = read_table(envelope_file)
    ex, lo, hi = [r[0] for r in env], [1000 * r[1] for r in env], [1000 * r[2] for r in env]
    ser = read_table(series_file)
    sx, sy = [r[0] for r in ser], [r[1] for r in ser]
    i = max(range(len(f)), key=lambda k: f[k])
    mx, my = monotone_envelope(u, f)
    upto = min(1.0, mx[-1])
    # The share of 0..upto (sampled every 0.005 mm) where the curve lies inside the envelope.
    inside = total = 0
    x = 0.005
    while x <= upto + 1e-12:
        y, a, b = interp(mx, my, x), interp(ex, lo, x), interp(ex, hi, x)
        if None not in (y, a, b):
            total += 1
            inside += 1 if a <= y <= b else 0
        x += 0.005
    si = max(range(len(sy)), key=lambda k: sy[k])
    post = [abs(interp(mx, my, x) - y) for x, y in zip(sx, sy) if sx[si] <= x <= upto and interp(mx, my, x) is not None]
    with open(f"{run_dir}/compare.csv", "w") as fo:
        fo.write("u_mm,F_ecm_N,F_lower_N,F_upper_N,F_seriesA_N\n")
        for x, y in zip(u, f):
            a, b, c = interp(ex, lo, x), interp(ex, hi, x), interp(sx, sy, x)
            fo.write(",".join(str(v) if v is not None else "" for v in (x, y, a, b, c)) + "\n")
    return {
        "peak_N": f[i], "u_at_peak_mm": u[i],
        "envelope_peak_N": [max(lo), max(hi)], "series_a_peak_N": sy[si], "series_a_u_at_peak_mm": sx[si],
        "inside_envelope_share": inside / total if total else None, "compared_up_to_mm": upto,
        "post_peak_distance_to_series_a": max(post) / sy[si] if post else None,
        "work_N_mm": work(mx, my, upto), "series_a_work_N_mm": work(sx, sy, min(upto, sx[-1])),
        "initial_slope_kN_per_mm": (lambda k: None if k is None else k / 1000)(elastic_slope(u, f)),
        "series_a_initial_slope_kN_per_mm": (lambda k: None if k is None else k / 1000)(elastic_slope(sx, sy)),
    }


if __name__ == "__main__":
    args = sys.argv[1:]
    t0, delta_kind = 0.0, "gauges"
    if "--t0" in args:
        k = args.index("--t0")
        t0 = float(args[k + 1])
        del args[k:k + 2]
    if "--delta" in args:
        k = args.index("--delta")
        delta_kind = args[k + 1]
        del args[k:k + 2]
    if len(args) == 3 and args[0] == "den":
        out = den(args[1], args[2], t0, delta_kind)
    elif len(args) == 4 and args[0] == "lpanel":
        out = lpanel(args[1], args[2], args[3])
    else:
        sys.exit(__doc__)
    print(json.dumps(out, indent=1))
