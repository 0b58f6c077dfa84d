#!/usr/bin/env bash
# The whole default test suite: installs what is missing, builds (Release), runs every test
# not labelled `slow`, CalculiX with ecm's UMAT included (built here from Debian's source
# package, scripts/calculix/build-ccx.sh). Usage: scripts/test.sh   (CI runs exactly this, see .ci/run)
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2
cmake --build build --target calculix
ctest --test-dir build -LE slow --output-on-failure -j2
