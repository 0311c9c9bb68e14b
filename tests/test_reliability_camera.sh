#!/usr/bin/env bash
# test_reliability_camera — a camera under the terrain is warned about: one stderr line, before
# the render's work, with the camera's height, the terrain's surface height there and the fix;
# the render still runs (exit 0, the image written). A camera above the surface, or placed on
# it with camera.on_terrain, gets no warning.
# labels: reliability cli
#
# Oracle: the terrain's surface height from `atmo terrain --at X,Z --json` (position_m's y: the
# kernels' own float height functions compiled on the host, what a render sees), which the
# warning must state to its printed 0.1 m (the two differ by the float and double evaluations
# of the field, under 1 mm: test_terrain_noise). thesis-1's terrain at (0, 0) is land.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
export ATMO_CACHE_DIR=$work/cache TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
r=(render --preset thesis-1 --width 8 --height 8 --samples 1)

surface=$("$atmo" terrain --preset thesis-1 --at 0,0 --json |
    python3 -c "import json, sys; print('%.1f' % json.load(sys.stdin)['position_m'][1])")
below=$(python3 -c "print('%.1f' % ($surface - 500.0))")
above=$(python3 -c "print('%.1f' % ($surface + 50.0))")

# under: one warning line with both heights and the fix, before the first progress line
"$atmo" "${r[@]}" --set camera.position_m=0,$below,0 --output under.png >out.txt 2>err.txt
rc=$?
[ $rc -eq 0 ] && [ -s under.png ] && ok || bad "camera under the terrain: exit $rc, image missing"
warn=$(grep -c 'warning: the camera is under the terrain' err.txt)
[ "$warn" -eq 1 ] && ok || bad "camera under the terrain: $warn warning lines, want 1: $(cat err.txt)"
grep -q "its height is $below m and the terrain's surface is at $surface m; raise camera.position_m's y above it, or set camera.on_terrain=below" err.txt &&
    ok || bad "the warning does not state height $below m, surface $surface m and the fix: $(cat err.txt)"
first_progress=$(grep -n '^render:' err.txt | head -1 | cut -d: -f1)
warn_line=$(grep -n 'warning: the camera' err.txt | head -1 | cut -d: -f1)
[ -n "$warn_line" ] && [ -n "$first_progress" ] && [ "$warn_line" -lt "$first_progress" ] &&
    ok || bad "the warning comes after the render's progress: $(cat err.txt)"

# above, and on the terrain by camera.on_terrain: no warning
"$atmo" "${r[@]}" --set camera.position_m=0,$above,0 --output above.png --quiet 2>err.txt
rc=$?
[ $rc -eq 0 ] && [ ! -s err.txt ] && ok || bad "camera 50 m above the surface: exit $rc, stderr: $(cat err.txt)"
"$atmo" "${r[@]}" --set camera.on_terrain=below --set camera.position_m=0,2,0 \
    --output on.png --quiet 2>err.txt
rc=$?
[ $rc -eq 0 ] && [ ! -s err.txt ] && ok || bad "camera on_terrain=below 2 m: exit $rc, stderr: $(cat err.txt)"

cli_end test_reliability_camera
