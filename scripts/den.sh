#!/usr/bin/env bash
# Nooru-Mohamed's double-edge-notched (DEN) panel with ecm-mpm: load path 4b on three meshes with
# the enriched model, the rate check, load path 4a, and the contrast of the paper (the same
# meshes with an unregularised and a regularised smeared crack).
# Run after the build (cmake -S . -B build -G Ninja && ninja -C build).
# Usage: scripts/den.sh [OUT_DIR] [WHAT...]   (default: results/den coarse)
#   WHAT: coarse | medium | fine            enriched, load path 4b (P_s = 10 kN), data/den/den-4b-MESH.yaml
#         all                               the three enriched meshes
#         halfrate  (= coarse-halfrate)     coarse at half the loading rate (data/den/den-4b-coarse-halfrate.yaml)
#         quarterrate (= coarse-quarterrate) coarse at a quarter of it (data/den/den-4b-coarse-quarterrate.yaml)
#         4a-coarse                         load path 4a (P_s = 5 kN), coarse
#         MESH-smeared | MESH-crackband     the 4b scene of MESH with data/materials/den-concrete-smeared.yaml
#                                           (the band's law on the whole point) or den-concrete-crackband-MESH.yaml
#                                           (crack band: E_p from G_F / H); the scene is written to OUT_DIR/scenes/
#         contrast                          smeared and crackband on the three meshes
#         MESH-tail | tail                  the 4b scene of MESH pulled on to delta = 0.4 mm at the same
#                                           22.2 mm/s, ended by stop_when once P < 10 % of its peak
#                                           (the end criterion P < 0.1 P_peak of docs/den.md, "End of
#                                           the run"; the fine one runs ~25 minutes)
#         MESH-second | second               the 4b scene of MESH with the second-band option,
#                                           data/den/den-4b-MESH-second-band.yaml (docs/model.md)
#         MESH-second-tail | second-tail    the same pulled on as MESH-tail
#         report                            no run: only the tables and plots of what is in OUT_DIR
# Writes OUT_DIR/RUN/ (ecm-mpm's output folder per run, without VTU snapshots),
# OUT_DIR/load_displacement.png (P against delta, enriched runs), OUT_DIR/contrast.png (all models),
# OUT_DIR/damage_RUN.png, OUT_DIR/crack_RUN.png, OUT_DIR/summary.json and the table on stdout, for
# every run whose output is in OUT_DIR (run now or by an earlier call, so `den.sh DIR medium` adds
# to an earlier coarse run).
# Exits 1 and lists the runs of this call that did not complete (each kept in the table with its
# status). Units: mm, N, MPa, t, s. Threads: $DEN_THREADS (default 2); binary: $DEN_BIN (default ./build/mpm/ecm-mpm).
# Shell, awk and gnuplot only. A failed run (exit status 10-20) is kept in the table with its status.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/mpm_runs.sh  # failureKind, runStatus
out=${1:-results/den}
shift || true
[[ $# -gt 0 ]] || set -- coarse
threads=${DEN_THREADS:-2}
allRuns=(coarse medium fine coarse-halfrate coarse-quarterrate 4a-coarse coarse-smeared medium-smeared fine-smeared
         coarse-crackband medium-crackband fine-crackband coarse-tail medium-tail fine-tail
         coarse-second medium-second fine-second coarse-second-tail medium-second-tail fine-second-tail)
runs=()
for w in "$@"; do
  case "$w" in
    all) runs+=(coarse medium fine) ;;
    halfrate) runs+=(coarse-halfrate) ;;
    quarterrate) runs+=(coarse-quarterrate) ;;
    contrast) runs+=(coarse-smeared medium-smeared fine-smeared coarse-crackband medium-crackband fine-crackband) ;;
    tail) runs+=(coarse-tail medium-tail fine-tail) ;;
    second) runs+=(coarse-second medium-second fine-second) ;;
    second-tail) runs+=(coarse-second-tail medium-second-tail fine-second-tail) ;;
    report) ;;
    coarse | medium | fine | coarse-halfrate | coarse-quarterrate | 4a-coarse | *-smeared | *-crackband | *-tail | *-second)
      [[ " ${allRuns[*]} " == *" $w "* ]] || { echo "error: unknown run '$w'" >&2; exit 2; }
      runs+=("$w") ;;
    *) echo "usage: scripts/den.sh [OUT_DIR] [coarse|medium|fine|all|halfrate|quarterrate|4a-coarse|MESH-smeared|MESH-crackband|contrast|MESH-tail|tail|MESH-second|second|MESH-second-tail|second-tail|report]..." >&2; exit 2 ;;
  esac
