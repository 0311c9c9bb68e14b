#!/usr/bin/env bash
# test_view_objects — moving the camera in a scene with objects: the viewer's image is the
# image of the scene it saves.
# labels: render
#
# Objects reach the kernels as camera-relative rows, a host table uploaded once before the
# precompute (plan_objects.c), so a camera move changes the table: the session must not
# take such a move as a view update (which only rewrites the scene struct) but as a scene
# update (atmo_session_set_scene, which uploads the new table). A sphere of radius 3 m stands
# 20 m ahead of the sky-sunset camera (16x8 pixels, 2 samples per pixel, method single); a
# --script holds W for 1 s (5 m along the camera's forward, pitched up 10 degrees: z moves by
# 5 cos 10 deg, test_view_keys' closed form), turns the sun 1 degree up, waits for 2 samples
# per pixel and saves with P. Done for the preview renderer (render.mode=preview, objects lit
# by the sun) and the path tracer (render.mode=path).
# Oracle: the determinism contract (same seed, device and samples give the same bits): P's PFM
# is bitwise `atmo render --scene` of P's scene file. The check can fail: the saved camera must
# have moved, and the render of the start scene must differ from the moved one (so a sphere
# left at its old place shows).
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

printf 'wait-samples 2\nhold W 1\npress Up\nwait-samples 2\npress P\nquit\n' >keys.txt
for mode in preview path; do
    scene=(--preset sky-sunset --set image.width=16 --set image.height=8 --set image.samples=2
           --set atmosphere.method=single --set render.mode=$mode
           --set 'objects=[{"type": "sphere", "center_m": [0, 3, 20], "radius_m": 3, "albedo": [0.8, 0.8, 0.8]}]')
    if ! "$atmo" render "${scene[@]}" --output start-$mode.pfm --quiet; then
        bad "$mode: atmo render of the start scene failed"
        continue
    fi
    if ! "$atmo" view "${scene[@]}" --script keys.txt --save $mode.pfm --quiet ||
        [ ! -f $mode-001.pfm ] || [ ! -f $mode-001.json ]; then
        bad "$mode: the viewer did not save $mode-001.pfm and $mode-001.json"
        continue
    fi
    z=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['camera']['position_m'][2])" $mode-001.json)
    if python3 -c "import math, sys; sys.exit(abs(float(sys.argv[1]) - 5 * math.cos(math.radians(10))) > 1e-6)" "$z"; then
        ok
    else
        bad "$mode: the camera is at z = $z m after W for 1 s, not 5 cos 10 deg m"
    fi
    if "$atmo" render --scene $mode-001.json --output again-$mode.pfm --quiet &&
        cmp -s $mode-001.pfm again-$mode.pfm; then
        ok
    else
        bad "$mode: the viewer's image after the move is not atmo render --scene of its saved scene"
    fi
    if cmp -s start-$mode.pfm again-$mode.pfm; then
        bad "$mode: the move changes nothing in the image (the test would not see a stale sphere)"
    else
        ok
    fi
done
echo "test_view_objects: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
