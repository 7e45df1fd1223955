#!/usr/bin/env bash
# Installs every Debian package ffr needs, then configures and builds Release in build/.
# Idempotent: packages already present are skipped by apt; an existing build/ is reused.
#   scripts/setup.sh            install + build
#   scripts/setup.sh --deps     install only
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# build-essential's GCC brings the sanitizer runtimes (libasan, libubsan) of scripts/test.sh's
# second pass; nothing else is needed for it.
packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libspectra-dev libarpack2-dev
  libopenblas-dev libopenblas0-pthread liblapack-dev
  libsuitesparse-dev libmetis-dev
  libgmsh-dev gmsh
  libhdf5-dev hdf5-tools
  nlohmann-json3-dev
  googletest libgtest-dev libgmock-dev
  calculix-ccx
  zlib1g-dev
  python3-dev python3-numpy pybind11-dev   # the Python package (python/), for /usr/bin/python3
  unzip                                    # tests/fmu unpacks the FMUs as an importer does
  python3-matplotlib                       # tools/bench/formulations/plot.py (the study's PNG)
  clang libclang-rt-14-dev   # libFuzzer and the sanitizers of tools/fuzz
  slepc-dev petsc-dev libopenmpi-dev openmpi-bin   # ffr-reduce's slepc backend (docs/cluster.md)
)

sudo_=""
[ "$(id -u)" -ne 0 ] && sudo_="sudo"

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_ apt-get update -qq
  $sudo_ apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# OpenBLAS as the system BLAS/LAPACK (the reference BLAS is ~20x slower for CHOLMOD).
arch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)
for lib in libblas.so.3 liblapack.so.3; do
  alt="$lib-$arch"
  cand=$(update-alternatives --list "$alt" 2>/dev/null | grep openblas-pthread | head -n1 || true)
  if [ -n "$cand" ]; then
    cur=$(readlink -f "/etc/alternatives/$alt" 2>/dev/null || true)
    [ "$cur" = "$(readlink -f "$cand")" ] || $sudo_ update-alternatives --set "$alt" "$cand" >/dev/null
  fi
done

[ "${1:-}" = "--deps" ] && exit 0

cmake -S "$here" -B "$here/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$here/build" -j "$(nproc)"