done
bin=${DEN_BIN:-./build/mpm/ecm-mpm}
[[ -x $bin ]] || { echo "error: $bin not built (cmake -S . -B build -G Ninja && ninja -C build)" >&2; exit 2; }
mkdir -p "$out"

# The scene file of a run: committed in data/den, or a smeared variant written to OUT_DIR/scenes
# (the @material line of the 4b scene pointed at the other material file, by absolute path).
sceneOf() {
  local run=$1 mesh=${1%%-*} variant=${1#*-}
  case "$run" in
    coarse | medium | fine) echo "data/den/den-4b-$run.yaml" ;;
    coarse-halfrate | coarse-quarterrate) echo "data/den/den-4b-$run.yaml" ;;
    4a-coarse) echo "data/den/den-4a-coarse.yaml" ;;
    *-second) echo "data/den/den-4b-$mesh-second-band.yaml" ;;
    *-tail)
      # The time line's last segment (delta 0.032 mm at 3.44004e-3 s, 22.2 mm/s) extended to
      # 0.4 mm (2.000004e-2 s), the shear held to then, and the end criterion P < 0.1 P_peak
      # (docs/den.md) as stop_when.
      # (MESH-second-tail: the same from the second-band scene.)
      local base=data/den/den-4b-$mesh.yaml
      [[ $variant == second-tail ]] && base=data/den/den-4b-$mesh-second-band.yaml
      mkdir -p "$out/scenes"
      sed -e "/@material/ s|{file: ../materials/|{file: $(realpath data/materials)/|" \
          -e 's|^end_time: 0.00650004 |end_time: 0.02000004 |' \
          -e 's|\[0.00650004, 0.1\]\]|[0.02000004, 0.4]]|' -e 's|\[0.00650004, 1\]\]|[0.02000004, 1]]|' \
          -e "s|^name: den-4b-$mesh.*|name: den-4b-$run|" "$base" >"$out/scenes/den-4b-$run.yaml"
      echo "stop_when: {condition: top, load_below: 0.1, after_time: 0.00344004}   # P < 10 % of its peak, after delta = 0.032 mm" \
        >>"$out/scenes/den-4b-$run.yaml"
      grep -q "0.02000004, 0.4" "$out/scenes/den-4b-$run.yaml" || { echo "error: den-4b-$mesh.yaml's time line is not the one den.sh extends" >&2; return 1; }
      echo "$out/scenes/den-4b-$run.yaml" ;;
    *)
      local material=den-concrete-smeared.yaml
      [[ $variant == crackband ]] && material=den-concrete-crackband-$mesh.yaml
      mkdir -p "$out/scenes"
      sed -e "/@material/ s|{file: ../materials/den-concrete.yaml}|{file: $(realpath data/materials/$material)}|" \
          -e "s|material: den-concrete}|material: ${material%.yaml}}|" \
          -e "s|^name: den-4b-$mesh|name: den-4b-$run|" "data/den/den-4b-$mesh.yaml" >"$out/scenes/den-4b-$run.yaml"
      grep -q "$material" "$out/scenes/den-4b-$run.yaml" || { echo "error: no @material line in den-4b-$mesh.yaml" >&2; return 1; }
      echo "$out/scenes/den-4b-$run.yaml" ;;
  esac
}

# history.csv column of a named header field (1-based).
col() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }

# A number from summary.json (flat "key": value lines as io/json_summary writes them).
jnum() { grep -m1 "\"$2\"" "$1" | sed 's/.*: *//; s/[",]//g'; }

