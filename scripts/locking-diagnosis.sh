#!/usr/bin/env bash
# Stress locking in the DEN (load path 4b): for the cracked points along each macro-crack of a
# mesh at the end of its scene (delta = 0.1 mm), how the point's band lies against the crack,
# how far the band had opened when the macro-crack reached the point, and the bulk stress it
# still carries along its band, sigma_tt = t . sigma . t with t the band's tangent.
# Run after the build (cmake -S . -B build -G Ninja && ninja -C build).
# Usage: scripts/locking-diagnosis.sh [OUT_DIR] [MESH]   (default: results/locking medium)
# Writes OUT_DIR/MESH/ (the ecm-mpm run with particle snapshots), OUT_DIR/points-MESH.csv (one
# row per point), OUT_DIR/locking-MESH.png (the three histograms, data in OUT_DIR/hist-*-MESH.dat),
# OUT_DIR/locking-MESH.txt (the tables, also on stdout).
# Definitions:
#   macro-crack particle   band opening > 0.01 mm at the end;
#   point along a crack    a cracked particle (it has a band) within 2.5 mm of one;
#   upper / lower crack    the point above / below y = 100 mm (the notches' height);
#   local crack direction  the principal axis of the macro-crack particles within 5 mm of the point;
#   angle                  between the band's normal and the local crack's normal (0: aligned);
#   opening on arrival     the point's band opening in the first snapshot in which a macro-crack
#                          particle lies within 2.5 mm of it (snapshots every 2.5e-4 s);
#   sigma_tt / f_t'        at the end, f_t' = 3 MPa (data/materials/den-concrete.yaml).
# Units: mm, N, MPa, t, s. Threads: $DEN_THREADS (default 2). Shell, awk and gnuplot only.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/locking}
mesh=${2:-medium}
threads=${DEN_THREADS:-2}
bin=${DEN_BIN:-./build/mpm/ecm-mpm}
[[ -x $bin ]] || { echo "error: $bin not built (cmake -S . -B build -G Ninja && ninja -C build)" >&2; exit 2; }
scene=data/den/den-4b-$mesh.yaml
[[ -f $scene ]] || { echo "error: no scene $scene (meshes: coarse, medium, fine)" >&2; exit 2; }
mkdir -p "$out/scenes"
times=$(awk 'BEGIN { s = ""; for (t = 0.002; t < 0.0065; t += 0.00025) s = s sprintf("%.5f, ", t); print s "0.0065" }')
# The scene's own file, with particle snapshots; data/materials/ is found from the copy.
sed -e "/@material/ s|{file: ../materials/|{file: $(realpath data/materials)/|" \
    -e "s|^name: den-4b-$mesh|name: den-4b-$mesh-snapshots|" "$scene" > "$out/scenes/den-4b-$mesh-snapshots.yaml"
echo "particle_snapshots: [$times]   # s" >> "$out/scenes/den-4b-$mesh-snapshots.yaml"
run=$out/$mesh
if [[ ! -f $run/summary.json ]]; then
  echo "running $scene with particle snapshots ($threads threads) ..." >&2
  "$bin" "$out/scenes/den-4b-$mesh-snapshots.yaml" --out "$run" --no-vtu --threads "$threads" -q
fi
snaps=$(ls "$run"/particles_t*.csv | awk -F'particles_t' '{ t = $2; sub(/\.csv$/, "", t); print t "\t" $0 }' | sort -g | cut -f2)

