#!/usr/bin/env bash
# The validation of ecm against two physical tests (docs/validation.md): Nooru-Mohamed's
# double-edge-notched panel (load path 4b) and Winkler's L-shaped panel, with each rig's own
# boundary conditions and gauges, material parameters from the tests' material data and the band
# law's shape from Hordijk's curve; nothing fitted to the structural curves.
# Run after the build (cmake -S . -B build -G Ninja && ninja -C build).
# Usage: scripts/validate.sh [OUT_DIR] [WHAT...]   (default: results/validation quick)
#   WHAT: quick     the coarse meshes: DEN explicit and implicit, L-panel explicit and implicit
#                   (one and two bands), and the DEN's gap accounting (today's scene, the rig with
#                   the paper's law, the second band), about 6 minutes on 2 threads
#         medium    the medium meshes (DEN and L-panel, explicit and implicit, one and two bands),
#                   about 1.5 hours (the implicit DEN alone took 69 minutes on one shared thread)
#         fine      the fine meshes (explicit, one and two bands), about 1.5 hours
#         all       quick medium fine
#         RUN       one run by name (see `scene` below; *-tracked: with tracked crack paths)
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

# run name -> scene file (variants are written to OUT_DIR/scenes/ from a shipped scene, one line changed)
declare -A scene=(
  [den-rig-coarse]=data/validation/den-4b-rig-coarse.yaml
  [den-rig-coarse-implicit]=data/validation/den-4b-rig-coarse-implicit.yaml
  [den-rig-medium]=data/validation/den-4b-rig-medium.yaml
  [den-rig-medium-implicit]=data/validation/den-4b-rig-medium-implicit.yaml
  [den-rig-fine]=data/validation/den-4b-rig-fine.yaml
  [den-today-coarse]=data/den/den-4b-coarse.yaml
  [den-rig-coarse-paper-law]=variant
  [den-rig-coarse-second-band]=variant
  [den-rig-coarse-second-band-implicit]=variant
  [den-rig-medium-second-band]=variant
  [den-rig-fine-second-band]=variant
  [lpanel-coarse]=data/validation/lpanel-coarse.yaml
  [lpanel-coarse-implicit]=data/validation/lpanel-coarse-implicit.yaml
  [lpanel-coarse-paper-n]=variant
  [lpanel-coarse-second-band]=variant
  [lpanel-medium-second-band]=variant
  [lpanel-fine-second-band]=variant
  [lpanel-coarse-second-band-implicit]=variant
  [lpanel-medium-second-band-implicit]=variant
  [lpanel-medium]=data/validation/lpanel-medium.yaml
  [lpanel-medium-implicit]=data/validation/lpanel-medium-implicit.yaml
  [lpanel-fine]=data/validation/lpanel-fine.yaml
  [den-rig-coarse-tracked]=variant
  [den-rig-coarse-tension]=variant
  [den-rig-coarse-tension-tracked]=variant
  [den-rig-medium-tracked]=variant
  [den-rig-fine-tracked]=variant
  [lpanel-coarse-tracked]=variant
  [lpanel-medium-tracked]=variant
  [lpanel-fine-tracked]=variant
  [lpanel-coarse-second-band-tracked]=variant
  [lpanel-medium-second-band-tracked]=variant
  [lpanel-fine-second-band-tracked]=variant
  [den-rig-coarse-second-band-tracked]=variant
  [den-rig-medium-second-band-tracked]=variant
  [den-rig-fine-second-band-tracked]=variant
  [den-rig-coarse-implicit-tracked]=variant
  [lpanel-coarse-implicit-tracked]=variant
  [den-rig-coarse-second-band-implicit-tracked]=variant
  [lpanel-coarse-second-band-implicit-tracked]=variant
)
runs=()
for w in "$@"; do
  case "$w" in
    quick) runs+=(den-today-coarse den-rig-coarse-paper-law den-rig-coarse den-rig-coarse-implicit den-rig-coarse-second-band
                  lpanel-coarse lpanel-coarse-paper-n lpanel-coarse-second-band lpanel-coarse-implicit lpanel-coarse-second-band-implicit) ;;
    medium) runs+=(den-rig-medium den-rig-medium-second-band den-rig-medium-implicit lpanel-medium lpanel-medium-second-band lpanel-medium-implicit lpanel-medium-second-band-implicit) ;;
    fine) runs+=(den-rig-fine den-rig-fine-second-band lpanel-fine lpanel-fine-second-band) ;;
    all) runs+=(den-today-coarse den-rig-coarse-paper-law den-rig-coarse den-rig-coarse-implicit den-rig-coarse-second-band
                lpanel-coarse lpanel-coarse-paper-n lpanel-coarse-second-band lpanel-coarse-implicit den-rig-medium lpanel-medium
                den-rig-medium-implicit lpanel-medium-second-band lpanel-medium-implicit
                lpanel-coarse-second-band-implicit lpanel-medium-second-band-implicit den-rig-medium-second-band
                den-rig-fine den-rig-fine-second-band lpanel-fine lpanel-fine-second-band) ;;
    report) ;;
    *) [[ -n ${scene[$w]:-} ]] || { echo "usage: scripts/validate.sh [OUT_DIR] [quick|medium|fine|all|report|RUN]... (RUN: ${!scene[*]})" >&2; exit 2; }
       runs+=("$w") ;;
  esac
