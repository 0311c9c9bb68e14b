#!/usr/bin/env bash
# viewer_screenshot.sh — the README's picture of `atmo view` (docs/gallery/viewer.png): the
# viewer on sky-sunset with its help and status overlay, as its window draws it, under Xvfb
# with Mesa's software OpenGL (where no DISPLAY is set).
#
#   tools/viewer_screenshot.sh [ATMO [OUTPUT]]   (default build/atmo, docs/gallery/viewer.png)
#
# A script presses H (the overlay), the viewer renders 8 samples per pixel of a 960x540 image,
# writes the image (OUTPUT's .exr beside nothing: a temporary file) and the window capture.
set -euo pipefail
cd "$(dirname "$0")/.."
atmo=${1:-build/atmo}
out=${2:-docs/gallery/viewer.png}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'press H\n' >"$tmp/keys.txt"
run=("$atmo" view --preset sky-sunset --set image.width=960 --set image.height=540
     --script "$tmp/keys.txt" --screenshot-after 8 --output "$tmp/image.exr"
     --window-capture "$out" --window 960x540 --force --quiet)
if [ -n "${DISPLAY:-}" ]; then
    "${run[@]}"
else
    xvfb-run -a -s "-screen 0 1280x800x24" "${run[@]}"
fi
echo "wrote $out"
