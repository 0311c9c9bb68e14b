#!/usr/bin/env bash
# test_view_denoise — the viewer's denoised display (key N, host/view/view.c).
# labels: render
#
# Scene: thesis-7 path traced (an open box: Monte Carlo noise on every surface), 48x32, 4
# samples per pixel, under Xvfb with Mesa's software OpenGL. Oracles:
#  1. The accumulation is not disturbed (exact): with N pressed, the viewer's --output PFM (a
#     save of the rendered image; PFM is not denoised under output.denoise=off) is bitwise
#     `atmo render --samples 4 --denoise off`'s.
#  2. The display is the denoised frame: the window as drawn with N pressed matches the PNG the
#     viewer saves with output.denoise=fast (the same filter on the same frame: Open Image
#     Denoise at quality fast on the colour alone, atmo_outputs_denoise_rgb, then the same
#     display pipeline) within one 8-bit step in at most 2 % of the values, the shader's bound
#     of test_view_screenshot; and it differs from the window drawn without N in more than a
#     third of the values (the filter changes most pixels of a 4-spp path-traced frame).
# Without the library the test is skipped (setup.sh installs it, so CI runs it).
set -u
atmo=$1
work=$(mktemp -d)
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_view.sh"
trap 'view_stop_x; rm -rf "$work"' EXIT
cd "$work"
scene=(--preset thesis-7 --set image.width=48 --set image.height=32)
if ! "$atmo" render "${scene[@]}" --samples 4 --denoise fast --output probe.pfm --quiet 2>probe.txt; then
    if grep -q "not installed" probe.txt; then
        echo "SKIP: $(cat probe.txt)" >&2
        exit 77
    fi
fi
view_start_x "$atmo"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
printf 'press N\n' >n.txt
view=(view "${scene[@]}" --screenshot-after 4 --window 48x32 --quiet)
if "$atmo" render "${scene[@]}" --samples 4 --denoise off --output r.pfm --quiet &&
    "$atmo" "${view[@]}" --denoise off --script n.txt --output n.pfm --window-capture wn.png &&
    "$atmo" "${view[@]}" --denoise off --output raw.pfm --window-capture wraw.png &&
    "$atmo" "${view[@]}" --denoise fast --output dn.png; then
    if cmp -s r.pfm n.pfm; then ok; else bad "with N the viewer's saved image differs from atmo render's"; fi
    read -r w h worst differing <<<"$(png_compare dn.png wn.png)"
    echo "N on: window vs the denoised PNG ${w}x${h}, max difference $worst/255, $differing of $((3 * w * h)) values differ"
    if [ "$w" = 48 ] && [ "$worst" -le 1 ] && [ "$differing" -le $((3 * 48 * 32 / 50)) ]; then
        ok
    else
        bad "the denoised display is not the denoised frame"
    fi
    read -r w h worst differing <<<"$(png_compare wraw.png wn.png)"
    echo "N on vs off: windows differ in $differing of $((3 * w * h)) values (max $worst/255)"
    if [ "$differing" -gt $((48 * 32)) ]; then ok; else bad "N did not change the display"; fi
else
    bad "render or view failed"
fi
echo "test_view_denoise: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