done

# A variant: a shipped scene with its material swapped (the file and the body's material name), or
# with tracked crack paths (docs/model.md, "Crack paths").
variant() {
  local name=$1 from material tracked=0 tension=0
  case "$name" in
    *-second-band-tracked | *-second-band-implicit-tracked) from=$(variant "${name%-tracked}") || exit 2; tracked=1 ;;  # (a material swap, then tracked)
    *-tracked) from=data/validation/${name%-tracked}.yaml; from=${from/den-rig-/den-4b-rig-}; tracked=1 ;;
  esac
  case "$name" in
    den-rig-coarse-tension*) from=data/validation/den-4b-rig-coarse.yaml; tension=1 ;;
  esac
  if [[ $tracked == 1 || $tension == 1 ]]; then
    local rule='&' shear='&'
    [[ $tracked == 1 ]] && rule='  crack_path: tracked'
    [[ $tension == 1 ]] && shear='    x: free   # P_s = 0: the DEN in pure tension'
    sed -e "s|{file: ../materials/|{file: $PWD/data/materials/|" -e "s|^name: .*|name: $name|" \
        -e "s|^  crack_path: free .*|$rule|" -e "s|^    x: {force: {type: table.*|$shear|" "$from" > "$out/scenes/$name.yaml"
    if [[ $tracked == 1 ]] && ! grep -q '^  crack_path: tracked$' "$out/scenes/$name.yaml"; then
      echo "error: $from has no 'crack_path: free' line to make tracked" >&2
      exit 2
    fi
    echo "$out/scenes/$name.yaml"
    return
  fi
  case "$name" in
    den-rig-coarse-paper-law) from=data/validation/den-4b-rig-coarse.yaml; material=den-concrete ;;
    den-rig-coarse-second-band) from=data/validation/den-4b-rig-coarse.yaml; material=den-concrete-hordijk-second-band ;;
    den-rig-coarse-second-band-implicit) from=data/validation/den-4b-rig-coarse-implicit.yaml; material=den-concrete-hordijk-second-band ;;
    den-rig-medium-second-band) from=data/validation/den-4b-rig-medium.yaml; material=den-concrete-hordijk-second-band ;;
    den-rig-fine-second-band) from=data/validation/den-4b-rig-fine.yaml; material=den-concrete-hordijk-second-band ;;
    lpanel-coarse-paper-n) from=data/validation/lpanel-coarse.yaml; material=lpanel-concrete-paper-n ;;
    lpanel-coarse-second-band) from=data/validation/lpanel-coarse.yaml; material=lpanel-concrete-hordijk-second-band ;;
    lpanel-medium-second-band) from=data/validation/lpanel-medium.yaml; material=lpanel-concrete-hordijk-second-band ;;
    lpanel-coarse-second-band-implicit) from=data/validation/lpanel-coarse-implicit.yaml; material=lpanel-concrete-hordijk-second-band ;;
    lpanel-medium-second-band-implicit) from=data/validation/lpanel-medium-implicit.yaml; material=lpanel-concrete-hordijk-second-band ;;
    lpanel-fine-second-band) from=data/validation/lpanel-fine.yaml; material=lpanel-concrete-hordijk-second-band ;;
  esac
  local old
  old=$(sed -n 's|.*{file: ../materials/\([a-z-]*\)\.yaml}.*|\1|p' "$from" | head -1)
  sed -e "s|{file: ../materials/$old.yaml}|{file: $PWD/data/materials/$material.yaml}|" \
      -e "s|material: $old}|material: $material}|" -e "s|^name: .*|name: $name|" "$from" > "$out/scenes/$name.yaml"
  echo "$out/scenes/$name.yaml"
}

failed=()
for r in "${runs[@]}"; do
  s=${scene[$r]}
  if [[ $s == variant ]]; then
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
    den-rig-coarse-paper-law)  # also against the upper frame's travel (a row of docs/validation.md); the gauges' last
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
