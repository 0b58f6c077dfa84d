#!/usr/bin/env bash
# Nooru-Mohamed's double-edge-notched (DEN) panel, load path 4b, on up to three meshes with
# ecm-mpm (run after the build: cmake -S . -B build -G Ninja && ninja -C build).
# Usage: scripts/den.sh [OUT_DIR] [coarse|medium|fine|all|4a-coarse]   (default: results/den coarse)
# (coarse, medium, fine: load path 4b, P_s = 10 kN; 4a-coarse: load path 4a, P_s = 5 kN, coarse)
# Writes OUT_DIR/MESH/ (ecm-mpm's output folder per mesh, without VTU snapshots),
# OUT_DIR/load_displacement.png (P against delta, all meshes), OUT_DIR/damage_MESH.png,
# OUT_DIR/summary.json and the summary table on stdout, for every mesh whose output is in OUT_DIR
# (run now or by an earlier call, so `den.sh DIR medium` adds to an earlier coarse run).
# Units: mm, N, MPa, t, s. Threads: $DEN_THREADS (default 2).
# Shell, awk and gnuplot only. A failed run (exit status 1) is kept in the table with its status.
set -uo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/den}
which=${2:-coarse}
threads=${DEN_THREADS:-2}
case "$which" in
  coarse | medium | fine | 4a-coarse) meshes=("$which") ;;
  all) meshes=(coarse medium fine) ;;
  *) echo "usage: scripts/den.sh [OUT_DIR] [coarse|medium|fine|all|4a-coarse]" >&2; exit 2 ;;
esac
bin=./build/mpm/ecm-mpm
[[ -x $bin ]] || { echo "error: $bin not built (cmake -S . -B build -G Ninja && ninja -C build)" >&2; exit 2; }
mkdir -p "$out"

# history.csv column of a named header field (1-based).
col() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }

# A number from summary.json (flat "key": value lines as io/json_summary writes them).
jnum() { grep -m1 "\"$2\"" "$1" | sed 's/.*: *//; s/[",]//g'; }

for m in "${meshes[@]}"; do
  scene=data/den/den-4b-$m.yaml
  [[ $m == 4a-coarse ]] && scene=data/den/den-4a-coarse.yaml
  echo "== DEN $m: $scene" >&2
  rm -f "$out/$m"/{history.csv,summary.json,particles_final.csv}  # no stale results if the run cannot start
  $bin "$scene" --out "$out/$m" --no-vtu --threads "$threads" -q
  rc=$?
  [[ $rc -le 1 ]] || echo "error: ecm-mpm could not run $scene (status $rc)" >&2
done

