#!/usr/bin/env bash
# test_view_denoise — the viewer's denoised display (key N, host/view/view_denoise.c) and its
# denoised saves, both with the view's albedo and normal guides, as `atmo render --denoise` does.
# labels: render
#
# Scene: thesis-7 path traced (an open box: Monte Carlo noise on every surface), 48x32, 4
# samples per pixel, under Xvfb with Mesa's software OpenGL. Oracles:
#  1. The accumulation is not disturbed (exact): with N pressed (the render thread then renders
#     the guides between its steps), the viewer's --output PFM (a save of the rendered image;
#     not denoised under output.denoise=off) is bitwise `atmo render --samples 4 --denoise
#     off`'s.
#  2. The saves are render's files (exact): the PNG the viewer saves with output.denoise=fast
#     is byte for byte `atmo render --samples 4 --denoise fast`'s, which denoises with the guide
#     pass (the same frame, the same guides, the same filter and display pipeline).
#  3. The display is the denoised frame with the guides: the window as drawn with N pressed
#     matches that PNG within one 8-bit step in at most 2 % of the values, the shader's bound of
#     test_view_screenshot (the display denoised on the colour alone differs from it in about
#     five sixths of the values, by up to 43 steps: measured); and it differs from the window
#     drawn without N in more than a third of the values (the filter changes most pixels of a
#     4-spp path-traced frame).
#  4. The guides follow the view: with N on, the camera turned (a mouse drag in the script),
#     then P: the saved PNG is byte for byte `atmo render --scene` of the saved scene's at 4
#     samples with --denoise fast (the guides of the turned view, not the first view's), the
#     window matches it as in 3, and it differs from the unturned view's PNG.
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
    "$atmo" "${view[@]}" --denoise fast --output dn.png &&
    "$atmo" render "${scene[@]}" --samples 4 --denoise fast --output r.png --quiet; then
    if cmp -s r.pfm n.pfm; then ok; else bad "with N the viewer's saved image differs from atmo render's"; fi
    if cmp -s r.png dn.png; then ok; else bad "the viewer's denoised PNG differs from atmo render --denoise fast's"; fi
    read -r w h worst differing <<<"$(png_compare dn.png wn.png)"
    echo "N on: window vs the denoised PNG ${w}x${h}, max difference $worst/255, $differing of $((3 * w * h)) values differ"
    if [ "$w" = 48 ] && [ "$worst" -le 1 ] && [ "$differing" -le $((3 * 48 * 32 / 50)) ]; then
        ok
    else
        bad "the denoised display is not the frame denoised with its guides"
    fi
    read -r w h worst differing <<<"$(png_compare wraw.png wn.png)"
    echo "N on vs off: windows differ in $differing of $((3 * w * h)) values (max $worst/255)"
    if [ "$differing" -gt $((48 * 32)) ]; then ok; else bad "N did not change the display"; fi
else
    bad "render or view failed"
fi
printf 'press N\nlook 6 3\nwait-samples 4\npress P\n' >turn.txt
if "$atmo" "${view[@]}" --denoise fast --script turn.txt --save turned.png --output t.png \
    --window-capture wt.png &&
    "$atmo" render --scene turned-001.json --samples 4 --denoise fast --output rt.png --quiet; then
    if cmp -s rt.png turned-001.png; then ok; else bad "the turned view's saved PNG differs from atmo render --scene's"; fi
    if cmp -s rt.png r.png; then bad "the drag did not turn the view"; else ok; fi
    read -r w h worst differing <<<"$(png_compare rt.png wt.png)"
    echo "turned view, N on: window vs the denoised PNG ${w}x${h}, max difference $worst/255, $differing of $((3 * w * h)) values differ"
    if [ "$w" = 48 ] && [ "$worst" -le 1 ] && [ "$differing" -le $((3 * 48 * 32 / 50)) ]; then
        ok
    else
        bad "the turned view's denoised display is not its frame denoised with its guides"
    fi
else
    bad "the turned view's render or view failed"
fi
echo "test_view_denoise: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
