#!/usr/bin/env bash
# The notched beam in three-point bending (docs/validation.md, "3. Grégoire's notched beam"): the
# shipped scenes of data/validation/beam-*.yaml run, compared with the cohesive reference
# (data/reference/beam-band-node.csv) and plotted over the test's envelope. Run after the build.
# Usage: scripts/beam.sh [OUT_DIR] [RUN...]   (default: results/beam coarse-implicit medium-implicit)
#   RUN: coarse-implicit (3 s), medium-implicit (15 s), fine-implicit (2 min), coarse (explicit,
#        16 s), medium (explicit, 15 min), fine (explicit, about 2 hours)
# Writes OUT_DIR/RUN/ (ecm-mpm's output folder), OUT_DIR/beam.csv, beam.json, beam.png and the table
# on stdout; exits non-zero and lists the failed runs when one fails. Units: mm, N, MPa, t, s.
# Threads: $BEAM_THREADS (default 2); binary: $BEAM_BIN (default ./build/mpm/ecm-mpm).
set -uo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/beam}
shift || true
[[ $# -gt 0 ]] || set -- coarse-implicit medium-implicit
bin=${BEAM_BIN:-./build/mpm/ecm-mpm}
[[ -x $bin ]] || { echo "error: $bin not built (cmake -S . -B build -G Ninja && ninja -C build)" >&2; exit 2; }
mkdir -p "$out"
failed=()
for run in "$@"; do
  scene=data/validation/beam-$run.yaml
  [[ -f $scene ]] || { echo "error: no scene $scene" >&2; exit 2; }
  echo "== beam-$run" >&2
  "$bin" "$scene" --out "$out/$run" --threads "${BEAM_THREADS:-2}" || failed+=("$run")
done
python3 scripts/validation/beam_compare.py "$out" "$@" || true
command -v gnuplot >/dev/null && gnuplot "$out/beam.gp" 2>/dev/null && echo "plot: $out/beam.png" >&2
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "failed runs: ${failed[*]}" >&2
  exit 1
fi