failed=()  # the runs of this call that did not complete (listed at the end; the exit status is 1)
for m in "${runs[@]}"; do
  scene=$(sceneOf "$m") || exit 2
  echo "== DEN $m: $scene" >&2
  rm -f "$out/$m"/{history.csv,summary.json,particles_final.csv}  # no stale results if the run cannot start
  $bin "$scene" --out "$out/$m" --no-vtu --threads "$threads" -q
  rc=$?
  runStatus "$rc" "$scene" "$out/$m"
  [[ $rc == 0 ]] || failed+=("$m (exit $rc$(failureKind "$out/$m"): $out/$m/summary.json)")
done

# The results of every run in OUT_DIR (run now or before), coarse to fine.
rows=()
for m in "${allRuns[@]}"; do
  dir=$out/$m
  [[ -f $dir/summary.json && -f $dir/particles_final.csv ]] || continue
  h=$dir/history.csv
  cu=$(col "$h" top_uy_mm) cr=$(col "$h" top_ry_N) ck=$(col "$h" kinetic_Nmm) cw=$(col "$h" external_work_Nmm)
  cd_=$(col "$h" dissipated_Nmm)
  # Peak of P over the output rows (P = the top edge's reaction, N), delta there, the final
  # dissipated energy, and the largest kinetic / external work ratio while delta > 0 (and at the end).
  read -r peak dpeak diss kmax kend dend pend <<<"$(awk -F, -v u="$cu" -v r="$cr" -v k="$ck" -v w="$cw" -v d="$cd_" '
    NR > 1 { if ($r > p) { p = $r; dp = $u } ; if ($u > 0 && $w > 0 && $k / $w > km) km = $k / $w; last_k = $k; last_w = $w; di = $d
             du = $u; pe = $r }
    END { printf "%.6g %.6g %.6g %.4g %.4g %.6g %.4g\n", p, dp, di, km, (last_w > 0 ? last_k / last_w : 0), du, (p > 0 ? pe / p : 0) }' "$h")"
  # Point symmetry of the final damage about the panel centre (100, 100): each particle is paired
  # with the one seeded at its 180-degree image (seeds on a grid of spacing s = cell / 2; the
  # current positions differ from the seeds by far less than s / 2, and the geometry is point
  # symmetric, so every particle has its image); mean |D(x) - D(-x)| and mean D.
  s=$(case $m in coarse* | 4a-coarse) echo 1.25 ;; medium*) echo 0.625 ;; fine*) echo 0.3125 ;; esac)
  read -r asym meand <<<"$(awk -F, -v s="$s" 'function ix(v) { return int(v / s) }
    NR > 1 { n++; x[n] = $1; y[n] = $2; D[n] = $3; at[ix($1) "," ix($2)] = n }
    END { a = 0; c = 0; sd = 0
          for (i = 1; i <= n; i++) { sd += D[i]; k = (int(200 / s) - 1 - ix(x[i])) "," (int(200 / s) - 1 - ix(y[i]))
                                     if (k in at) { a += (D[i] > D[at[k]] ? D[i] - D[at[k]] : D[at[k]] - D[i]); c++ } }
          printf "%.4g %.4g\n", (c ? a / c : -1), (n ? sd / n : 0) }' "$dir/particles_final.csv")"
  # ... and the fraction of cracked particles (D > 0) whose image is cracked too.
  symc=$(awk -F, -v s="$s" 'function ix(v) { return int(v / s) }
    NR > 1 { n++; x[n] = $1; y[n] = $2; D[n] = $3; at[ix($1) "," ix($2)] = n }
    END { c = 0; m = 0
          for (i = 1; i <= n; i++) { if (D[i] <= 0) continue; c++
                                     k = (int(200 / s) - 1 - ix(x[i])) "," (int(200 / s) - 1 - ix(y[i]))
                                     if ((k in at) && D[at[k]] > 0) m++ }
          printf "%.4g\n", (c ? m / c : -1) }' "$dir/particles_final.csv")
  wall=$(jnum "$dir/summary.json" wall_time_s)
  status=$(jnum "$dir/summary.json" status)
  parts=$(jnum "$dir/summary.json" particles)
  bpu=$(jnum "$dir/summary.json" bytes_per_particle_uncracked)
  bpc=$(jnum "$dir/summary.json" bytes_per_particle_cracked)
  rows+=("$m $status $peak $dpeak $diss $kmax $kend $wall $parts $bpu $bpc $asym $meand $symc $dend $pend")

  # Damage map of this mesh.
  ps=$(case $m in coarse* | 4a-coarse) echo 0.35 ;; medium*) echo 0.18 ;; fine*) echo 0.09 ;; esac)
  cat >"$out/damage_$m.gp" <<EOF
