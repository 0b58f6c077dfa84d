#!/usr/bin/env bash
# Whole-process speed-up of ecm-mpm with the thread count, measured the way a shared machine
# allows: every (scene, thread count) is run REPS times, interleaved (scene by scene, thread
# count by thread count, then the next repetition), so that a minute of noise from other work
# falls on all of them alike; each time is the wall time of the whole process (/usr/bin/time)
# minus the median time of the same process stopped after its first step (reading the scene,
# seeding, the first scatter: the set-up); the speed-up is the ratio of the medians.
# Usage: scripts/scaling.sh [-r REPS] [-t "1 2 4 8"] [-n STEPS] [-b "ECM_MPM..."] [-o OUT_DIR] SCENE...
#   defaults: 5 repetitions, threads "1 2", 500 steps, ./build/mpm/ecm-mpm, results/scaling,
#   scene data/mpm/two-disks.yaml. Every run stops after STEPS steps (--max-steps), with the
#   checkpoint that --max-steps writes (in the set-up runs too, so it cancels in the difference).
#   -b takes several builds (quoted, space-separated) to compare them side by side, interleaved.
#   Paths (scenes, builds, OUT_DIR) are taken from the repository root.
# Writes OUT_DIR/times.csv (build, scene, threads, repetition, kind, seconds) and OUT_DIR/summary.txt,
# and prints the summary: build, scene, threads, median [min-max] s (set-up subtracted), the speed-up
# against the first (smallest) thread count.
# Example on a bigger machine:
#   scripts/scaling.sh -r 5 -t "1 2 4 8 16 32 64" data/mpm/two-disks.yaml data/mpm/two-disks-usl.yaml
#   scripts/scaling.sh -r 3 -t "1 2 4 8 16" -n 20000 data/den/den-4b-medium.yaml
# On a machine shared with other tenants, check that a second core is whole at the time: the
# summary also gives the speed-up of a compute loop with no shared data (ceiling), run with
# the same thread counts before and after the measurement.
set -euo pipefail
cd "$(dirname "$0")/.."
reps=5 threads="1 2" steps=500 bins=./build/mpm/ecm-mpm out=results/scaling
while getopts "r:t:n:b:o:h" opt; do
  case $opt in
    r) reps=$OPTARG ;;
    t) threads=$OPTARG ;;
    n) steps=$OPTARG ;;
    b) bins=$OPTARG ;;
    o) out=$OPTARG ;;
    *) sed -n '2,21p' "$0" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
scenes=("$@")
[[ ${#scenes[@]} -gt 0 ]] || scenes=(data/mpm/two-disks.yaml)
for bin in $bins; do [[ -x $bin ]] || { echo "error: $bin not built (cmake --build build)" >&2; exit 2; }; done
[[ -x /usr/bin/time ]] || { echo "error: /usr/bin/time missing (apt-get install -y time)" >&2; exit 2; }
for s in "${scenes[@]}"; do [[ -f $s ]] || { echo "error: no scene $s" >&2; exit 2; }; done
[[ $reps =~ ^[1-9][0-9]*$ && $steps =~ ^[1-9][0-9]*$ ]] || { echo "error: -r and -n take positive integers" >&2; exit 2; }
for t in $threads; do [[ $t =~ ^[1-9][0-9]*$ ]] || { echo "error: -t takes positive integers, got '$t'" >&2; exit 2; }; done
mkdir -p "$out"
csv=$out/times.csv
echo "build,scene,threads,repetition,kind,seconds" >"$csv"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Wall seconds of one run of build $bin: $1 scene, $2 threads, $3 steps. Exit code 3 is the stop
# at --max-steps; a run that ends before (exit 0) is timed whole, and said.
wall() {
  local rc=0
  /usr/bin/time -o "$scratch/time" -f "%e" "$bin" "$1" --out "$scratch/run" --no-vtu --no-plot -q \
    --threads "$2" --max-steps "$3" >/dev/null 2>"$scratch/stderr" || rc=$?
  if [[ $rc -ne 3 ]]; then
    [[ $rc -eq 0 ]] && echo "note: $1 ended before $3 steps" >&2 ||
      { echo "error: $bin $1 -t $2 --max-steps $3 failed (exit $rc):" >&2; cat "$scratch/stderr" >&2; return 1; }
  fi
  tail -n1 "$scratch/time"
}

# The speed-up a compute loop with no shared data gets from the thread counts (awk's sqrt sum,
# one process per thread): what the machine's cores give at the moment, the ceiling.
ceiling() {
  local t k start end one=""
  for t in $threads; do
    start=$(date +%s.%N)
    for ((k = 0; k < t; ++k)); do awk 'BEGIN { s = 0; for (i = 1; i <= 3e7; ++i) s += sqrt(i); print s }' >/dev/null & done
    wait
    end=$(date +%s.%N)
    local secs; secs=$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')
    [[ -n $one ]] || one=$secs
    printf "%s:%.2f " "$t" "$(awk -v o="$one" -v s="$secs" -v t="$t" 'BEGIN { print t * o / s }')"
  done
}

before=$(ceiling)
echo "compute-loop speed-up before: $before" >&2
for ((r = 1; r <= reps; ++r)); do
  for s in "${scenes[@]}"; do
    for t in $threads; do
      for bin in $bins; do
        secs=$(wall "$s" "$t" 1) || exit 1
        echo "$bin,$s,$t,$r,setup,$secs" >>"$csv"
        secs=$(wall "$s" "$t" "$steps") || exit 1
        echo "$bin,$s,$t,$r,run,$secs" >>"$csv"
      done
    done
  done
  echo "repetition $r of $reps done" >&2
done
after=$(ceiling)

{
  echo "ecm-mpm whole-process times, $steps steps, set-up subtracted (median of $reps, min-max), $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) CPUs"
  echo "compute-loop speed-up (ceiling) before: $before after: $after"
  awk -F, 'NR > 1 { key = $1 "," $2 "," $3; if ($5 == "setup") su[key] = su[key] " " $6; else run[key] = run[key] " " $6 }
    function median(list,   a, n, i, j, x) {
      n = split(list, a, " ")
      for (i = 2; i <= n; ++i) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; --j) a[j + 1] = a[j]; a[j + 1] = x }
      lo = a[1]; hi = a[n]
      return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
    }
    END {
      for (key in run) {
        split(key, k, ",")
        s = median(su[key]); m = median(run[key])
        printf "%s %s %s %.3f %.3f %.3f\n", k[1], k[2], k[3], m - s, lo - s, hi - s
      }
    }' "$csv" | sort -k1,1 -k2,2 -k3,3n |
    awk '{ if ($1 "," $2 != run) { run = $1 "," $2; base = $4; t0 = $3 }
           printf "%s %s %3d threads  %8.3f s [%.3f-%.3f]  speed-up %.2f (against %d)\n", $1, $2, $3, $4, $5, $6, base / $4, t0 }'
} | tee "$out/summary.txt"