# One awk pass: the end state first (the last snapshot is the end, delta = 0.1 mm), then every
# snapshot in time order for the arrival of the macro-crack.
awk -F, -v ft=3.0 -v near=2.5 -v around=5.0 -v macro=0.01 -v points="$out/points-$mesh.csv" '
  function key(x, y, c) { return int((x + 1000) / c) "," int((y + 1000) / c) }
  FNR == 1 { file++; next }
  file == 1 {  # the end state
    n = FNR - 1
    x[n] = $1; y[n] = $2; open[n] = $5; nx[n] = $6; ny[n] = $7; sxx[n] = $8; syy[n] = $9; sxy[n] = $10
    if ($5 > macro) { m++; mx[m] = $1; my[m] = $2; bucket[key($1, $2, around)] = bucket[key($1, $2, around)] " " m }
    count = n
    next
  }
  file == 2 && FNR == 2 {  # before the snapshots: the points along the cracks, their angle and sigma_tt
    for (i = 1; i <= count; i++) {
      if (nx[i] == 0 && ny[i] == 0) continue
      cx = int((x[i] + 1000) / around); cy = int((y[i] + 1000) / around)
      sx = sy = sxx2 = syy2 = sxy2 = k = 0; isnear = 0
      for (a = -1; a <= 1; a++) for (b = -1; b <= 1; b++) {
        s = bucket[(cx + a) "," (cy + b)]; nm = split(s, ids, " ")
        for (j = 1; j <= nm; j++) {
          q = ids[j]; dx = mx[q] - x[i]; dy = my[q] - y[i]; d2 = dx * dx + dy * dy
          if (d2 <= near * near) isnear = 1
          if (d2 <= around * around) { k++; px[k] = mx[q]; py[k] = my[q]; sx += mx[q]; sy += my[q] }
        }
      }
      if (!isnear || k < 3) continue
      sx /= k; sy /= k
      for (j = 1; j <= k; j++) { dx = px[j] - sx; dy = py[j] - sy; sxx2 += dx * dx; syy2 += dy * dy; sxy2 += dx * dy }
      phi = 0.5 * atan2(2 * sxy2, sxx2 - syy2)          # principal axis: the crack direction
      mnx = -sin(phi); mny = cos(phi)                      # the crack normal
      c = nx[i] * mnx + ny[i] * mny; if (c < 0) c = -c; if (c > 1) c = 1
      angle[i] = atan2(sqrt(1 - c * c), c) * 180 / 3.141592653589793
      tx = -ny[i]; ty = nx[i]
      stt[i] = (tx * tx * sxx[i] + ty * ty * syy[i] + 2 * tx * ty * sxy[i]) / ft
      along[i] = 1; arrival[i] = -1
    }
  }
  FNR == 2 && file > 2 { arrivals() }  # the previous snapshot is complete
  FNR == 2 { delete now }
  {  # every snapshot (file >= 2), in time order: its macro-crack particles
    i = FNR - 1
    sopen[i] = $5
    if ($5 > macro) now[key($1, $2, near)] = now[key($1, $2, near)] " " $1 ":" $2
  }
  # The points that the snapshot just read finds next to a macro-crack particle for the first time.
  function arrivals(   i, cx, cy, hit, a, b, nm, ids, j, xy, dx, dy) {
    for (i in along) {
      if (arrival[i] >= 0) continue
      cx = int((x[i] + 1000) / near); cy = int((y[i] + 1000) / near); hit = 0
      for (a = -1; a <= 1 && !hit; a++) for (b = -1; b <= 1 && !hit; b++) {
        nm = split(now[(cx + a) "," (cy + b)], ids, " ")
        for (j = 1; j <= nm; j++) { split(ids[j], xy, ":"); dx = xy[1] - x[i]; dy = xy[2] - y[i]
          if (dx * dx + dy * dy <= near * near) { hit = 1; break } }
      }
      if (hit) arrival[i] = sopen[i]
    }
  }
  END {
    arrivals()
    print "crack,x_mm,y_mm,angle_deg,opening_on_arrival_mm,opening_end_mm,sigma_tt_over_ft" > points
    for (i in along) printf "%s,%.4f,%.4f,%.3f,%.6g,%.6g,%.6g\n", (y[i] > 100 ? "upper" : "lower"), x[i], y[i], angle[i], arrival[i], open[i], stt[i] > points
  }' "$run/particles_final.csv" $snaps

