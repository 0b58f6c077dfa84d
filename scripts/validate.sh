#!/usr/bin/env bash
# The validation of ecm against two physical tests (docs/validation.md): Nooru-Mohamed's
# double-edge-notched panel (load path 4b) and Winkler's L-shaped panel, with each rig's own
# boundary conditions and gauges, material parameters from the tests' material data and the band
# law's shape from Hordijk's curve; nothing fitted to the structural curves.
# Run after the build (cmake -S . -B build -G Ninja && ninja -C build).
# Usage: scripts/validate.sh [OUT_DIR] [WHAT...]   (default: results/validation quick)
#   WHAT: quick     the coarse meshes: the validation scenes (tracked crack paths, second band) explicit
#                   and implicit, with one band beside them, and the DEN's gap accounting from the
#                   paper's scene to the validation scene, about 6 minutes on 1 thread
#         medium    the medium meshes (DEN and L-panel, explicit and implicit, second band and one
#                   band), about 25 minutes on 1 thread
#         fine      the fine meshes (explicit and implicit, second band; explicit, one band), about
#                   2 hours on 1 thread
#         free      the runs of docs/validation.md's tables before crack paths were tracked (the free
#                   rule), several hours
#         all       quick medium fine
#         RUN       one run by name: a validation scene (below) and modifiers, in this order, each
#                   changing the scene in one respect: -tension (explicit DEN: P_s = 0); -one-band
#                   (the band law without the second band), -paper-law (DEN: the paper's law, one
#                   band) or -paper-n (L-panel: the paper's n = 0.128, one band); -free (the free
#                   crack path rule); e.g. den-rig-medium-implicit-one-band, den-rig-coarse-paper-law-free
#         report    no run: the tables and plots of what is in OUT_DIR
# Writes OUT_DIR/RUN/ (ecm-mpm's output folder, without VTU snapshots, plus compare.csv and
# compare.json), OUT_DIR/den.png and OUT_DIR/lpanel.png (ecm against the tests), OUT_DIR/summary.json
# and the tables on stdout. Units: mm, N, MPa, t, s.
# Threads: $VALIDATE_THREADS (default 2); binary: $VALIDATE_BIN (default ./build/mpm/ecm-mpm).
# A run stopped with a checkpoint (Ctrl-C or a signal: ecm-mpm writes one as it stops) is resumed
# from it when the script is run again with the same OUT_DIR.
# Exit status: 0 when every run completed and has its comparison; 1 otherwise, with the failed
# runs listed at the end. $VALIDATE_KNOWN_FAILURES (run names, space-separated) lists runs known to
# fail: they are reported, not counted, and one that completes is counted (take it off the list).
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/mpm_runs.sh  # failureKind
out=${1:-results/validation}
shift || true
[[ $# -gt 0 ]] || set -- quick
threads=${VALIDATE_THREADS:-2}
bin=${VALIDATE_BIN:-./build/mpm/ecm-mpm}
[[ -x $bin ]] || { echo "error: $bin not built (cmake -S . -B build -G Ninja && ninja -C build)" >&2; exit 2; }
mkdir -p "$out/scenes"

# The shipped scenes by run name; every other run is one of them with modifiers (variant below).
declare -A scene=(
  [den-rig-coarse]=data/validation/den-4b-rig-coarse.yaml
  [den-rig-coarse-implicit]=data/validation/den-4b-rig-coarse-implicit.yaml
  [den-rig-medium]=data/validation/den-4b-rig-medium.yaml
  [den-rig-medium-implicit]=data/validation/den-4b-rig-medium-implicit.yaml
  [den-rig-fine]=data/validation/den-4b-rig-fine.yaml
  [den-rig-fine-implicit]=data/validation/den-4b-rig-fine-implicit.yaml
  [den-today-coarse]=data/den/den-4b-coarse.yaml
  [lpanel-coarse]=data/validation/lpanel-coarse.yaml
  [lpanel-coarse-implicit]=data/validation/lpanel-coarse-implicit.yaml
  [lpanel-medium]=data/validation/lpanel-medium.yaml
  [lpanel-medium-implicit]=data/validation/lpanel-medium-implicit.yaml
  [lpanel-fine]=data/validation/lpanel-fine.yaml
  [lpanel-fine-implicit]=data/validation/lpanel-fine-implicit.yaml
)
modifiers=(one-band paper-law paper-n tension free)
runs=()
set -- $(printf '%s\n' "$@" | sed 's/^all$/quick medium fine/')
for w in "$@"; do
  case "$w" in
    quick) runs+=(den-today-coarse den-rig-coarse-paper-law-free den-rig-coarse-one-band-free den-rig-coarse-free
                  den-rig-coarse den-rig-coarse-implicit den-rig-coarse-one-band den-rig-coarse-implicit-one-band den-rig-coarse-tension
                  lpanel-coarse lpanel-coarse-implicit lpanel-coarse-one-band lpanel-coarse-implicit-one-band lpanel-coarse-paper-n) ;;
    medium) runs+=(den-rig-medium den-rig-medium-implicit den-rig-medium-one-band den-rig-medium-implicit-one-band
                   lpanel-medium lpanel-medium-implicit lpanel-medium-one-band lpanel-medium-implicit-one-band) ;;
    fine) runs+=(den-rig-fine den-rig-fine-implicit den-rig-fine-one-band lpanel-fine lpanel-fine-implicit lpanel-fine-one-band) ;;
    free) runs+=(den-today-coarse den-rig-coarse-paper-law-free den-rig-coarse-one-band-free den-rig-coarse-implicit-one-band-free
                 den-rig-coarse-free den-rig-coarse-implicit-free den-rig-medium-one-band-free den-rig-medium-implicit-one-band-free
                 den-rig-medium-free den-rig-fine-one-band-free den-rig-fine-free den-rig-coarse-tension-one-band-free
                 lpanel-coarse-one-band-free lpanel-coarse-implicit-one-band-free lpanel-coarse-paper-n-free lpanel-coarse-free
                 lpanel-medium-one-band-free lpanel-medium-free lpanel-fine-one-band-free lpanel-medium-implicit-one-band-free
                 lpanel-fine-free lpanel-coarse-implicit-free lpanel-medium-implicit-free) ;;
    report) ;;
    *) runs+=("$w") ;;
  esac
