#!/usr/bin/env bash
# test_frames — animations: `atmo render --frames A..B` with --animate KEY=V0..V1 or
# --scene-end FILE writes NAME.NNNN.EXT per frame, each frame the render of the scene with the
# key at its interpolated value; with --part I/N, part I renders frames A+I-1, A+I-1+N, ...;
# bad animations are refused before any work.
# labels: cli render
#
# Oracle: the closed form of linear interpolation, v(f) = (1 - t) v0 + t v1 with
# t = (f - A) / (B - A), whose values here are exact in binary (zenith 30, 55, 80 deg; altitude
# 0, 500, 1000 m), so each frame must equal byte for byte a render of the same scene with
# --set KEY=v(f) (cmp, no tolerance); the file names are the ones the CLI documents.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin

small=(--width 24 --height 16 --samples 2 --quiet)
"$atmo" render --preset sky-sunset "${small[@]}" --frames 1..3 --animate sun.zenith_deg=30..80 --output sky.pfm ||
    bad "--frames 1..3 failed"
for f in 1 2 3; do
    z=$((30 + 25 * (f - 1)))
    "$atmo" render --preset sky-sunset "${small[@]}" --set sun.zenith_deg=$z --output ref$f.pfm
    cmp -s ref$f.pfm sky.000$f.pfm && ok || bad "frame $f differs from zenith $z"
done
[ ! -e sky.pfm ] && [ ! -e sky.0004.pfm ] && ok || bad "files beyond the frames: $(ls sky*)"

# two scene files: the camera's altitude moves, the sun's zenith stays
cat >start.json <<'EOF'
{"sun": {"zenith_deg": 70}, "camera": {"position_m": [0, 0, 0]}}
EOF
cat >end.json <<'EOF'
{"sun": {"zenith_deg": 70}, "camera": {"position_m": [0, 1000, 0]}}
EOF
"$atmo" render --scene start.json --scene-end end.json --frames 4..6 "${small[@]}" \
    --output alt.pfm || bad "--scene-end failed"
"$atmo" render --scene start.json --set camera.position_m=0,500,0 "${small[@]}" --output mid.pfm
cmp -s mid.pfm alt.0005.pfm && ok || bad "frame 5 differs from the altitude 500 m"
"$atmo" render --scene end.json "${small[@]}" --output last.pfm
cmp -s last.pfm alt.0006.pfm && ok || bad "frame 6 differs from the end scene"

# --part 2/2 of frames 1..3: frame 2 only
rm -f sky.*.pfm
"$atmo" render --preset sky-sunset "${small[@]}" --frames 1..3 --animate sun.zenith_deg=30..80 --part 2/2 \
    --output sky.pfm || bad "--frames with --part failed"
[ "$(ls sky.*.pfm)" = "sky.0002.pfm" ] && ok || bad "part 2/2 wrote $(ls sky.*.pfm)"
cmp -s ref2.pfm sky.0002.pfm && ok || bad "part 2/2's frame 2 differs"

refused "reversed range" "--frames needs A..B" render --preset sky-sunset "${small[@]}" --frames 3..1 --output out/a.pfm
refused "animate a count" "only float keys" render --preset sky-sunset "${small[@]}" --frames 1..2 --animate image.samples=1..4 --output out/a.pfm
refused "animate unknown key" "did you mean 'sun.zenith_deg'" render --preset sky-sunset "${small[@]}" --frames 1..2 --animate sun.zenit=1..4 --output out/a.pfm
refused "animate out of range" "frame 2" render --preset sky-sunset "${small[@]}" --frames 1..2 --animate sun.zenith_deg=30..200 --output out/a.pfm
refused "animate without frames" "need --frames" render --preset sky-sunset "${small[@]}" --animate sun.zenith_deg=30..80 --output out/a.pfm
echo '{"camera": {"kind": "panorama"}}' >kind.json
refused "scene-end changes a choice" "camera.kind differs" render "${small[@]}" --frames 1..2 --scene-end kind.json --output out/a.pfm

cli_end test_frames
