#!/usr/bin/env bash
# Usage: consumer_test.sh BUILD_DIR SOURCE_DIR WORK_DIR CXX
# Installs the build into WORK_DIR/prefix, builds examples/point_path against it out of tree and
# checks what it prints against the model: before onset the path is uniaxial stress
# (eps_yy = -nu eps_xx, nu = 0.2), so sigma_xx = E eps_xx with E = 32000 MPa and onset comes at
# sigma_xx = f_t' = 3 MPa (eps_xx = 9.375e-5, step 94 of 1e-6): the rows at steps 25, 50, 75 show
# 0.8, 1.6, 2.4 MPa and no damage. Loading past onset damages the band and dissipates (rows 4-10,
# damage and dissipation growing); unloading (rows 11-12) is elastic with the band's damage
# frozen: no damage growth, no dissipation (Eq. (13)'s loading condition), the stress falling.
set -euo pipefail
build=$1 src=$2 work=$3 cxx=$4
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
# Only the package's own headers and Eigen: the consumer must not see the source tree.
cmake -S "$src/examples/point_path" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/point_path" | tee "$work/out.txt"
awk 'NR == 1 { next }
     { row++; eps[row] = $1; sig[row] = $2; dmg[row] = $3; w[row] = $4 }
     END {
       if (row != 12) { print "expected 12 rows, got " row; exit 1 }
       for (r = 1; r <= 3; r++)
         if (sig[r] - 32000 * eps[r] > 1e-9 || 32000 * eps[r] - sig[r] > 1e-9 || dmg[r] != 0) { print "row " r ": not elastic"; bad = 1 }
       for (r = 4; r <= 10; r++)
         if (!(dmg[r] > dmg[r - 1] && w[r] > w[r - 1])) { print "row " r ": loading past onset must damage and dissipate"; bad = 1 }
       for (r = 11; r <= 12; r++)
         if (!(dmg[r] == dmg[10] && w[r] == w[10] && sig[r] < sig[r - 1])) { print "row " r ": unloading must be elastic"; bad = 1 }
       exit bad
     }' "$work/out.txt"
config_version=$(find "$work/prefix" -name ecmConfigVersion.cmake)
test -n "$config_version"
# ecm/version.hpp says the package's version, and the program built against it prints it.
version=$(sed -n 's/^set(PACKAGE_VERSION "\(.*\)")$/\1/p' "$config_version")
grep -q "#define ECM_VERSION_STRING \"$version\"" "$work/prefix/include/ecm/ecm/version.hpp"
test "$("$work/build/point_path" 2>&1 >/dev/null)" = "ecm $version"
# Every document an installed header cites is installed (share/doc/ecm/), and the consumer's page.
for doc in $(grep -rhoE "docs/[a-z_-]+\.md" "$work/prefix/include/ecm" | sort -u) docs/cpp.md; do
  test -f "$work/prefix/share/doc/ecm/$(basename "$doc")" || { echo "not installed: $doc"; exit 1; }
done
! grep -rqE "yaml-cpp|nlohmann" "$work/prefix/include/ecm/material" "$work/prefix/include/ecm/calibration"
echo "consumer: built against $work/prefix and ran"