# Redraw: cd $(realpath "$out") && gnuplot damage_$m.gp
set terminal pngcairo size 800,760 enhanced font 'Sans,11'
set output 'damage_$m.png'
set datafile separator ','
set size ratio -1
set xrange [0:200]; set yrange [0:200]
set cbrange [0:1]; set cblabel 'damage D'
set palette defined (0 '#f2f2f2', 0.3 '#9ecae1', 0.7 '#de2d26', 1 '#67000d')
set title 'DEN $m: damage at the end ($status), delta = $(awk -F, -v u="$cu" 'END { printf "%.4f", $u }' "$h") mm'
set xlabel 'x (mm)'; set ylabel 'y (mm)'
plot '$m/particles_final.csv' every ::1 using 1:2:3 with points pt 5 ps $ps lc palette notitle
EOF
  (cd "$out" && gnuplot "damage_$m.gp") || echo "warning: damage map of $m not drawn" >&2
  # Crack map: the band's normal opening (column 5 of particles_final.csv), log colour scale;
  # damage alone saturates at tiny openings (the band is h = 0.05 mm wide), the opening shows
  # where the crack localises.
  if [[ $(head -1 "$dir/particles_final.csv" | tr ',' '\n' | grep -c opening_mm) -eq 1 ]]; then
    cat >"$out/crack_$m.gp" <<EOF
# Redraw: cd $(realpath "$out") && gnuplot crack_$m.gp
set terminal pngcairo size 800,760 enhanced font 'Sans,11'
set output 'crack_$m.png'
set datafile separator ','
set size ratio -1
set xrange [0:200]; set yrange [0:200]
set logscale cb; set cbrange [1e-4:0.1]; set cblabel 'opening (mm)' offset -1,0
set palette defined (0 '#fee8c8', 0.5 '#e34a33', 1 '#000000')
set title 'DEN $m: crack opening at the end ($status)'
set xlabel 'x (mm)'; set ylabel 'y (mm)'
plot '$m/particles_final.csv' every ::1 using 1:2 with points pt 5 ps $ps lc rgb '#eeeeee' notitle, \\
     '' every ::1 using 1:2:(\$5 > 1e-4 ? \$5 : 1/0) with points pt 5 ps $ps lc palette notitle
EOF
    (cd "$out" && gnuplot "crack_$m.gp") || echo "warning: crack map of $m not drawn" >&2
  fi
done

