#!/usr/bin/env bash
# test_view_screenshot — what the viewer shows and writes is what `atmo render` writes.
# labels: render
#
# Oracles, for a 32x16 sky-sunset (the sun's disc in the frame, so values from the dark ground
# to far above white) at 4 samples per pixel with method single (the quickest to build; the
# display path does not depend on the method), under Xvfb with Mesa's software OpenGL:
#  1. The image: `atmo view --screenshot-after 4 --output F.pfm` is bitwise the PFM of
#     `atmo render --samples 4` of the same scene. Both are one render session's mean of the
#     same samples (same seed, device and sample order; sums built in sample order whatever the
#     tiles, launches and the viewer's draft), so no tolerance: any difference is a bug.
#  2. The writers: its --output PNG is byte for byte `atmo render`'s (the same atmo_image_write,
#     atmo_post and metadata), for every tone mapper and both transfer curves.
#  3. The shader: the window as drawn (--window-capture, glReadPixels of the 8-bit framebuffer)
#     matches that PNG within one 8-bit step per channel, for every tone mapper (none, exposure,
#     reinhard, reinhard-white, aces, unreal3, uchimura, lottes), both transfer curves, and
#     white balance off, at exposures 10 (the default) and 200 (aces). The shader evaluates the
#     formulas of kernels/post/tonemap.h in GLSL floats; exp, pow and division may differ from
#     the host's by a few ulps (~1e-6 relative), far below a step of 1/255, so the quantised
#     values can differ only where the exact value lies that close to a rounding boundary: by
#     one step, in a fraction of about 2 * 127 * (relative error) of the values (5e-4 here, 1.3%
#     for a driver whose pow is good to 1e-4). The test allows one step in at most 2% of the
#     values; a formula that differs moves most values, or by more than a step.
#  1b. The same with render's scene shorthands given to the viewer (--width, --height, --seed,
#     --camera): the image has the size asked for and is bitwise atmo render's.
#  4. The same for the OpenGL 2.1 / GLSL 1.20 path, forced by telling Mesa to offer no more
#     than OpenGL 2.1 (MESA_GL_VERSION_OVERRIDE), with the default post settings.
set -u
atmo=$1
work=$(mktemp -d)
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_view.sh"
trap 'view_stop_x; rm -rf "$work"' EXIT
view_start_x "$atmo"
cd "$work"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# output.denoise=off: the window shows the frame as rendered, and auto would denoise the PNGs
# (test_view_denoise compares the denoised saves)
scene=(--preset sky-sunset --set image.width=32 --set image.height=16 --set atmosphere.method=single
       --set output.denoise=off)
if "$atmo" render "${scene[@]}" --samples 4 --output r.pfm --quiet &&
    "$atmo" view "${scene[@]}" --screenshot-after 4 --output v.pfm --window 32x16 --quiet; then
    if cmp -s r.pfm v.pfm; then ok; else bad "the viewer's PFM differs from atmo render's"; fi
else
    bad "render or view of the base scene failed"
fi

# render's scene shorthands in the viewer: --width, --height, --seed and --camera are the keys
# they stand for, so the screenshot is again bitwise atmo render's with the same flags
short=(--preset sky-sunset --width 40 --height 20 --seed 3 --camera panorama --set atmosphere.method=single)
if "$atmo" render "${short[@]}" --samples 4 --output rs.pfm --quiet &&
    "$atmo" view "${short[@]}" --screenshot-after 4 --output vs.pfm --window 40x20 --quiet &&
    [ "$(head -c 12 vs.pfm | tr '\n' ' ')" = "PF 40 20 -1." ]; then
    if cmp -s rs.pfm vs.pfm; then ok; else bad "view with the shorthands differs from atmo render's"; fi
else
    bad "render or view with --width/--height/--seed/--camera failed, or the size is not 40x20"
fi

# tone mapper, transfer, white balance, exposure
cases="none,srgb,true,10 exposure,srgb,true,10 reinhard,srgb,true,10 reinhard-white,srgb,true,10
aces,srgb,true,10 unreal3,gamma22,true,10 uchimura,srgb,true,10 lottes,srgb,true,10
aces,gamma22,false,200"
for c in $cases; do
    IFS=, read -r tm tr wb ex <<<"$c"
    post=(--set post.tonemap="$tm" --set post.transfer="$tr" --set post.white_balance="$wb"
          --set post.exposure="$ex")
    if ! "$atmo" render "${scene[@]}" "${post[@]}" --samples 4 --output "r-$tm-$ex.png" --quiet ||
        ! "$atmo" view "${scene[@]}" "${post[@]}" --screenshot-after 4 --output "v-$tm-$ex.png" \
            --window-capture "w-$tm-$ex.png" --window 32x16 --quiet; then
        bad "$c: render or view failed"
        continue
    fi
    if cmp -s "r-$tm-$ex.png" "v-$tm-$ex.png"; then ok; else bad "$c: the viewer's PNG differs from atmo render's"; fi
    read -r w h worst differing <<<"$(png_compare "r-$tm-$ex.png" "w-$tm-$ex.png")"
    echo "$tm $tr white_balance=$wb exposure=$ex: window vs PNG ${w}x${h}, max difference $worst/255, $differing of $((3 * w * h)) values differ"
    if [ "$w" = 32 ] && [ "$h" = 16 ] && [ "$worst" -le 1 ] && [ "$differing" -le $((3 * w * h / 50)) ]; then
        ok
    else
        bad "$c: the shader's output is off by $worst/255 in $differing values"
    fi
done

# the OpenGL 2.1 path (GLSL 1.20): Mesa told to offer no more than 2.1, so no 3.3 core context
if MESA_GL_VERSION_OVERRIDE=2.1 MESA_GLSL_VERSION_OVERRIDE=120 "$atmo" view "${scene[@]}" \
    --screenshot-after 4 --output v-legacy.png --window-capture w-legacy.png --window 32x16 \
    2>legacy.txt && grep -q "2.1 context, GLSL 1.20" legacy.txt; then
    read -r w h worst differing <<<"$(png_compare "r-exposure-10.png" "w-legacy.png")"
else
    worst=x
fi
echo "OpenGL 2.1, the default post settings: window vs PNG max difference $worst/255, ${differing:-?} values differ"
if [ "$worst" != x ] && [ "$worst" -le 1 ] && [ "$differing" -le $((3 * 32 * 16 / 50)) ]; then
    ok
else
    bad "the OpenGL 2.1 path: $(cat legacy.txt)"
fi

echo "test_view_screenshot: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
