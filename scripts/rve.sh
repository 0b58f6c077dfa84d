#!/usr/bin/env bash
# The RVE of a cement-matrix composite (the paper's second example) on two meshes with ecm-mpm:
# macro stress-strain curves overlaid, the damage D at the states A (pre-peak), B (peak) and
# C (post-peak) and its increment since the previous state, per mesh, and a table.
# Run after the build (cmake -S . -B build -G Ninja && ninja -C build).
# Usage: scripts/rve.sh [OUT_DIR] [coarse|fine|xfine|all|MESH-second|second|report]...   (default: results/rve coarse)
# (xfine: the 0.0625 mm convergence check, 640k particles, ~20 minutes; `all` is coarse and fine;
# MESH-second: the scene of MESH with the second-band option on all three phases, written to
# OUT_DIR/scenes/ with its material files (docs/model.md, "A second band"); `second`: coarse and fine)
# The states are the scene's particle_snapshots (times in s, picked on the coarse curve: A at
# 84 % of the peak load before it, B at the peak, C at 58 % after it); ecm-mpm writes
# particles_t<time>.csv at each. Writes OUT_DIR/MESH/ (ecm-mpm's folder), OUT_DIR/stress_strain.png,
# OUT_DIR/damage_MESH_{A,B,C}.png, OUT_DIR/increment_MESH_{A,B,C}.png, OUT_DIR/summary.json and
# the table on stdout; exits 1 and lists the runs of this call that did not complete. Units: mm,
# N, MPa, t, s. Threads: $RVE_THREADS (default 2); binary:
# $RVE_BIN (default ./build/mpm/ecm-mpm). Shell, awk and gnuplot only.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/mpm_runs.sh  # failureKind, runStatus
out=${1:-results/rve}
shift || true
[[ $# -gt 0 ]] || set -- coarse
threads=${RVE_THREADS:-2}
bin=${RVE_BIN:-./build/mpm/ecm-mpm}
runs=()
for w in "$@"; do
  case "$w" in
    coarse | fine | xfine | coarse-second | fine-second | xfine-second) runs+=("$w") ;;
    all) runs+=(coarse fine) ;;
    second) runs+=(coarse-second fine-second) ;;
    report) ;;
    *) echo "usage: scripts/rve.sh [OUT_DIR] [coarse|fine|xfine|all|MESH-second|second|report]..." >&2; exit 2 ;;
  esac
done
[[ -x $bin ]] || { echo "error: $bin not built (cmake -S . -B build -G Ninja && ninja -C build)" >&2; exit 2; }
mkdir -p "$out"
side=25 thick=10  # mm: the sample (data/rve/rve-*.yaml)

# The scene of a run: data/rve/rve-MESH.yaml, or for MESH-second a copy next to copies of the
# three phases' material files with `second_band: orthogonal` (found first, beside the scene).
sceneOf() {
  local mesh=${1%-second}
  [[ $1 == *-second ]] || { echo "data/rve/rve-$1.yaml"; return; }
  mkdir -p "$out/scenes"
  for phase in matrix inclusion itz; do
    { cat "data/materials/rve-$phase.yaml"; echo "second_band: orthogonal   # off | orthogonal (docs/model.md)"; } \
      >"$out/scenes/rve-$phase.yaml"
  done
  sed -e "s|^name: rve-$mesh|name: rve-$1|" "data/rve/rve-$mesh.yaml" >"$out/scenes/rve-$1.yaml"
  echo "$out/scenes/rve-$1.yaml"
}

failed=()  # the runs of this call that did not complete (listed at the end; the exit status is 1)
for m in "${runs[@]}"; do
  scene=$(sceneOf "$m")
  echo "== RVE $m: $scene" >&2
  rm -f "$out/$m"/{history.csv,summary.json,particles_*.csv}
  $bin "$scene" --out "$out/$m" --no-vtu --threads "$threads" -q
  rc=$?
  runStatus "$rc" "$scene" "$out/$m"
  [[ $rc == 0 ]] || failed+=("$m (exit $rc$(failureKind "$out/$m"): $out/$m/summary.json)")
done

col() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }
jnum() { grep -m1 "\"$2\"" "$1" | sed 's/.*: *//; s/[",]//g'; }