[[ ${#rows[@]} -gt 0 ]] || { echo "error: no run produced output" >&2; exit 1; }

# P against delta, the meshes together.
{
  echo "# Redraw: cd $(realpath "$out") && gnuplot load_displacement.gp"
  echo "set terminal pngcairo size 900,600 enhanced font 'Sans,11'"
  echo "set output 'load_displacement.png'"
  echo "set datafile separator ','"
  echo "set grid; set key top right"
  echo "set title 'DEN (4b: P_s = 10 kN, 4a: 5 kN): tensile load P against {/Symbol d}'"
  echo "set xlabel '{/Symbol d} (mm): the gauges across the notches (solid, as the test), the top edge (dashed)'; set ylabel 'P (N)'"
  printf "plot "
  sep=""
  colour=1
  # The test (Nooru-Mohamed, load path 4b; data/experiments/): its delta is the gauges' across the
  # notches, stiffer than the top edge's (docs/validation.md compares like with like); each run is
  # drawn against its own gauges where its scene has them, and against the top edge, dashed.
  if [[ -f data/experiments/nooru-mohamed-4b.txt ]]; then
    awk '!/^#/ && NF == 2 {print $1 "," $2}' data/experiments/nooru-mohamed-4b.txt >"$out/test-4b.csv"
    printf "'test-4b.csv' using 1:2 with linespoints lw 2 lc rgb 'black' pt 7 title 'test 4b ({/Symbol d} of its gauges)'"
    sep=", \\"$'\n'"     "
  fi
  for r in "${rows[@]}"; do
    set -- $r
    [[ $1 == *-smeared || $1 == *-crackband || $1 == *-tail ]] && continue  # in contrast.png, tail.png
    h=$out/$1/history.csv
    p=$(col "$h" top_ry_N)
    gl=$(col "$h" delta-left_mm); gr=$(col "$h" delta-right_mm)
    if [[ -n $gl && -n $gr ]]; then
      # The gauges' mean, zeroed at the first row of the tension (t >= 0.0008 s, as the test's
      # delta starts at 0 when the tension starts; scripts/validation/compare.py does the same).
      z=$(awk -F, -v l="$gl" -v r="$gr" 'NR > 1 && $1 >= 0.0008 { printf "%.17g", ($l + $r) / 2; exit }' "$h")
      printf "%s'%s/history.csv' every ::1 using ((\$%s + \$%s) / 2 - (%s)):%s with lines lw 2 lc %d title '%s (%s), gauges'" \
        "$sep" "$1" "$gl" "$gr" "${z:-0}" "$p" "$colour" "$1" "$2"
      sep=", \\"$'\n'"     "
    fi
    printf "%s'%s/history.csv' every ::1 using %s:%s with lines lw 1 dt 2 lc %d title '%s (%s), top edge'" "$sep" "$1" "$(col "$h" top_uy_mm)" "$p" "$colour" "$1" "$2"
    sep=", \\"$'\n'"     "
    colour=$((colour + 1))
  done
  echo
} >"$out/load_displacement.gp"
[[ -z $sep ]] || (cd "$out" && gnuplot load_displacement.gp) || echo "warning: load-displacement plot not drawn" >&2

# All models together (enriched solid, smeared dashed, crack band dotted), when any contrast ran.
if printf '%s\n' "${rows[@]}" | grep -q -e '-smeared ' -e '-crackband '; then
  {
    echo "# Redraw: cd $(realpath "$out") && gnuplot contrast.gp"
    echo "set terminal pngcairo size 1000,640 enhanced font 'Sans,11' dashed"
    echo "set output 'contrast.png'"
    echo "set datafile separator ','"
    echo "set grid; set key top right"
    echo "set title 'DEN 4b: enriched (solid), unregularised smeared (dashed), crack band (dotted)'"
    echo "set xlabel '{/Symbol d} (mm)'; set ylabel 'P (N)'"
    printf "plot "
    sep=""
    for r in "${rows[@]}"; do
      set -- $r
      case $1 in coarse | medium | fine) dt=1 ;; *-smeared) dt=2 ;; *-crackband) dt=3 ;; *) continue ;; esac
      color=$(case $1 in coarse*) echo '#1b9e77' ;; medium*) echo '#d95f02' ;; fine*) echo '#7570b3' ;; esac)
      h=$out/$1/history.csv
      printf "%s'%s/history.csv' every ::1 using %s:%s with lines lw 2 dt %s lc rgb '%s' title '%s'" "$sep" "$1" "$(col "$h" top_uy_mm)" "$(col "$h" top_ry_N)" "$dt" "$color" "$1"
      sep=", \\"$'\n'"     "
    done
    echo
  } >"$out/contrast.gp"
  (cd "$out" && gnuplot contrast.gp) || echo "warning: contrast plot not drawn" >&2
fi

