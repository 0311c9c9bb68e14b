#!/usr/bin/env bash
# test_reliability_parts — parts and their inputs are verified: a part cut short or with one
# flipped bit in its pixels, parts rendered from different heightmap contents under one file
# name, and a PNG heightmap whose chunk CRC is wrong are each refused with exit 2 and one line
# naming the file; --part with --noise or --time-limit (which would leave parts that merge
# cannot join) is refused before any work; a --noise render's report gives each tile's noise.
# labels: reliability cli render
#
# Oracles: the part format of atmo/part.h (atmoDataChecksum: FNV-1a 64 over the stored planes,
# so any changed byte of the pixels changes it; atmoInputHash: the heights the render read),
# the PNG specification's chunk CRC-32 (ISO/IEC 15948 5.3; the test writes its PNGs with
# Python's zlib.crc32, an independent implementation), and the refusal contract of
# tests/support_cli.sh (exit 2, one stderr line matching, nothing written).
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
export ATMO_CACHE_DIR=$work/cache TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
scene=(--preset sky-sunset --width 16 --height 16 --samples 2 --seed 3 --quiet)

# write_dem FILE BASE [BAD_CRC]: an 8 x 8 16-bit grey PNG, heights BASE + 10 (x + y); with
# BAD_CRC the IDAT chunk's stored CRC has one bit flipped (its data intact)
write_dem() {
    python3 - "$@" <<'PY'
import struct, sys, zlib
path, base = sys.argv[1], int(sys.argv[2])
bad = len(sys.argv) > 3
def chunk(t, d, flip=False):
    crc = zlib.crc32(t + d) & 0xffffffff
    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', crc ^ (1 if flip else 0))
rows = b''.join(b'\0' + b''.join(struct.pack('>H', base + 10 * (x + y)) for x in range(8)) for y in range(8))
open(path, 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 8, 8, 16, 0, 0, 0, 0))
    + chunk(b'IDAT', zlib.compress(rows), bad) + chunk(b'IEND', b''))
PY
}

for i in 1 2; do
    "$atmo" render "${scene[@]}" --part $i/2 --output p$i.exr || bad "part $i/2 failed"
done
"$atmo" merge --quiet p1.exr p2.exr --output whole.pfm && ok || bad "the intact parts do not merge"

# a part cut short: exit 2, the file named, what is wrong said
size=$(stat -c %s p1.exr)
head -c $((size - 3000)) p1.exr >cut.exr
refused "a part cut short" "'cut.exr' is damaged or cut short" merge cut.exr p2.exr --output out/m.pfm

# one bit flipped in the pixels, 100 bytes before the end (the last rows' planes)
python3 -c "
import sys
d = bytearray(open('p1.exr', 'rb').read()); d[-100] ^= 0x10
open('flip.exr', 'wb').write(d)"
refused "a part with a flipped bit" "'flip.exr'.* is damaged" merge flip.exr p2.exr --output out/m.pfm

# parts of one scene text, rendered from different heightmap contents under one name
terrain=(--set terrain.heightmap_file=dem.png --set terrain.heightmap_file_extent_m=8000)
write_dem dem.png 1000
"$atmo" render "${scene[@]}" "${terrain[@]}" --part 1/2 --output t1.exr || bad "terrain part 1/2 failed"
write_dem dem.png 3000
"$atmo" render "${scene[@]}" "${terrain[@]}" --part 2/2 --output t2.exr || bad "terrain part 2/2 failed"
refused "parts from different heightmap contents" "'t2.exr' was rendered from other input data than 't1.exr'" \
    merge t1.exr t2.exr --output out/m.pfm

# a PNG heightmap whose IDAT CRC is wrong
write_dem bad.png 1000 bad_crc
refused "a PNG heightmap with a bad CRC" "bad.png: chunk 2 \(IDAT\) at byte 33 fails its CRC-32" \
    render "${scene[@]}" --set terrain.heightmap_file=bad.png --set terrain.heightmap_file_extent_m=8000 --output out/a.pfm

# --part with --noise or --time-limit
refused "--part with --noise" "--part renders every pixel.*--noise cannot stop it" \
    render "${scene[@]}" --part 1/2 --noise 5% --output out/p.exr
refused "--part with --time-limit" "--time-limit cannot stop it" \
    render "${scene[@]}" --part 1/2 --time-limit 10 --output out/p.exr

# a --noise render's report states the noise each tile reached: the tiles cover the image once,
# and a tile that stopped before image.samples had met the target (the session's stopping rule,
# atmo/session.h; the report's e is computed from the same sums, in double from float errors,
# hence the relative slack of 1e-4)
"$atmo" render --preset sky-sunset --width 32 --height 16 --tile-size 8 --samples 256 --noise 5% --quiet \
    --output noise.pfm --report noise.json || bad "--noise render failed"
python3 - <<'PY' && ok || bad "the report's tiles_noise does not state each tile's noise"
import json, sys
r = json.load(open('noise.json'))['render']
tiles = r.get('tiles_noise', [])
area = sum(t['w'] * t['h'] for t in tiles)
early = [t for t in tiles if t['samples'] < r['samples_requested']]
ok = (len(tiles) == 8 and area == 32 * 16 and early
      and all(t['noise'] <= r['noise_target'] * (1 + 1e-4) for t in early)
      and all(t['noise'] > 0 for t in tiles))
if not ok:
    print(tiles, file=sys.stderr)
sys.exit(not ok)
PY

cli_end test_reliability_parts