rows=()
for m in coarse fine xfine coarse-second fine-second xfine-second; do
  dir=$out/$m
  [[ -f $dir/summary.json ]] || continue
  h=$dir/history.csv
  cu=$(col "$h" top_uy_mm) cr=$(col "$h" top_ry_N)
  read -r peak epeak <<<"$(awk -F, -v u="$cu" -v r="$cr" -v a="$side" -v t="$thick" '
    NR > 1 { s = $r / (a * t); if (s > p) { p = s; e = $u / a } } END { printf "%.6g %.6g\n", p, e }' "$h")"
  # The states: particles_t<time>.csv in time order, labelled A, B, C.
  snaps=($(cd "$dir" && ls particles_t*.csv 2>/dev/null | sed 's/particles_t//; s/\.csv$//' | sort -g))
  labels=(A B C D E F)
  states=""
  prev=""
  ps=$(case $m in coarse*) echo 0.22 ;; fine*) echo 0.11 ;; xfine*) echo 0.055 ;; esac)
  for k in "${!snaps[@]}"; do
    t=${snaps[$k]} l=${labels[$k]}
    f=$m/particles_t$t.csv
    # The mean stress at that time (history row nearest in time) relative to the peak.
    s=$(awk -F, -v u="$cu" -v r="$cr" -v t="$t" -v a="$side" -v th="$thick" '
      NR > 1 { d = $1 - t; if (d < 0) d = -d; if (!n || d < best) { best = d; s = $r / (a * th); n = 1 } } END { printf "%.4g", s }' "$h")
    states="$states $l:$t:$s"
    cat >"$out/damage_${m}_$l.gp" <<GP
# Redraw: cd $(realpath "$out") && gnuplot damage_${m}_$l.gp
set terminal pngcairo size 760,720 enhanced font 'Sans,11'
set output 'damage_${m}_$l.png'
set datafile separator ','
set size ratio -1; set xrange [0:$side]; set yrange [0:$side]
set cbrange [0:1]; set cblabel 'damage D'
set palette defined (0 '#f2f2f2', 0.3 '#9ecae1', 0.7 '#de2d26', 1 '#67000d')
set title 'RVE $m, state $l (t = $t s, mean stress $s MPa, peak $(printf %.3g "$peak")): damage D'
set xlabel 'x (mm)'; set ylabel 'y (mm)'
plot '$f' every ::1 using 1:2:3 with points pt 5 ps $ps lc palette notitle
GP
    # The increment of D since the previous state (since the start for A): paste joins the rows
    # of the same particle (same order in every snapshot).
    if [[ -n $prev ]]; then
      paste -d, "$out/$f" "$out/$prev" | awk -F, 'NR > 1 { print $1 "," $2 "," ($3 - $8) }' >"$out/increment_${m}_$l.csv"
    else
      awk -F, 'NR > 1 { print $1 "," $2 "," $3 }' "$out/$f" >"$out/increment_${m}_$l.csv"
    fi
    cat >"$out/increment_${m}_$l.gp" <<GP
# Redraw: cd $(realpath "$out") && gnuplot increment_${m}_$l.gp
set terminal pngcairo size 760,720 enhanced font 'Sans,11'
set output 'increment_${m}_$l.png'
set datafile separator ','
set size ratio -1; set xrange [0:$side]; set yrange [0:$side]
set cbrange [0:1]; set cblabel 'increment of D'
set palette defined (0 '#f7f7f7', 0.05 '#c6dbef', 0.4 '#6baed6', 1 '#08306b')
set title 'RVE $m, state $l: damage growth since $([[ -n $prev ]] && echo "the previous state" || echo "the start")'
set xlabel 'x (mm)'; set ylabel 'y (mm)'
plot 'increment_${m}_$l.csv' using 1:2:3 with points pt 5 ps $ps lc palette notitle
GP
    (cd "$out" && gnuplot "damage_${m}_$l.gp" && gnuplot "increment_${m}_$l.gp") || echo "warning: maps of $m $l not drawn" >&2
    prev=$f
  done
  rows+=("$m $(jnum "$dir/summary.json" status) $peak $epeak $(jnum "$dir/summary.json" dissipated) $(jnum "$dir/summary.json" wall_time_s) $(jnum "$dir/summary.json" particles) $(jnum "$dir/summary.json" snap_back_releases) ${states# }")
done
[[ ${#rows[@]} -gt 0 ]] || { echo "error: no run produced output" >&2; exit 1; }

# Macro stress-strain curves overlaid.
{
  echo "# Redraw: cd $(realpath "$out") && gnuplot stress_strain.gp"
  echo "set terminal pngcairo size 900,600 enhanced font 'Sans,11'"
  echo "set output 'stress_strain.png'"
  echo "set datafile separator ','"
  echo "set grid; set key top right"
  echo "set title 'RVE 25 x 25 mm in uniaxial tension: mean stress against mean strain'"
  echo "set xlabel 'mean strain (-)'; set ylabel 'mean stress (MPa)'"
  printf "plot "
  sep=""
  for r in "${rows[@]}"; do
    set -- $r
    h=$out/$1/history.csv
    printf "%s'%s/history.csv' every ::1 using (\$%s / %s):(\$%s / %s) with lines lw 2 title '%s (%s)'" "$sep" "$1" "$(col "$h" top_uy_mm)" "$side" "$(col "$h" top_ry_N)" "$((side * thick))" "$1" "$2"
    sep=", \\"$'\n'"     "
  done
  echo
} >"$out/stress_strain.gp"
(cd "$out" && gnuplot stress_strain.gp) || echo "warning: stress-strain plot not drawn" >&2

# Table and summary.json.
{
  echo "{"
  echo "  \"units\": \"mm, N, MPa, t, s\","
  echo "  \"meshes\": {"
  for i in "${!rows[@]}"; do
    set -- ${rows[$i]}
    sep=$([[ $i -lt $((${#rows[@]} - 1)) ]] && echo "," || echo "")
    st=""
    for s in "${@:9}"; do IFS=: read -r l t v <<<"$s"; st="$st${st:+, }\"$l\": {\"time_s\": $t, \"mean_stress_MPa\": $v}"; done
    printf '    "%s": {"status": "%s", "peak_mean_stress_MPa": %s, "strain_at_peak": %s, "dissipated_Nmm": %s, "wall_time_s": %s, "particles": %s, "snap_back_releases": %s, "states": {%s}}%s\n' \
      "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$8" "$st" "$sep"
  done
  echo "  }"
  echo "}"
} >"$out/summary.json"
printf "\n%-7s %-10s %12s %12s %12s %9s %9s %9s  %s\n" mesh status "peak (MPa)" "strain pk" "dissip(Nmm)" "time(s)" particles releases "states (label:time s:mean stress MPa)"
for r in "${rows[@]}"; do
  set -- $r
  printf "%-7s %-10s %12.4f %12.4g %12.4g %9.1f %9s %9s  %s\n" "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$8" "${*:9}"
done
# The peak of each finer mesh against the one before it; with three meshes (halving the cell
# each time) also the observed order of convergence p = log2(e1 / e2) and the extrapolated peak
# P_fine + (P_fine - P_coarse) / (2^p - 1) (Richardson).
for ((i = 1; i < ${#rows[@]}; ++i)); do
  # (only meshes of the same model: with or without the second band; and each model against
  # the other on the same mesh)
  a=$(set -- ${rows[$((i - 1))]}; echo "$1") b=$(set -- ${rows[$i]}; echo "$1")
  if [[ $a == *-second && $b != *-second ]] || [[ $a != *-second && $b == *-second ]]; then continue; fi
  awk -v na="$(set -- ${rows[$((i - 1))]}; echo "$1")" -v a="$(set -- ${rows[$((i - 1))]}; echo "$3")" \
      -v nb="$(set -- ${rows[$i]}; echo "$1")" -v b="$(set -- ${rows[$i]}; echo "$3")" \
      'BEGIN { printf "peak mean stress, %s against %s: %+.2f %%\n", nb, na, 100 * (b - a) / a }'
done
for r in "${rows[@]}"; do
  set -- $r
  [[ $1 == *-second ]] || continue
  for q in "${rows[@]}"; do
    [[ $(set -- $q; echo "$1") == "${1%-second}" ]] || continue
    awk -v n="$1" -v a="$(set -- $q; echo "$3")" -v b="$3" \
      'BEGIN { printf "peak mean stress, %s against the one-band model: %+.2f %%\n", n, 100 * (b - a) / a }'
  done
done
if [[ ${#rows[@]} -eq 3 && " ${rows[*]} " != *-second* ]]; then
  awk -v a="$(set -- ${rows[0]}; echo "$3")" -v b="$(set -- ${rows[1]}; echo "$3")" -v c="$(set -- ${rows[2]}; echo "$3")" 'BEGIN {
    if ((a - b) * (b - c) > 0) { p = log((a - b) / (b - c)) / log(2); x = c + (c - b) / (2 ^ p - 1)
      printf "observed order of convergence %.2f, extrapolated peak %.4f MPa (finest mesh %+.2f %% from it)\n", p, x, 100 * (c - x) / x }
    else print "no monotone convergence of the peak over the three meshes" }'
fi
echo "written: $out/summary.json $out/stress_strain.png $(cd "$out" && ls damage_*.png increment_*.png 2>/dev/null | sed "s|^|$out/|" | tr '\n' ' ')"
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "failed runs (kept in the table with their status):" >&2
  printf '  %s\n' "${failed[@]}" >&2
  exit 1
fi
