#!/usr/bin/env bash
# The coarse DEN's and L-panel's rows of docs/validation.md against a rerun (scripts/validate.sh
# den-rig-coarse lpanel-coarse, about 30 s on 2 threads): a documented figure that moved fails the
# test. Tolerance: half a unit of the table's last digit, plus 0.2 % of the value (a compiler's
# contraction of a multiply-add moves the last digits of an explicit run, not its figures).
# Usage: validation_rows_check.sh SOURCE_DIR VALIDATE_SH OUT_DIR
set -u
source=$1 validate=$2 out=$3
rm -rf "$out"
"$validate" "$out" den-rig-coarse lpanel-coarse > "$out.log" 2>&1 || { echo "FAIL: validate.sh failed"; cat "$out.log"; exit 1; }
python3 - "$source/docs/validation.md" "$out/summary.json" <<'PY'
import json, re, sys
doc, summary = open(sys.argv[1]).read().splitlines(), json.load(open(sys.argv[2]))

def row(prefix):
    rows = [l for l in doc if l.startswith(prefix)]
    if len(rows) != 1:
        sys.exit(f"FAIL: docs/validation.md has {len(rows)} rows starting '{prefix}'")
    return [c.strip() for c in rows[0].strip().strip("|").split("|")]

def number(cell):
    m = re.match(r"[*]*([-0-9.]+)", cell)
    return m.group(1)

failed = []
def check(what, cell, value):
    text = number(cell)
    digits = len(text.split(".")[1]) if "." in text else 0
    documented = float(text)
    tolerance = 0.5 * 10 ** -digits + 2e-3 * abs(documented)
    verdict = "ok" if abs(value - documented) <= tolerance else "MOVED"
    print(f"{what:44s} documented {text:>8s}  now {value:12.6g}  {verdict}")
    if verdict != "ok":
        failed.append(what)

# | coarse (2.5 mm) | explicit, one band | peak P (kN) | / test | delta at peak | post-peak distance | work | dissipated | wall |
d, den = row("| coarse (2.5 mm) | explicit, one band |"), summary["den-rig-coarse"]
check("DEN coarse: peak (kN)", d[2], den["peak_N"] / 1000)
check("DEN coarse: peak / test", d[3], den["peak_ratio"])
check("DEN coarse: delta at peak (mm)", d[4], den["delta_at_peak_mm"])
check("DEN coarse: post-peak distance", d[5], den["post_peak_distance"])
check("DEN coarse: work to 0.1 mm (N mm)", d[6], den["work_N_mm"])
check("DEN coarse: dissipated (N mm)", d[7], den["dissipated_N_mm"])
# | coarse (10 mm), explicit | peak F (kN) | u at peak | inside envelope | post-peak distance | work | slope | dissipated | wall |
l, lp = row("| coarse (10 mm), explicit |"), summary["lpanel-coarse"]
check("L-panel coarse: peak (kN)", l[1], lp["peak_N"] / 1000)
check("L-panel coarse: u at peak (mm)", l[2], lp["u_at_peak_mm"])
check("L-panel coarse: inside the envelope (%)", l[3], 100 * lp["inside_envelope_share"])
check("L-panel coarse: post-peak distance", l[4], lp["post_peak_distance_to_series_a"])
check("L-panel coarse: work to 1 mm (N mm)", l[5], lp["work_N_mm"])
check("L-panel coarse: elastic slope (kN/mm)", l[6], lp["initial_slope_kN_per_mm"])
check("L-panel coarse: dissipated (N mm)", l[7], lp["dissipated_N_mm"])
if failed:
    sys.exit("FAIL: documented figures moved: " + ", ".join(failed) + " (rerun, then update docs/validation.md)")
print("docs/validation.md: the coarse DEN's and L-panel's rows reproduce")
PY
