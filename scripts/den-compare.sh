#!/usr/bin/env bash
# The DEN meshes compared after the peak, for the one-band model and the second-band option
# (docs/model.md, "A second band"), from the runs scripts/den.sh left in OUT_DIR:
#   MESH-tail and MESH-second-tail (pulled until P < 10 % of the peak), MESH = coarse medium fine.
# Prints markdown tables:
#   1. per run: peak P, delta at the peak, end delta, P at the end / peak, dissipated energy at
#      the end and at the smallest end delta of the model's three meshes, two-band points;
#   2. the post-peak overlay: the largest |P_mesh(delta) - P_ref(delta)| over the softening
#      branch (delta past both peaks, up to the smaller end delta) as a fraction of the
#      reference's peak, for coarse and medium against fine and coarse against medium
#      (P_ref linearly interpolated between its output rows), also restricted to delta <= 0.1 mm;
#   3. crack paths: the y of each macro-crack (particles whose band opens more than 0.01 mm;
#      with two bands the larger opening) at x = 30, 45, ..., 165 mm: the opening-weighted mean
#      y of the particles within half a particle spacing of x, upper crack (y > 100 mm) / lower.
# Usage: scripts/den-compare.sh OUT_DIR   Units: mm, N. Shell and awk only.
set -uo pipefail
out=${1:?usage: scripts/den-compare.sh OUT_DIR}
col() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }
jnum() { { grep -m1 "\"$2\"" "$1" || true; } | sed 's/.*: *//; s/[",]//g'; }
spacing() { case $1 in coarse*) echo 1.25 ;; medium*) echo 0.625 ;; fine*) echo 0.3125 ;; esac; }

# delta, P, dissipated of a run's history (rows with delta > 0).
curve() {
  local h=$out/$1/history.csv
  awk -F, -v u="$(col "$h" top_uy_mm)" -v r="$(col "$h" top_ry_N)" -v d="$(col "$h" dissipated_Nmm)" \
    'NR > 1 && $u > 0 { print $u, $r, $d }' "$h"
}

runs=()
for model in tail second-tail; do
  for mesh in coarse medium fine; do
    [[ -f $out/$mesh-$model/history.csv ]] && runs+=("$mesh-$model")
  done
done
[[ ${#runs[@]} -gt 0 ]] || { echo "error: no MESH-tail or MESH-second-tail run in $out" >&2; exit 2; }

echo "## Runs"
echo
echo "| run | status | peak P (kN) | delta at peak (mm) | end delta (mm) | P end / peak | dissipated at end (N mm) | at delta* (N mm) | two-band points | wall (s) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for model in tail second-tail; do
  # delta*: the smallest end delta of this model's meshes
  dstar=$(for r in "${runs[@]}"; do [[ $r == *-$model && ( $model == second-tail || $r != *second* ) ]] && curve "$r" | tail -1 | cut -d' ' -f1; done | sort -g | head -1)
  for r in "${runs[@]}"; do
    [[ $r == *-$model ]] || continue
    [[ $model == tail && $r == *second* ]] && continue
    curve "$r" | awk -v run="$r" -v ds="$dstar" -v status="$(jnum "$out/$r/summary.json" status)" \
      -v two="$(jnum "$out/$r/summary.json" two_band_points)" -v wall="$(jnum "$out/$r/summary.json" wall_time_s)" '
      { if ($2 > p) { p = $2; dp = $1 }
        if ($1 <= ds) { dl = $1; el = $3 } else if (!done) { done = 1; es = el + ($3 - el) * (ds - dl) / ($1 - dl) }
        du = $1; pe = $2; ee = $3 }
      END { if (!done) es = ee
            printf "| %s | %s | %.3f | %.4f | %.4f | %.3f | %.0f | %.0f (delta* = %.4f) | %s | %.0f |\n",
                   run, status, p / 1000, dp, du, pe / p, ee, es, ds, (two == "" ? "-" : two), wall }'
  done
done

echo
echo "## Post-peak overlay: max |P_mesh - P_ref| / peak of P_ref"
echo
echo "| model | coarse vs fine | medium vs fine | coarse vs medium | coarse vs medium, delta <= 0.1 mm |"
echo "|---|---|---|---|---|"
overlay() {  # RUN REF [DMAX]: max |P_run - P_ref| / peak_ref on the softening branch
  [[ -f $out/$1/history.csv && -f $out/$2/history.csv ]] || { echo "-"; return; }
  awk -v dmax="${3:-1e9}" 'FNR == 1 { f++ }
    f == 1 { n++; rd[n] = $1; rp[n] = $2; if ($2 > rpk) { rpk = $2; rdp = $1 }; next }
    { m++; md[m] = $1; mp[m] = $2; if ($2 > mpk) { mpk = $2; mdp = $1 } }
    END { lo = (rdp > mdp ? rdp : mdp); hi = (rd[n] < md[m] ? rd[n] : md[m]); if (dmax < hi) hi = dmax
          worst = 0; k = 1
          for (i = 1; i <= m; i++) {
            if (md[i] < lo || md[i] > hi) continue
            while (k < n && rd[k + 1] < md[i]) k++
            if (k >= n) break
            pr = rp[k] + (rp[k + 1] - rp[k]) * (md[i] - rd[k]) / (rd[k + 1] - rd[k])
            e = (mp[i] > pr ? mp[i] - pr : pr - mp[i]); if (e > worst) worst = e }
          printf "%.1f %%", 100 * worst / rpk }' <(curve "$2") <(curve "$1")
}
for model in tail second-tail; do
  name=$([[ $model == tail ]] && echo "one band (off)" || echo "second band (orthogonal)")
  echo "| $name | $(overlay coarse-$model fine-$model) | $(overlay medium-$model fine-$model) | $(overlay coarse-$model medium-$model) | $(overlay coarse-$model medium-$model 0.1) |"
done

echo
echo "## Crack paths: y (mm) of the upper / lower crack at x (opening > 0.01 mm)"
echo
header="| run |"
sep="|---|"
for x in 30 45 60 75 90 105 120 135 150 165; do header+=" x = $x |"; sep+="---|"; done
echo "$header"
echo "$sep"
for r in "${runs[@]}"; do
  f=$out/$r/particles_final.csv
  [[ -f $f ]] || continue
  awk -F, -v run="$r" -v s="$(spacing "$r")" -v two="$(col "$f" opening_2_mm)" '
    NR > 1 { w = $5; if (two != "" && $two > w) w = $two
             if (w <= 0.01) next
             for (x = 30; x <= 165; x += 15) if ($1 > x - s / 2 && $1 <= x + s / 2) {
               k = ($2 > 100 ? "u" : "l") x; sw[k] += w; sy[k] += w * $2 } }
    END { printf "| %s |", run
          for (x = 30; x <= 165; x += 15) {
            u = ("u" x in sw) ? sprintf("%.0f", sy["u" x] / sw["u" x]) : "-"
            l = ("l" x in sw) ? sprintf("%.0f", sy["l" x] / sw["l" x]) : "-"
            printf " %s / %s |", u, l }
          printf "\n" }' "$f"
done
