#!/usr/bin/env bash
# test_view_keys — keys move the camera and turn the sun, and P saves a shot that
# `atmo render --scene` reproduces.
# labels: render
#
# A --script (host/view/view_script.c) drives the viewer with synthetic key events instead of
# an X event injector: movement then depends on the script's simulated hold time, not on the
# frame rate, so the expected scene is exact. From the camera at (0, 1.7, 0) with pitch 0 and
# yaw 30 degrees, the sun at zenith 60 and azimuth 45, method fast (whose sky-view LUT follows
# the view: every change reruns that pass), 16x8 pixels, 2 samples per pixel:
#     hold W 1        W for one second
#     press Up        twice: the sun 1 degree higher each
#     press Right shift   the sun 10 degrees to the right
#     wait-samples 2, press P
# Oracles (closed forms of host/view/view_controls.c's documented rules):
#  - position: forward = (-cos p sin y, sin p, cos p cos y) = (-1/2, 0, sqrt(3)/2), speed
#    0.5/s * max(h, 10 m) = 5 m/s (h stays 1.7 m to within 2e-6 m over 5 m: the ground's
#    curvature, 5^2 / (2 * 6360 km)), 60 ticks of 1/60 s: (0, 1.7, 0) + 5 m * forward =
#    (-2.5, 1.7, 4.330127...), to 1e-6 m (the curvature term and summation rounding ~1e-14);
#  - the sun: zenith 60 - 2 = 58, azimuth 45 + 10 = 55 degrees, exactly;
#  - nothing else in the scene file changed (every other key as in the start scene);
#  - the saved PFM is bitwise `atmo render --scene` of the saved scene (same session, seed and
#    samples: the draft and the refinement after each change leave no trace).
# Also: a hold of Q for 10 s from 1.7 m stops at the ground clearance of 0.5 m (altitude
# 0.5 m to 1e-6 m); Tab (preview: method fast at half size) saves an 8x4 image with the
# quality scene beside it; key 3 loads thesis-3 with the --set options but camera.* and sun.*
# (the scene file equals `atmo render --preset thesis-3 --set ... --save-scene`'s), = raises
# the exposure by 2^(1/3) and T moves to the next tone mapper (exposure -> reinhard), and the
# saved PNG is byte for byte `atmo render --scene` of the saved scene's. thesis-3 stands its
# camera on the terrain (camera.on_terrain); the viewer moves cameras in world metres, so its
# scene has the camera placed (on_terrain off, y absolute: above the preset's relative y), and
# that scene renders bitwise the preset's image.
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

scene=(--preset sky-afternoon --set image.width=16 --set image.height=8 --set image.samples=2
       --set atmosphere.method=fast --set camera.pitch_deg=0 --set camera.yaw_deg=30
       --set sun.zenith_deg=60 --set sun.azimuth_deg=45)
"$atmo" render "${scene[@]}" --save-scene start.json
cat >keys.txt <<'KEYS'
# move, turn the sun, save
wait-samples 2
hold W 1
press Up
press Up
press Right shift
wait-samples 2
press P
quit
KEYS
if "$atmo" view "${scene[@]}" --script keys.txt --save shot.pfm --quiet && [ -f shot-001.pfm ] &&
    [ -f shot-001.json ]; then
    ok
else
    bad "the viewer did not save shot-001.pfm and shot-001.json"
fi
python3 - start.json shot-001.json <<'PY' && ok || bad "the saved scene is not the expected one"
import json, math, sys
start, shot = (json.load(open(p)) for p in sys.argv[1:3])
p, y = 0.0, math.radians(30.0)
forward = (-math.cos(p) * math.sin(y), math.sin(p), math.cos(p) * math.cos(y))
want = [s + 5.0 * f for s, f in zip(start['camera']['position_m'], forward)]
got = shot['camera']['position_m']
err = max(abs(a - b) for a, b in zip(got, want))
print('position', got, 'expected', want, 'error %.3g m' % err)
assert err < 1e-6
assert shot['sun']['zenith_deg'] == 58.0 and shot['sun']['azimuth_deg'] == 55.0, shot['sun']
start['camera']['position_m'] = got
start['sun']['zenith_deg'], start['sun']['azimuth_deg'] = 58.0, 55.0
assert start == shot, 'other keys changed'
PY
if "$atmo" render --scene shot-001.json --output again.pfm --quiet && cmp -s shot-001.pfm again.pfm; then
    ok
