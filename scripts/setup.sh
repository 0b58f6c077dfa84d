#!/usr/bin/env bash
# Installs the Debian 12 packages ecm needs, only those that are missing (idempotent, quiet).
# The last line is for CalculiX rebuilt with ecm's UMAT (scripts/calculix/build-ccx.sh).
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libgsl-dev libyaml-cpp-dev
          libgtest-dev googletest libbenchmark-dev gnuplot-nox libcli11-dev nlohmann-json3-dev libsuitesparse-dev libopenblas0-serial
          python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib time
          python3-dask python3-distributed libhypre-dev
          gfortran libspooles-dev libarpack2-dev liblapack-dev libblas-dev dpkg-dev xz-utils bzip2)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
