#!/usr/bin/env bash
# test_merge — a render split into parts (atmo render --part I/N) and joined (atmo merge) gives
# the single render's files byte for byte, whatever tile size and launch budget each part used;
# the merge refuses a missing, duplicated, foreign, interrupted or non-part file with one line naming it,
# exit 2 and no output; --part refuses bad use before any work.
# labels: cli render
#
# Oracle: the single-process render of the same scene and seed on the same device. Each pixel's
# sums are built in sample order whatever the tiles and batches (atmo/session.h), a part holds
# its pixels' sums exactly (lossless EXR float layers), and the merge copies them and divides
# as the session does, so the comparison is exact (cmp), with no tolerance. Parts of 3 and of
# 2 cover an image of 5 bands of 8 rows (40 rows), which neither divides evenly.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin

# same_files A B: byte for byte, for each of .exr .pfm .png
same_files() {
    local x
    for x in exr pfm png; do
        cmp -s "$1.$x" "$2.$x" && ok || bad "$2.$x differs from $1.$x"
    done
}

scene=(--preset sky-sunset --width 48 --height 40 --samples 5 --seed 7 --set sun.zenith_deg=84 --quiet)
"$atmo" render "${scene[@]}" --output single.exr --output single.pfm --output single.png ||
    { echo "single render failed"; exit 1; }

# 3 parts: tile sizes 8, 16 and 48 px, launch budgets 1, 20 and 1000 ms
tiles=(8 16 48)
budgets=(1 20 1000)
for i in 1 2 3; do
    "$atmo" render "${scene[@]}" --part $i/3 --tile-size ${tiles[i - 1]} \
        --launch-budget-ms ${budgets[i - 1]} --output p3_$i.exr || bad "part $i/3 failed"
done
"$atmo" merge --quiet p3_2.exr p3_3.exr p3_1.exr --output m3.exr --output m3.pfm --output m3.png ||
    bad "merge of 3 parts failed"
same_files single m3

# 2 parts with the default tiles, one with batches of a single sample (budget 1 ms)
"$atmo" render "${scene[@]}" --part 1/2 --output p2_1.exr || bad "part 1/2 failed"
"$atmo" render "${scene[@]}" --part 2/2 --tile-size 32 --launch-budget-ms 1 --output p2_2.exr ||
    bad "part 2/2 failed"
"$atmo" merge --quiet p2_1.exr p2_2.exr --output m2.exr --output m2.pfm --output m2.png ||
    bad "merge of 2 parts failed"
same_files single m2

# a part file is readable by other EXR tools and holds only its own rows: part 1/3 of 40 rows
# in bands of 8 has bands 0 and 3, 16 rows
if command -v exrheader >/dev/null; then
    exrheader p3_1.exr >hdr.txt
    grep -q 'atmoPart (type string): "1/3"' hdr.txt && ok || bad "exrheader: no atmoPart"
    grep -q 'dataWindow (type box2i): (0 0) - (47 15)' hdr.txt && ok || bad "part 1/3 is not 48x16"
fi

# refusals: no output is written
refused "missing part" "part 2/3 is missing" merge p3_1.exr p3_3.exr --output out/m.exr
refused "duplicated part" "'p3_1.exr' is part 1/3 again" merge p3_1.exr p3_2.exr p3_3.exr p3_1.exr --output out/m.pfm
"$atmo" render "${scene[@]}" --seed 8 --part 2/3 --output other_seed.exr || bad "foreign part failed"
refused "part of another scene" "'other_seed.exr' is a part of another scene" merge p3_1.exr other_seed.exr p3_3.exr --output out/m.pfm
refused "parts of another split" "'p2_2.exr' is part 2/2" merge p3_1.exr p2_2.exr p3_3.exr --output out/m.pfm
refused "not a part" "'single.exr' is not a part" merge single.exr --output out/m.pfm
refused "not an EXR" "single.pfm" merge single.pfm --output out/m.pfm
refused "output is a part" "is the part" merge p3_1.exr p3_2.exr p3_3.exr --output p3_1.exr
refused "existing output" "--output 'single.pfm' exists; add --force" merge p3_1.exr p3_2.exr p3_3.exr --output single.pfm
refused "no output" "no --output" merge p3_1.exr
# an interrupted part (Ctrl-C: exit 3, the samples so far written) is refused as incomplete:
# part 1/1 of a scene of 10^6 samples per pixel; the signal must land in the render, after the
# first launch: wait longer if it came too early
for wait_s in 2 4 8; do
    "$atmo" render --preset sky-sunset --width 16 --height 16 --samples 1000000 --quiet --part 1/1 \
        --output cut.exr 2>/dev/null &
    pid=$!
    sleep $wait_s
    kill -INT $pid
    wait $pid
    rc=$?
    [ $rc -ne 4 ] && break
done
[ $rc -eq 3 ] && ok || bad "interrupted part: exit $rc, want 3"
refused "incomplete part" "'cut.exr' \\(part 1/1\\) is incomplete: [0-9]+ (to [0-9]+ )?samples( per pixel| in every pixel), its scene 1000000" \
    merge cut.exr --output out/m.pfm
refused "--part to a PNG" "one --output FILE.exr" render "${scene[@]}" --part 1/2 --output out/p.png
refused "--part with two outputs" "one --output FILE.exr" render "${scene[@]}" --part 1/2 --output out/p.exr --output out/q.exr
refused "--part 0/2" "--part needs I/N" render "${scene[@]}" --part 0/2 --output out/p.exr
refused "--part 3/x" "--part needs I/N" render "${scene[@]}" --part 3/x --output out/p.exr
refused "more parts than bands" "only 5 bands" render "${scene[@]}" --part 1/6 --output out/p.exr
refused "spectral mode" "spectral mode" render "${scene[@]}" --set render.spectral_bands=15 --part 1/2 --output out/p.exr

cli_end test_merge
