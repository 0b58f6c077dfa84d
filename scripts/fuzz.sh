#!/usr/bin/env bash
# Fuzzing with libFuzzer (clang): builds the harnesses of fuzz/ under ASan/UBSan in build-fuzz/
# and runs each for SECONDS (default 60) from its seed corpus in fuzz/corpus/<harness>/.
# New interesting inputs go to build-fuzz/work/<harness>/; crashes to build-fuzz/crashes/.
# A crash input belongs in fuzz/corpus/<harness>/ (and in a regression test) once fixed.
# Usage: scripts/fuzz.sh [SECONDS] [HARNESS...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
./scripts/setup.sh
export DEBIAN_FRONTEND=noninteractive
dpkg-query -W -f='${Status}' clang libclang-rt-dev 2>/dev/null | grep -q "install ok installed" ||
  { apt-get update -qq && apt-get install -y -qq clang libclang-rt-dev >/dev/null; }
CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DECM_FUZZ=ON \
  -DECM_BUILD_TESTS=OFF -DECM_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j2
harnesses=("$@")
[[ ${#harnesses[@]} -gt 0 ]] || harnesses=($(cd build-fuzz/fuzz && ls fuzz_* | grep -v '\.'))
mkdir -p build-fuzz/crashes
status=0
for h in "${harnesses[@]}"; do
  name=${h#fuzz_}
  mkdir -p "build-fuzz/work/$name"
  echo "== $h: ${seconds} s"
  if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
      "build-fuzz/fuzz/$h" "build-fuzz/work/$name" "fuzz/corpus/$name" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -artifact_prefix="build-fuzz/crashes/$name-" -print_final_stats=1 \
      2> "build-fuzz/$name.log"; then
    echo "   FINDING: see build-fuzz/$name.log and build-fuzz/crashes/"; status=1
  fi
  grep -E "stat::number_of_executed_units|stat::new_units_added" "build-fuzz/$name.log" | sed 's/^/   /' || true
done
exit $status
