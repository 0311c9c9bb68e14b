#!/usr/bin/env bash
# test_merge_denoise — `atmo merge` of parts whose scene asks for denoising denoises the merged
# image once, with the albedo and normal guides `atmo render` uses (host/cli/cmd_merge.c).
# labels: cli render
#
# Oracle: the single-process render of the same scene, seed, samples and --denoise on the same
# device. The merged sums are the single render's exactly (test_merge); the merge renders the
# guides of the whole image itself, and the guides draw no random number, so they are the single
# render's bit for bit; Open Image Denoise's CPU filter gives the same output for the same input
# on one machine (measured: repeated runs are bitwise equal, which these comparisons would catch
# otherwise). So the denoised .exr, .pfm and .png are compared byte for byte (cmp), with no
# tolerance. Scene: thesis-7 path traced (an open box, Monte Carlo noise on every surface),
# 48x40 in bands of 8 rows, 4 samples per pixel, --denoise fast; parts of 3 (tile sizes 8, 16,
# 48) and of 2. Also: the merge's report says what render's says (applied, quality fast, guides
# "albedo, normal", clean_aux), the merged EXR holds the guide layers and the "denoise"
# attribute naming the guides, and the merge refuses, exit 2 with one line and no output, a
# heightmap that differs from the one the parts read (the guides would be another terrain's),
# a --device that names none and a --denoise that names no quality. --denoise at the merge
# replaces the parts' setting: parts rendered with --denoise off and merged with --denoise fast
# give the single --denoise fast render's files byte for byte, and --denoise off denoises
# nothing.
# Without the library the test is skipped (setup.sh installs it, so CI runs it).
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin

scene=(--preset thesis-7 --width 48 --height 40 --samples 4 --seed 3 --denoise fast --quiet)
if ! "$atmo" render "${scene[@]}" --output single.exr --output single.pfm --output single.png \
    --report single.json 2>probe.txt; then
    if grep -q "not installed" probe.txt; then
        echo "SKIP: $(cat probe.txt)" >&2
        exit 77
    fi
    cat probe.txt >&2
    exit 1
fi

# same_files A B: byte for byte, for each of .exr .pfm .png
same_files() {
    local x
    for x in exr pfm png; do
        cmp -s "$1.$x" "$2.$x" && ok || bad "$2.$x differs from $1.$x"
    done
}

tiles=(8 16 48)
for i in 1 2 3; do
    "$atmo" render "${scene[@]}" --part $i/3 --tile-size ${tiles[i - 1]} --output p3_$i.exr ||
        bad "part $i/3 failed"
done
"$atmo" merge p3_3.exr p3_1.exr p3_2.exr --output m3.exr --output m3.pfm --output m3.png \
    --report m3.json 2>merge.txt || bad "merge of 3 parts failed"
same_files single m3
grep -q "denoised with albedo and normal guides" merge.txt && ok ||
    { bad "merge's summary does not say it denoised with guides"; cat merge.txt >&2; }

for i in 1 2; do
    "$atmo" render "${scene[@]}" --part $i/2 --output p2_$i.exr || bad "part $i/2 failed"
done
"$atmo" merge --quiet p2_1.exr p2_2.exr --output m2.exr --output m2.pfm --output m2.png ||
    bad "merge of 2 parts failed"
same_files single m2

python3 - single.json m3.json <<'EOF' && ok || bad "the merge's report differs from render's on denoising"
import json, sys
r = json.load(open(sys.argv[1]))["render"]["denoise"]
m = json.load(open(sys.argv[2]))["merge"]["denoise"]
for d in (r, m):
    assert d["applied"] is True and d["quality"] == "fast", d
    assert d["guides"] == "albedo, normal" and d["clean_aux"] is True, d
    assert d["guide_pass_seconds"] > 0, d
for k in ("setting", "applied", "quality", "guides", "clean_aux", "sun_disc_kept_out",
          "library_version"):
    assert r[k] == m[k], (k, r[k], m[k])
EOF

if command -v exrheader >/dev/null; then
    exrheader m3.exr >hdr.txt
    grep -q 'denoise (type string): ".*albedo and normal guides' hdr.txt && ok ||
        bad "m3.exr's denoise attribute does not name the guides"
    for c in "Denoising Albedo.R" "Denoising Normal.X" "Denoising Depth.Z" "Noisy Image.R"; do
        grep -q "^ *$c, 32-bit floating-point" hdr.txt && ok || bad "m3.exr lacks the layer '$c'"
    done
fi

refused "unknown --device" "device" merge p2_1.exr p2_2.exr --device no-such-device --output out/m.pfm

# --denoise at the merge: parts rendered with --denoise off merge with --denoise fast into the
# single render's denoised files (the parts are sums either way; the merge sets the quality);
# and the parts' own setting is overridden the other way, --denoise off giving no denoised PNG
for i in 1 2; do
    "$atmo" render "${scene[@]}" --denoise off --part $i/2 --output raw2_$i.exr ||
        bad "part $i/2 with --denoise off failed"
done
"$atmo" merge --quiet raw2_1.exr raw2_2.exr --denoise fast --output md.exr --output md.pfm \
    --output md.png || bad "merge with --denoise fast failed"
same_files single md
"$atmo" merge --quiet p2_1.exr p2_2.exr --denoise off --output raw.png --report raw.json ||
    bad "merge with --denoise off failed"
python3 -c "import json, sys; d = json.load(open('raw.json'))['merge'].get('denoise', {}); sys.exit(d.get('applied', False))" &&
    ok || bad "merge --denoise off still denoised"
cmp -s raw.png single.png && bad "merge --denoise off wrote the denoised PNG" || ok
refused "bad --denoise" "output.denoise.*did you mean 'high'" merge p2_1.exr p2_2.exr --denoise hig --output out/m.png

# a heightmap changed after the parts were rendered: its guides would be another terrain's.
# ramp FILE K: a 16x16 16-bit greyscale PNG of heights 4000 ((x + K y) mod 17)
ramp() {
    python3 - "$1" "$2" <<'EOF'
import struct, sys, zlib
w, h, k = 16, 16, int(sys.argv[2])
rows = b"".join(b"\0" + b"".join(struct.pack(">H", 4000 * ((x + k * y) % 17)) for x in range(w))
                for y in range(h))
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 0, 0, 0, 0))
open(sys.argv[1], "wb").write(png + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
EOF
}
ramp ramp.png 3
dem=(--preset sky-sunset --width 16 --height 16 --samples 1 --quiet --set render.mode=path --denoise fast
     --set terrain.heightmap_file="$work/ramp.png" --set terrain.heightmap_file_extent_m=4000
     --set terrain.heightmap_scale_m=512)
"$atmo" render "${dem[@]}" --part 1/2 --output d1.exr && "$atmo" render "${dem[@]}" --part 2/2 \
    --output d2.exr || bad "parts with a heightmap failed"
"$atmo" merge --quiet d1.exr d2.exr --output d.png && ok || bad "merge with the same heightmap failed"
ramp ramp.png 5
refused "changed heightmap" "the heightmap '.*ramp.png' is not the one the parts were rendered with" \
    merge d1.exr d2.exr --output out/d.png

cli_end test_merge_denoise