# The results of every mesh in OUT_DIR (run now or before), coarse to fine.
rows=()
for m in coarse medium fine 4a-coarse; do
  dir=$out/$m
  [[ -f $dir/summary.json && -f $dir/particles_final.csv ]] || continue
  h=$dir/history.csv
  cu=$(col "$h" top_uy_mm) cr=$(col "$h" top_ry_N) ck=$(col "$h" kinetic_Nmm) cw=$(col "$h" external_work_Nmm)
  cd_=$(col "$h" dissipated_Nmm)
  # Peak of P over the output rows (P = the top edge's reaction, N), delta there, the final
  # dissipated energy, and the largest kinetic / external work ratio while delta > 0 (and at the end).
  read -r peak dpeak diss kmax kend <<<"$(awk -F, -v u="$cu" -v r="$cr" -v k="$ck" -v w="$cw" -v d="$cd_" '
    NR > 1 { if ($r > p) { p = $r; dp = $u } ; if ($u > 0 && $w > 0 && $k / $w > km) km = $k / $w; last_k = $k; last_w = $w; di = $d }
    END { printf "%.6g %.6g %.6g %.4g %.4g\n", p, dp, di, km, (last_w > 0 ? last_k / last_w : 0) }' "$h")"
  # Point symmetry of the final damage about the panel centre (100, 100): each particle is paired
  # with the one seeded at its 180-degree image (seeds on a grid of spacing s = cell / 2; the
  # current positions differ from the seeds by far less than s / 2, and the geometry is point
  # symmetric, so every particle has its image); mean |D(x) - D(-x)| and mean D.
  s=$(case $m in coarse | 4a-coarse) echo 1.25 ;; medium) echo 0.625 ;; fine) echo 0.3125 ;; esac)
  read -r asym meand <<<"$(awk -F, -v s="$s" 'function ix(v) { return int(v / s) }
    NR > 1 { n++; x[n] = $1; y[n] = $2; D[n] = $3; at[ix($1) "," ix($2)] = n }
    END { a = 0; c = 0; sd = 0
          for (i = 1; i <= n; i++) { sd += D[i]; k = (int(200 / s) - 1 - ix(x[i])) "," (int(200 / s) - 1 - ix(y[i]))
                                     if (k in at) { a += (D[i] > D[at[k]] ? D[i] - D[at[k]] : D[at[k]] - D[i]); c++ } }
          printf "%.4g %.4g\n", (c ? a / c : -1), (n ? sd / n : 0) }' "$dir/particles_final.csv")"
  wall=$(jnum "$dir/summary.json" wall_time_s)
  status=$(jnum "$dir/summary.json" status)
  parts=$(jnum "$dir/summary.json" particles)
  bpu=$(jnum "$dir/summary.json" bytes_per_particle_uncracked)
  bpc=$(jnum "$dir/summary.json" bytes_per_particle_cracked)
  rows+=("$m $status $peak $dpeak $diss $kmax $kend $wall $parts $bpu $bpc $asym $meand")

  # Damage map of this mesh.
  ps=$(case $m in coarse | 4a-coarse) echo 0.35 ;; medium) echo 0.18 ;; fine) echo 0.09 ;; esac)
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
  echo "set title 'DEN (4b: P_s = 10 kN, 4a: 5 kN): tensile load P against top displacement {/Symbol d}'"
  echo "set xlabel '{/Symbol d} (mm)'; set ylabel 'P (N)'"
  printf "plot "
  sep=""
  for r in "${rows[@]}"; do
    set -- $r
    h=$out/$1/history.csv
    printf "%s'%s/history.csv' every ::1 using %s:%s with lines lw 2 title '%s (%s)'" "$sep" "$1" "$(col "$h" top_uy_mm)" "$(col "$h" top_ry_N)" "$1" "$2"
    sep=", \\"$'\n'"     "
  done
  echo
} >"$out/load_displacement.gp"
(cd "$out" && gnuplot load_displacement.gp) || echo "warning: load-displacement plot not drawn" >&2

# The table (stdout) and summary.json.
{
  echo "{"
  echo "  \"units\": \"mm, N, MPa, t, s\","
  echo "  \"load_paths\": \"coarse, medium, fine: 4b (P_s = 10 kN, then delta); 4a-coarse: 4a (P_s = 5 kN)\","
  echo "  \"meshes\": {"
  for i in "${!rows[@]}"; do
    set -- ${rows[$i]}
    sep=$([[ $i -lt $((${#rows[@]} - 1)) ]] && echo "," || echo "")
    printf '    "%s": {"status": "%s", "peak_load_N": %s, "delta_at_peak_mm": %s, "dissipated_Nmm": %s, "kinetic_over_external_max_tension": %s, "kinetic_over_external_end": %s, "wall_time_s": %s, "particles": %s, "bytes_per_particle_uncracked": %s, "bytes_per_particle_cracked": %s, "damage_point_symmetry_mean_abs_diff": %s, "mean_damage": %s}%s\n' \
      "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$8" "$9" "${10}" "${11}" "${12}" "${13}" "$sep"
  done
  echo "  }"
  echo "}"
} >"$out/summary.json"
printf "\n%-9s %-10s %10s %10s %12s %10s %10s %9s %9s %8s %8s %9s\n" mesh status "peak P(N)" "delta(mm)" "dissip(Nmm)" "KE/W tmax" "KE/W end" "time(s)" particles "B/pt" "B/crk" "sym|dD|"
for r in "${rows[@]}"; do
  set -- $r
  printf "%-9s %-10s %10.1f %10.4f %12.2f %10.3g %10.3g %9.1f %9s %8s %8s %9.3g\n" "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$8" "$9" "${10}" "${11}" "${12}"
done
echo "(peak P and delta from the output rows of history.csv; KE/W: kinetic over external work,"
echo " tmax: the largest while delta > 0 (tension phase), end: at the end;"
echo " sym|dD|: mean |D(x) - D(rotated x)| over particles, 180 degrees about (100, 100))"
echo "written: $out/summary.json $out/load_displacement.png $(cd "$out" && ls damage_*.png crack_*.png 2>/dev/null | sed "s|^|$out/|" | tr '\n' ' ')"