# The long pulls (MESH-tail) together, with the 10 % line of each one's peak.
if printf '%s\n' "${rows[@]}" | grep -q -e '-tail '; then
  {
    echo "# Redraw: cd $(realpath "$out") && gnuplot tail.gp"
    echo "set terminal pngcairo size 900,600 enhanced font 'Sans,11' dashed"
    echo "set output 'tail.png'"
    echo "set datafile separator ','"
    echo "set grid; set key top right"
    echo "set title 'DEN 4b pulled until P < 10 % of its peak (stop\\_when), or to {/Symbol d} = 0.4 mm'"
    echo "set xlabel '{/Symbol d} (mm)'; set ylabel 'P (N)'"
    printf "plot "
    sep=""
    for r in "${rows[@]}"; do
      set -- $r
      [[ $1 == *-tail ]] || continue
      color=$(case $1 in coarse*) echo '#1b9e77' ;; medium*) echo '#d95f02' ;; fine*) echo '#7570b3' ;; esac)
      lt=1  # the second-band model dash-dotted
      [[ $1 == *-second-tail ]] && lt=4
      h=$out/$1/history.csv
      printf "%s'%s/history.csv' every ::1 using %s:%s with lines lw 2 dt %s lc rgb '%s' title '%s (%s, end at %.3f mm)', \\\\\\n     %s with lines dt 2 lc rgb '%s' notitle" \
        "$sep" "$1" "$(col "$h" top_uy_mm)" "$(col "$h" top_ry_N)" "$lt" "$color" "$1" "$2" "${15}" "$(awk -v p="$3" 'BEGIN { print 0.1 * p }')" "$color"
      sep=", \\"$'\n'"     "
    done
    echo
  } >"$out/tail.gp"
  (cd "$out" && gnuplot tail.gp) || echo "warning: tail plot not drawn" >&2
fi

# Mesh objectivity per model: spread (max - min) / mean of the peak load and of the dissipated
# energy over the meshes that completed.
families=()
for fam in enriched smeared crackband; do
  read -r n pk ds <<<"$(for r in "${rows[@]}"; do
      set -- $r
      case $fam:$1 in enriched:coarse | enriched:medium | enriched:fine | smeared:*-smeared | crackband:*-crackband)
        [[ $2 == completed ]] && echo "$3 $5" ;;
      esac
    done | awk 'NR == 1 { pmin = pmax = $1; dmin = dmax = $2 }
                { n++; ps += $1; ds += $2; if ($1 < pmin) pmin = $1; if ($1 > pmax) pmax = $1; if ($2 < dmin) dmin = $2; if ($2 > dmax) dmax = $2 }
                END { if (n) printf "%d %.4g %.4g\n", n, (pmax - pmin) / (ps / n), (dmax - dmin) / (ds / n); else print "0 0 0" }')"
  [[ $n -gt 1 ]] && families+=("$fam $n $pk $ds")
done

# Rate check: the change of the peak load and of the dissipated energy per halving of the loading
# rate (coarse -> halfrate -> quarterrate: the tension time line stretched 1, 2 and 4 times; through
# the peak 11.1, 5.55 and 2.78 mm/s), relative to the slower run.
rates=()
# Only neighbours in the sequence are compared (a missing halfrate run leaves no coarse-to-quarter pair).
prev=""
for name in coarse coarse-halfrate coarse-quarterrate; do
  found=""
  for r in "${rows[@]}"; do
    set -- $r
    [[ $1 == "$name" && $2 == completed ]] || continue
    found="$1 $3 $5"
    [[ -n $prev ]] && rates+=("$(awk -v a="$prev" -v b="$found" 'BEGIN { split(a, x, " "); split(b, y, " ");
        printf "%s_to_%s %.4g %.4g", x[1], y[1], (x[2] - y[2]) / y[2], (x[3] - y[3]) / y[3] }')")
  done
  prev=$found
done

