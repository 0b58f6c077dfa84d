#!/usr/bin/env bash
# The two-disks throughput benchmark (data/mpm/two-disks.yaml): two elastic disks, ~100,400
# particles, 316 x 316 cells, linear shape functions, MUSL, pure FLIP, dt = 0.2 x cell, 500 and
# 3200 steps. Google Benchmark (bench_two_disks) gives particle-updates per second per core on 1
# and 2 threads (set-up not timed) and the solver's bytes per particle; then one whole ecm-mpm run
# of the scene (3200 steps, 2 threads, a history.csv row of energies every 100 steps) gives the
# program's peak resident memory per particle (/usr/bin/time) and its energies.
# Usage: scripts/two-disks.sh [OUT_DIR]   (default results/two-disks; build first: ninja -C build)
# Writes OUT_DIR/bench.csv (Google Benchmark), OUT_DIR/run/ (ecm-mpm), OUT_DIR/summary.txt.
# Timings on a machine shared with other work are noisy: run it on a quiet machine to compare.
# There, libgomp's default spin-waiting makes 2-thread runs collapse (measured 1.9 M/s instead of
# 17 M/s with OMP_WAIT_POLICY=passive while two other 2-thread jobs ran): export
# OMP_WAIT_POLICY=passive to measure what a shared machine can give. Threads of the ecm-mpm run:
# $TWO_DISKS_THREADS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/two-disks}
threads=${TWO_DISKS_THREADS:-2}
bench=./build/bench/bench_two_disks
bin=./build/mpm/ecm-mpm
for b in "$bench" "$bin"; do
  [[ -x $b ]] || { echo "error: $b not built (ninja -C build)" >&2; exit 2; }
done
mkdir -p "$out"

echo "== Google Benchmark: $bench" >&2
"$bench" --benchmark_out="$out/bench.csv" --benchmark_out_format=csv

echo "== ecm-mpm data/mpm/two-disks.yaml (3200 steps, $threads threads)" >&2
rss_kb=""
if [[ -x /usr/bin/time ]]; then
  /usr/bin/time -v "$bin" data/mpm/two-disks.yaml --out "$out/run" --no-vtu --no-plot -q --threads "$threads" 2>"$out/time.txt"
  rss_kb=$(awk -F: '/Maximum resident set size/ { gsub(/ /, "", $2); print $2 }' "$out/time.txt")
else
  "$bin" data/mpm/two-disks.yaml --out "$out/run" --no-vtu --no-plot -q --threads "$threads"
fi

# A number from summary.json (flat "key": value lines as io/json_summary writes them).
jnum() { grep -m1 "\"$2\"" "$1" | sed 's/.*: *//; s/[",]//g'; }
particles=$(jnum "$out/run/summary.json" particles)
steps=$(jnum "$out/run/summary.json" steps)
wall=$(jnum "$out/run/summary.json" wall_time_s)

{
  echo "two disks: $particles particles, 316 x 316 cells"
  # bench.csv: the machine's context lines, then the header (name,iterations,real_time,...,
  # then the counters in alphabetical order, quoted) and one row per benchmark.
  awk -F, '/^name,/ { for (i = 1; i <= NF; i++) { gsub(/"/, "", $i); c[$i] = i }; next }
    /BM_TwoDisks/ { gsub(/"/, "", $1)
      printf "%-34s %8.2f M particle-updates/s per core  (%6.2f M/s in all)  solver %5.0f B/particle, process peak RSS %5.0f B/particle\n",
        $1, $c["updates_per_s_per_core"] / 1e6, $c["updates_per_s"] / 1e6,
        $c["solver_bytes_per_particle"], $c["peak_rss_bytes_per_particle"] }' "$out/bench.csv"
  echo "ecm-mpm whole run: $steps steps in $wall s (set-up and output included) on $threads threads" \
    "(OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-unset})"
  if [[ -n $rss_kb ]]; then
    awk -v kb="$rss_kb" -v n="$particles" 'BEGIN { printf "ecm-mpm peak resident memory: %.1f MB, %.0f bytes per particle\n", kb / 1024, kb * 1024 / n }'
  fi
  echo "energies (history.csv, every 100 steps): time, kinetic, strain"
  h=$out/run/history.csv
  ck=$(head -1 "$h" | tr ',' '\n' | grep -nx kinetic_Nmm | cut -d: -f1)
  cs=$(head -1 "$h" | tr ',' '\n' | grep -nx strain_Nmm | cut -d: -f1)
  awk -F, -v k="$ck" -v s="$cs" 'NR > 1 { printf "  %8.4f  %.6e  %.6e\n", $1, $k, $s }' "$h"
} | tee "$out/summary.txt"