done

# A run's scene and modifiers, "BASE MODIFIER...", on stdout; nothing when the name is not a
# validation scene followed by modifiers, each at most once and each one that applies to its test.
parseRun() {
  local base=$1 found=() m again=1
  while [[ -z ${scene[$base]:-} && $again == 1 ]]; do
    again=0
    for m in "${modifiers[@]}"; do
      if [[ $base == *-$m ]]; then base=${base%-$m}; found+=("$m"); again=1; break; fi
    done
  done
  [[ -n ${scene[$base]:-} ]] || return 0
  [[ $base == den-today-* && ${#found[@]} -gt 0 ]] && return 0  # the paper's scene is not varied
  local materials=0 seen=" "
  for m in "${found[@]}"; do
    [[ $seen == *" $m "* ]] && return 0
    seen+="$m "
    case "$m" in one-band | paper-law | paper-n) materials=$((materials + 1)) ;; esac
    case "$m:$base" in paper-law:lpanel-* | tension:lpanel-* | tension:*-implicit | paper-n:den-*) return 0 ;; esac
  done
  [[ $materials -le 1 ]] || return 0
  # One name per scene: the modifiers in the order of the usage (tension, material, free).
  local canonical=$base k
  for m in tension one-band paper-law paper-n free; do
    for k in "${found[@]}"; do [[ $k == "$m" ]] && canonical+="-$m"; done
  done
  [[ $canonical == "$1" ]] && echo "$base ${found[*]}"
  return 0
}

# A variant: a shipped scene with lines changed, written to OUT_DIR/scenes/NAME.yaml: its name; the
# material file and the body's material name (-one-band, -paper-law, -paper-n); the crack path rule
# (-free); the upper frame's P_s (-tension).
variant() {
  local name=$1 parsed from m material='' free=0 tension=0
  read -r -a parsed <<< "$(parseRun "$name")"
  from=${scene[${parsed[0]}]}
  for m in "${parsed[@]:1}"; do
    case "$m:${parsed[0]}" in
      one-band:den-*) material=den-concrete-hordijk ;;
      one-band:lpanel-*) material=lpanel-concrete-hordijk ;;
      paper-law:*) material=den-concrete ;;
      paper-n:*) material=lpanel-concrete-paper-n ;;
      free:*) free=1 ;;
      tension:*) tension=1 ;;
    esac
  done
  local old rule='&' shear='&' note='&'
  old=$(sed -n 's|.*{file: ../materials/\([a-z-]*\)\.yaml}.*|\1|p' "$from" | head -1)
  [[ -n $material ]] || material=$old
  local bandNote='&'
  if [[ $material != "$old" ]]; then
    note="{file: $PWD/data/materials/$material.yaml}   # $material (scripts/validate.sh)"
    bandNote="# This variant's material: $material (scripts/validate.sh $name)."
  fi
  [[ $free == 1 ]] && rule='  crack_path: free'
  [[ $tension == 1 ]] && shear='    x: free   # P_s = 0: the DEN in pure tension'
  sed -e "s|{file: ../materials/$old.yaml}|{file: $PWD/data/materials/$material.yaml}|" -e "s|{file: $PWD/data/materials/$material.yaml}.*|$note|" \
      -e "s|material: $old}|material: $material}|" -e "s|^name: .*|name: $name|" \
      -e "/^# The band law with the second band/{N;s|.*|$bandNote|}" \
      -e "s|^  crack_path: tracked .*|$rule|" -e "s|^    x: {force: {type: table.*|$shear|" "$from" > "$out/scenes/$name.yaml"
  if [[ $free == 1 ]] && ! grep -q '^  crack_path: free$' "$out/scenes/$name.yaml"; then
    echo "error: $from has no 'crack_path: tracked' line to make free" >&2
    exit 2
  fi
  if [[ $tension == 1 ]] && ! grep -q '^    x: free   # P_s = 0' "$out/scenes/$name.yaml"; then
    echo "error: $from has no P_s line to take off" >&2
    exit 2
  fi
  echo "$out/scenes/$name.yaml"
}

