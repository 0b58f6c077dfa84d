#!/usr/bin/env bash
# The whole default test suite: installs what is missing, builds (Release), runs every test
# not labelled `slow`. Usage: scripts/test.sh   (CI runs exactly this, see .ci/run)
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2
ctest --test-dir build -LE slow --output-on-failure -j2
