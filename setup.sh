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
          libstb-dev libcjson-dev libopenexr-dev openexr libglfw3-dev libgdal-dev gnuplot-nox
          python3-pip)
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

# Intel Open Image Denoise 2.x (denoising; Debian has no package): the PyPI wheel pyoidn ships
# the library with its TBB. It goes under build/oidn (no system Python change), and its path into
# build/oidn-path, which CMake compiles in. The build works without it; in test mode it is
# required, so the denoiser's tests run.
oidn_dir=$PWD/build/oidn
oidn_lib=$oidn_dir/pyoidn/oidn/lib/libOpenImageDenoise.so.2
if [ ! -f "$oidn_lib" ]; then
    echo "setup: installing Open Image Denoise (PyPI wheel pyoidn) into $oidn_dir"
    mkdir -p build
    python3 -m pip install --quiet --disable-pip-version-check --no-deps --target "$oidn_dir" \
        pyoidn || [ "$mode" != test ] || { echo "setup: pip install pyoidn failed" >&2; exit 1; }
fi
if [ -f "$oidn_lib" ]; then
    echo "$oidn_lib" > build/oidn-path
else
    rm -f build/oidn-path
    echo "setup: Open Image Denoise not installed; atmo builds and renders without denoising" >&2
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
    echo "setup: installed $prefix/bin/atmo; try: atmo presets"
    case ":$PATH:" in
    *":$prefix/bin:"*) ;;
    *) echo "setup: $prefix/bin is not on your PATH; add it (e.g. to ~/.profile):"
       echo "    export PATH=\"$prefix/bin:\$PATH\"" ;;
    esac ;;
esac
