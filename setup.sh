#!/usr/bin/env bash
# setup.sh — install what atmo needs (Debian 12 packages), build it, then render or test.
#
#   ./setup.sh render   install, build, render the default scene to atmo.png (here)
#   ./setup.sh test     install, build with warnings as errors, run the whole test suite (CI)
#   ./setup.sh build    install and build only
#   ./setup.sh install  install, build, then put the atmo command in $PREFIX/bin
#                       (PREFIX=/usr/local by default: /usr/local/bin/atmo)
#
# Needs root for apt-get and for installing under /usr/local (runs them through sudo when not
# root). Installs only missing packages.
set -euo pipefail
cd "$(dirname "$0")"
mode=${1:-render}
case "$mode" in render|test|build|install) ;; *)
    echo "usage: ./setup.sh render|test|build|install  (install: PREFIX=/usr/local by default)" >&2
    exit 2 ;;
esac
as_root=()
[ "$(id -u)" -ne 0 ] && as_root=(sudo)

packages=(cmake make gcc pkg-config
          pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers
          libstb-dev libcjson-dev libopenexr-dev openexr libglfw3-dev libgdal-dev gnuplot-nox)
# the viewer's tests (tests/test_view_*.sh): an X server and Mesa's software OpenGL
[ "$mode" = test ] && packages+=(xvfb xauth libgl1-mesa-dri)
# the tests also start a one-node Slurm cluster (tests/test_slurm.sh)
[ "$mode" = test ] && packages+=(slurm-wlm munge)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${missing[*]}"
    "${as_root[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc 2>/dev/null || echo 2)
werror=OFF
[ "$mode" = test ] && werror=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DATMO_WERROR=$werror
cmake --build build -j"$jobs"

case "$mode" in
render)
    build/atmo render --force --output atmo.png --report atmo-run.json
    echo "setup: wrote atmo.png (and the run report atmo-run.json)" ;;
test)
    ctest --test-dir build --output-on-failure -j"$jobs" ;;
install)
    prefix=${PREFIX:-/usr/local}
    sudo_install=()
    [ -w "$prefix" ] || [ ! -e "$prefix" -a -w "$(dirname "$prefix")" ] || sudo_install=("${as_root[@]}")
    "${sudo_install[@]}" cmake --install build --prefix "$prefix"
    echo "setup: installed $prefix/bin/atmo; try: atmo presets" ;;
esac
