#!/usr/bin/env bash
# The paper in one command: installs what is missing, builds, then
#   1. calibrates the DEN concrete (E_p for G_F = 0.11 N/mm, h = 0.05 mm, n = 0.128),
#   2. runs the point snap-back study (enriched point and smeared crack, H = 1 mm ... 2 m),
#   3. runs the DEN example on the coarse mesh (when ecm-mpm and its scene exist),
# and writes their plots, CSVs and summaries under results/paper/ (or the folder given).
# Usage: scripts/paper.sh [OUTPUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/paper}
./scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
# Only the tools it runs (not the tests, benchmarks and the Python module: scripts/test.sh builds
# those); ecm-mpm where the tree has it.
targets=(ecm-calibrate ecm-point)
if [[ -f mpm/CMakeLists.txt ]]; then targets+=(ecm-mpm); fi
cmake --build build -j2 --target "${targets[@]}"
mkdir -p "$out"
parts=()
failed=()  # the parts that did not complete: listed at the end, and the exit status is 1

echo "== 1. calibration of the DEN concrete (ecm-calibrate)"
./build/calibration/ecm-calibrate --E 32000 --nu 0.2 --ft 3.0 --GF 0.11 --h 0.05 --n 0.128 \
  --density 2.4e-9 --name den-concrete-calibrated --out "$out/calibration" \
  --write-material "$out/calibration/den-concrete-calibrated.yaml"
parts+=("calibration")

echo "== 2. point snap-back study (ecm-point --study)"
./build/driver/ecm-point --study data/point/snapback-study.yaml --out "$out/snapback-study"
parts+=("snapback-study")

if [[ -x build/mpm/ecm-mpm && -f data/den/den-4b-coarse.yaml ]]; then
  echo "== 3. DEN mixed-mode fracture, coarse mesh (ecm-mpm)"
  # scripts/den.sh: the run (ecm-mpm's folder den-coarse/coarse), the load-displacement plot,
  # the damage and crack maps, the table; a failed run is kept in the table with its status.
  scripts/den.sh "$out/den-coarse" coarse || {
    echo "   DEN coarse run stopped early: see $out/den-coarse/coarse/summary.json"
    failed+=("den-coarse ($out/den-coarse/coarse/summary.json)")
  }
  parts+=("den-coarse")
fi

# One summary: the parts' summary.json side by side.
{
  echo "{"
  for i in "${!parts[@]}"; do
    sep=$([[ $i -lt $((${#parts[@]} - 1)) ]] && echo "," || echo "")
    printf '"%s": ' "${parts[$i]}"
    cat "$out/${parts[$i]}/summary.json"
    echo "$sep"
  done
  echo "}"
} > "$out/summary.json"
echo "== done: $out/summary.json, plots: $(cd "$out" && find . -maxdepth 2 -name '*.png' -path './*/*' | grep -v '/enriched-\|/smeared-' | sort | tr '\n' ' ')"
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "failed parts (their summaries are in the summary above):" >&2
  printf '  %s\n' "${failed[@]}" >&2
  exit 1
fi