else
    bad "atmo render --scene shot-001.json does not reproduce the saved image"
fi

# the ground clearance, and preview mode's save
printf 'hold Q 10\npress Tab\nwait-samples 2\npress P\nquit\n' >down.txt
if "$atmo" view "${scene[@]}" --script down.txt --save low.pfm --quiet; then
    python3 - low-001.json low-001.pfm <<'PY' && ok || bad "the clearance or the preview save is wrong"
import json, math, sys
s = json.load(open(sys.argv[1]))
x, y, z = s['camera']['position_m']
R = s['atmosphere']['bottom_radius_m']
h = math.sqrt(x * x + (y + R) ** 2 + z * z) - R
print('altitude after hold Q 10: %.9f m' % h)
assert abs(h - 0.5) < 1e-6, h
assert s['image']['width'] == 16 and s['atmosphere']['method'] == 'fast'
header = open(sys.argv[2], 'rb').read(32).split(b'\n')
assert header[0] == b'PF' and header[1] == b'8 4', header[:2]
PY
else
    bad "the viewer failed on down.txt"
fi

# a thesis view, exposure and tone mapper keys, saved as a PNG
printf 'press 3\npress Equal\npress T\nwait-samples 2\npress P\nquit\n' >thesis.txt
"$atmo" render --preset thesis-3 --set image.width=16 --set image.height=8 --set image.samples=2 \
    --set atmosphere.method=fast --save-scene want3.json --output want3.png --quiet
if "$atmo" view "${scene[@]}" --script thesis.txt --save th.png --quiet; then
    python3 - want3.json th-001.json <<'PY' && ok || bad "the thesis view or the display keys are wrong"
import json, sys
want, got = (json.load(open(p)) for p in sys.argv[1:3])
e = got['post']['exposure']
print('exposure after =: %.17g (want 10 * 2^(1/3) = %.17g), tone mapper %s' % (e, 10 * 2 ** (1 / 3), got['post']['tonemap']))
assert abs(e - 10 * 2 ** (1 / 3)) < 1e-12 and got['post']['tonemap'] == 'reinhard'
want['post']['exposure'], want['post']['tonemap'] = e, 'reinhard'
wc, gc = want['camera'], got['camera']
print('camera placed: on_terrain %s -> %s, y %.6g m above the terrain -> %.9g m' % (wc['on_terrain'], gc['on_terrain'], wc['position_m'][1], gc['position_m'][1]))
assert wc['on_terrain'] == 'at' and gc['on_terrain'] == 'off' and gc['position_m'][1] > wc['position_m'][1]
for k in ('on_terrain', 'terrain_at_m'):
    wc.pop(k, None), gc.pop(k, None)
wc['position_m'][1] = gc['position_m'][1]
assert want == got, 'the scene is not thesis-3 with the --set options but camera.* and sun.*'
PY
    # the placed camera is where the preset's camera stands: the same image (display keys aside)
    python3 - th-001.json want3.json placed.json <<'PY'
import json, sys
got, want = (json.load(open(p)) for p in sys.argv[1:3])
got['post'] = want['post']
json.dump(got, open(sys.argv[3], 'w'))
PY
    if "$atmo" render --scene placed.json --output placed.png --quiet && cmp -s placed.png want3.png; then
        ok
    else
        bad "the viewer's placed thesis-3 camera does not render the preset's image"
    fi
    if "$atmo" render --scene th-001.json --output again.png --quiet && cmp -s th-001.png again.png; then
        ok
    else
        bad "atmo render --scene th-001.json does not reproduce the saved PNG"
    fi
else
    bad "the viewer failed on thesis.txt"
fi

echo "test_view_keys: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