# The table (stdout) and summary.json.
{
  echo "{"
  echo "  \"units\": \"mm, N, MPa, t, s\","
  echo "  \"load_paths\": \"coarse, medium, fine: 4b (P_s = 10 kN, then delta); 4a-coarse: 4a (P_s = 5 kN)\","
  echo "  \"meshes\": {"
  for i in "${!rows[@]}"; do
    set -- ${rows[$i]}
    sep=$([[ $i -lt $((${#rows[@]} - 1)) ]] && echo "," || echo "")
    printf '    "%s": {"status": "%s", "peak_load_N": %s, "delta_at_peak_mm": %s, "dissipated_Nmm": %s, "kinetic_over_external_max_tension": %s, "kinetic_over_external_end": %s, "wall_time_s": %s, "particles": %s, "bytes_per_particle_uncracked": %s, "bytes_per_particle_cracked": %s, "damage_point_symmetry_mean_abs_diff": %s, "mean_damage": %s, "cracked_with_cracked_image": %s, "delta_at_end_mm": %s, "load_at_end_over_peak": %s}%s\n' \
      "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$8" "$9" "${10}" "${11}" "${12}" "${13}" "${14}" "${15}" "${16}" "$sep"
  done
  echo "  },"
  echo "  \"mesh_objectivity\": {"
  for i in "${!families[@]}"; do
    set -- ${families[$i]}
    sep=$([[ $i -lt $((${#families[@]} - 1)) ]] && echo "," || echo "")
    printf '    "%s": {"meshes": %s, "peak_load_spread": %s, "dissipated_spread": %s}%s\n' "$1" "$2" "$3" "$4" "$sep"
  done
  echo "  },"
  echo "  \"rate_check\": {"
  for i in "${!rates[@]}"; do
    set -- ${rates[$i]}
    sep=$([[ $i -lt $((${#rates[@]} - 1)) ]] && echo "," || echo "")
    printf '    "%s": {"peak_load_change": %s, "dissipated_change": %s}%s\n' "$1" "$2" "$3" "$sep"
  done
  echo "  }"
  echo "}"
} >"$out/summary.json"
printf "\n%-17s %-10s %10s %10s %12s %10s %10s %9s %9s %8s %8s %8s %8s %9s %8s\n" run status "peak P(N)" "delta(mm)" "dissip(Nmm)" "KE/W tmax" "KE/W end" "time(s)" particles "B/pt" "B/crk" "sym|dD|" "sym crk" "end d(mm)" "P/Ppk"
for r in "${rows[@]}"; do
  set -- $r
  printf "%-17s %-10s %10.1f %10.4f %12.2f %10.3g %10.3g %9.1f %9s %8s %8s %8.3g %8.3g %9.4f %8.3f\n" "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$8" "$9" "${10}" "${11}" "${12}" "${14}" "${15}" "${16}"
done
for f in "${families[@]}"; do
  set -- $f
  printf "mesh objectivity, %-9s (%s meshes): peak load spread %.1f %%, dissipated energy spread %.1f %%\n" "$1" "$2" "$(awk -v v="$3" 'BEGIN { print 100 * v }')" "$(awk -v v="$4" 'BEGIN { print 100 * v }')"
done
for r in "${rates[@]}"; do
  set -- $r
  printf "rate check, %-34s: peak load %+.2f %%, dissipated energy %+.2f %% (relative to the slower run)\n" "$1" "$(awk -v v="$2" 'BEGIN { print 100 * v }')" "$(awk -v v="$3" 'BEGIN { print 100 * v }')"
done
echo "(peak P and delta from the output rows of history.csv; KE/W: kinetic over external work,"
echo " tmax: the largest while delta > 0 (tension phase), end: at the end;"
echo " sym|dD|: mean |D(x) - D(rotated x)| over particles, 180 degrees about (100, 100);"
echo " sym crk: fraction of cracked particles whose rotated image is cracked; spread: (max - min) / mean;"
echo " end d, P/Ppk: delta at the last row and P there over the peak; the DEN study ends the pull at P/Ppk < 0.1)"
echo "written: $out/summary.json $out/load_displacement.png $(cd "$out" && ls contrast.png tail.png damage_*.png crack_*.png 2>/dev/null | sed "s|^|$out/|" | tr '\n' ' ')"
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "failed runs (kept in the table with their status):" >&2
  printf '  %s\n' "${failed[@]}" >&2
  exit 1
fi
