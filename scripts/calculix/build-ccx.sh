#!/usr/bin/env bash
# Builds CalculiX's solver `ccx` from Debian's source package, linked with ecm's UMAT
# (libecm_umat.so) in place of CalculiX's example umat.o. Debian's binary `ccx` carries that
# example and cannot load a UMAT at run time (docs/fe-codes.md), hence the relink.
#
# Usage: scripts/calculix/build-ccx.sh OUT_DIR UMAT_LIB_DIR
#   OUT_DIR       where the source, the objects and the executable OUT_DIR/ccx go
#   UMAT_LIB_DIR  the folder holding libecm_umat.so (the build tree's umat/ folder)
# The source comes from Debian's archive as configured on this machine (`apt-get source` with a
# private list of deb-src entries made from the system's own: nothing in /etc/apt is changed).
# The packages it needs are installed by scripts/setup.sh. A second run reuses what is built.
set -euo pipefail
out=$(mkdir -p "$1" && cd "$1" && pwd)
umat_dir=$(cd "$2" && pwd)
[[ -f "$umat_dir/libecm_umat.so" ]] || { echo "build-ccx: no libecm_umat.so in $umat_dir" >&2; exit 2; }
jobs=${ECM_JOBS:-2}

# 1. The source, once: deb-src entries mirroring the system's deb entries, in a private apt state.
src=$(ls -d "$out"/src/ccx_*/src 2>/dev/null | head -n1 || true)
if [[ -z "$src" ]]; then
  apt_dir="$out/apt"
  mkdir -p "$apt_dir/sources.list.d" "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial"
  # Debian's own entries only (a third-party repository may have no source indices).
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f "$f" ]] || continue
    awk 'BEGIN { RS = ""; ORS = "\n\n" } /URIs:[^\n]*debian/ { sub(/Types:[^\n]*/, "Types: deb-src"); print }' "$f" \
      > "$apt_dir/sources.list.d/$(basename "$f")"
  done
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [[ -f "$f" ]] && sed -n 's/^deb \(.*debian.*\)/deb-src \1/p' "$f" > "$apt_dir/sources.list.d/$(basename "$f").list"
  done
  apt_opts=(-o "Dir::Etc::SourceList=/dev/null" -o "Dir::Etc::SourceParts=$apt_dir/sources.list.d"
            -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache" -o "APT::Sandbox::User=root")
  echo "build-ccx: fetching Debian's source of calculix-ccx" >&2
  apt-get "${apt_opts[@]}" update -qq
  mkdir -p "$out/download"
  (cd "$out/download" && apt-get "${apt_opts[@]}" source --download-only -qq calculix-ccx >/dev/null)
  rm -rf "$out/src"
  dpkg-source --no-check -x "$(ls "$out"/download/calculix-ccx_*.dsc | head -n1)" "$out/src" >/dev/null
  src=$(ls -d "$out"/src/ccx_*/src | head -n1)
fi
version=$(basename "$(dirname "$src")")   # ccx_2.20

# 2. CalculiX's objects, as Debian builds them (debian/rules), less the example UMAT.
cflags="-O2 -w -I/usr/include/spooles -DARCH=\"Linux\" -DSPOOLES -DARPACK -DMATRIXSTORAGE -DUSE_MT=1"
fflags="-O2 -w -fallow-argument-mismatch"
echo "build-ccx: compiling $version ($(ls "$src"/*.f "$src"/*.c | wc -l) files, $jobs jobs)" >&2
make -C "$src" -s -j"$jobs" CFLAGS="$cflags" FFLAGS="$fflags" "$version.a" >/dev/null
ar d "$src/$version.a" umat.o 2>/dev/null || true
make -C "$src" -s CFLAGS="$cflags" "$version.o" >/dev/null

# 3. The executable: CalculiX's link line with libecm_umat.so where umat.o was.
gfortran -O2 -o "$out/ccx" "$src/$version.o" "$src/$version.a" -L"$umat_dir" -lecm_umat -Wl,-rpath,"$umat_dir" \
  -lspooles -lpthread -larpack -llapack -lblas -lm -lc -fopenmp
nm -D "$out/ccx" | grep -q " U umat_" || { echo "build-ccx: ccx does not take umat_ from libecm_umat.so" >&2; exit 1; }
echo "build-ccx: $out/ccx ($version, UMAT from $umat_dir/libecm_umat.so)" >&2