# The histograms (counts per crack) as tables and plots.
hist() {  # column, edges... ($ONLY_LOCKED=1: only the points with sigma_tt >= f_t')
  local col=$1; shift
  awk -F, -v col="$col" -v edges="$*" -v locked="${ONLY_LOCKED:-0}" '
    NR == 1 || (locked && $7 < 1) { next }
    { n = split(edges, e, " "); v = $col
      for (k = 1; k < n; k++) if (v >= e[k] && v < e[k + 1]) { c[$1 "," k]++; break }
      if (v >= e[n]) c[$1 "," n]++ ; if (v < e[1]) c[$1 ",0"]++ }
    END { n = split(edges, e, " ")
      printf "%-16s %7s %7s\n", "bin", "upper", "lower"
      if (c["upper,0"] + c["lower,0"] > 0) printf "%-16s %7d %7d\n", "< " e[1], c["upper,0"], c["lower,0"]
      for (k = 1; k < n; k++) printf "%-16s %7d %7d\n", e[k] " - " e[k + 1], c["upper," k], c["lower," k]
      printf "%-16s %7d %7d\n", ">= " e[n], c["upper," n], c["lower," n] }' "$out/points-$mesh.csv"
}
{
  echo "# DEN 4b $mesh mesh at delta = 0.1 mm: cracked points along the macro-cracks ($(($(wc -l < "$out/points-$mesh.csv") - 1)) points)"
  echo; echo "## angle between band normal and crack normal (degrees)"; hist 4 0 10 20 30 40 50 60 70 80 90
  echo; echo "## band opening when the macro-crack reached the point (mm; -1: not reached in a snapshot)"
  hist 5 0 1e-4 1e-3 4e-3 1e-2 3e-2 1e-1 2e-1
  echo; echo "## sigma_tt / f_t' at delta = 0.1 mm"; hist 7 -1 -0.5 0 0.25 0.5 0.75 1 1.5 2 3
  echo; echo "## the locked points (sigma_tt >= f_t'): band opening when the macro-crack reached them (mm)"
  ONLY_LOCKED=1 hist 5 0 1e-4 1e-3 4e-3 1e-2 3e-2 1e-1
  echo; echo "## the locked points: their band's own opening at delta = 0.1 mm (mm)"
  ONLY_LOCKED=1 hist 6 0 1e-3 4e-3 1e-2 3e-2 1e-1 2e-1
} | tee "$out/locking-$mesh.txt"

# Histogram data for the plots: bin centre and count, for all points.
bins() {  # column, transform (none | log10), width, file
  awk -F, -v col="$1" -v tr="$2" -v w="$3" 'function floor(a) { return (a >= 0 || a == int(a)) ? int(a) : int(a) - 1 }
    NR > 1 { v = $col; if (tr == "log10") { if (v <= 0) next; v = log(v) / log(10) }; c[floor(v / w)]++ }
    END { for (k in c) printf "%.6g %d\n", (k + 0.5) * w, c[k] }' "$out/points-$mesh.csv" | sort -g > "$4"
}
bins 4 none 10 "$out/hist-angle-$mesh.dat"
bins 5 log10 0.25 "$out/hist-arrival-$mesh.dat"
bins 7 none 0.25 "$out/hist-sigma-tt-$mesh.dat"
gnuplot <<EOF
set terminal pngcairo size 1500,450
set output "$out/locking-$mesh.png"
set multiplot layout 1,3 title "DEN 4b $mesh, delta = 0.1 mm: cracked points along the macro-cracks" noenhanced
set style fill solid 0.6
set ylabel "points"
set key noenhanced
set xlabel noenhanced
set xlabel "angle between band normal and crack normal (deg)"
set boxwidth 9 absolute
set xrange [0:90]
plot "$out/hist-angle-$mesh.dat" using 1:2 with boxes title "points"
set xlabel "log10 of the band opening on arrival of the macro-crack (mm)"
set boxwidth 0.22 absolute
set xrange [-7:-1]
plot "$out/hist-arrival-$mesh.dat" using 1:2 with boxes title "points"
set xlabel "sigma_tt / f_t' at delta = 0.1 mm (outside [-5, 5] not drawn)"
set boxwidth 0.22 absolute
set xrange [-5:5]
plot "$out/hist-sigma-tt-$mesh.dat" using 1:2 with boxes title "points"
unset multiplot
EOF
echo "written: $out/points-$mesh.csv $out/locking-$mesh.txt $out/locking-$mesh.png" >&2