# Each run once, in the order asked; every name is checked and every variant's scene written before
# the first run (a typo found after hours of runs is no use).
declare -A asked=()
unique=()
for r in "${runs[@]}"; do
  [[ -n ${asked[$r]:-} ]] || unique+=("$r")
  asked[$r]=1
done
runs=("${unique[@]}")
for r in "${runs[@]}"; do
  [[ -n $(parseRun "$r") ]] || { echo "usage: scripts/validate.sh [OUT_DIR] [quick|medium|fine|free|all|report|RUN]... (RUN: one of ${!scene[*]}, each but den-today-coarse followed by any of -tension, -one-band, -paper-law, -paper-n, -free in this order; not '$r')" >&2; exit 2; }
  [[ -n ${scene[$r]:-} ]] || variant "$r" > /dev/null || exit 2
done

failed=()
for r in "${runs[@]}"; do
  s=${scene[$r]:-}
  if [[ -z $s ]]; then
    s=$(variant "$r") || exit 2  # (a scene it cannot make: refused, named on stderr)
  fi
  echo "== $r ($s)" >&2
  start=$SECONDS
  if [[ -f $out/$r/checkpoint.bin ]] && grep -q '"status": *"stopped"' "$out/$r/summary.json" 2>/dev/null; then
    # stopped before (Ctrl-C, a signal, --max-steps): resumed; a failed run starts afresh
    echo "$r: resuming from $out/$r/checkpoint.bin" >&2
    "$bin" "$s" --restart "$out/$r" --threads "$threads" --no-vtu -q
  else
    "$bin" "$s" --out "$out/$r" --threads "$threads" --no-vtu -q
  fi
  code=$?
  echo "$r: exit $code, $((SECONDS - start)) s" >&2
  if [[ " ${VALIDATE_KNOWN_FAILURES:-} " == *" $r "* ]]; then
    [[ $code == 0 ]] && failed+=("$r (listed in VALIDATE_KNOWN_FAILURES, but it completed: take it off the list)") \
                     || echo "$r: a known failure (VALIDATE_KNOWN_FAILURES)" >&2
  elif [[ $code != 0 ]]; then
    failed+=("$r (exit $code$(failureKind "$out/$r"): $out/$r/summary.json)")
  fi
done

# The comparisons (scripts/validation/compare.py) and the report (scripts/validation/report.py).
for d in "$out"/*/; do
  r=$(basename "$d")
  [[ -f $d/history.csv ]] || continue
  case "$r" in
    den-today-*) python3 scripts/validation/compare.py den "$d" data/experiments/nooru-mohamed-4b.txt --t0 0.0008 --delta top > "$d/compare.json" ;;
    den-rig-coarse-paper-law*)  # also against the upper frame's travel (a row of docs/validation.md); the gauges' last
      python3 scripts/validation/compare.py den "$d" data/experiments/nooru-mohamed-4b.txt --t0 0.0008 --delta platen > "$d/compare-platen.json"
      python3 scripts/validation/compare.py den "$d" data/experiments/nooru-mohamed-4b.txt --t0 0.0008 > "$d/compare.json" ;;
    den-*implicit*) python3 scripts/validation/compare.py den "$d" data/experiments/nooru-mohamed-4b.txt --t0 1 > "$d/compare.json" ;;
    den-*) python3 scripts/validation/compare.py den "$d" data/experiments/nooru-mohamed-4b.txt --t0 0.0008 > "$d/compare.json" ;;
    lpanel-*) python3 scripts/validation/compare.py lpanel "$d" data/experiments/winkler-lpanel-envelope.csv data/experiments/winkler-lpanel-series-a.csv > "$d/compare.json" ;;
  esac
done
python3 scripts/validation/report.py "$out"
# Every run asked for has its comparison (a failed run too: its status is in the table), and a
# run that failed fails the script, named at the end.
status=0
for r in "${runs[@]}"; do
  [[ -s $out/$r/compare.json ]] || { echo "error: $r has no comparison ($out/$r)" >&2; status=1; }
done
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "failed runs (${#failed[@]} of ${#runs[@]}):" >&2
  printf '  %s\n' "${failed[@]}" >&2
  status=1
fi
exit $status
