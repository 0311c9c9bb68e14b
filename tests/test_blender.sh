#!/usr/bin/env bash
# test_blender — `atmo render --blender` writes what Blender reads as it is: linear Rec.709 RGB
# with the standard chromaticities, the quantity and unit stated, panoramas in Blender's world
# orientation, and the World settings that reproduce the PNG's exposure; radiance output keeps
# its wavelengths and gets no chromaticities.
# labels: cli render
#
# Oracles:
#  - attributes: OpenEXR's own reader (exrheader) against ITU-R BT.709's primaries and D65 white
#    (x, y: R 0.64 0.33, G 0.30 0.60, B 0.15 0.06, W 0.3127 0.3290), channels exactly B, G, R;
#  - orientation: Cycles' equirectangular mapping (blender/blender,
#    intern/cycles/kernel/camera/projection.h: u = 1/2 - atan2(y, x) / 2 pi, v = 1 - acos(z) / pi,
#    row 0 of the file at v = 1) with Blender's axes (X, Y, Z) = atmo's (X, Z, Y), so a sun at
#    zenith angle z and azimuth a (atmo's direction (sin z sin a, cos z, sin z cos a)) lies at
#    column u W = (1/4 + a / 360 deg) W and row z / 180 deg H, whatever camera.yaw_deg the scene
#    had. The sun (angular radius 4 deg, 3 px) is found as the luminance-weighted centroid of
#    the pixels above 1e6 cd/m^2 (the disc keeps the sun's irradiance, so it is ~7e6 at this
#    radius, against ~1e5 for the brightest sky); 16 samples per
#    pixel put the centroid within about 0.1 px of the disc's centre, so the tolerance is 0.5 px,
#    where yaw 0 would be 32 px off and a mirrored map 21 px;
#  - World strength: post.c's pipeline (x = S m_c L_c, PNG = round(255 srgb(1 - exp(-x)))) with
#    S and m the file's blenderWorldStrength and blenderWhiteBalance, for every pixel of the PNG
#    written beside it, within one 8-bit step (float vs double rounding at a half step).
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
if ! command -v exrheader >/dev/null; then
    echo "test_blender: exrheader (package openexr) not found; skipped"
    exit 77
fi

# attr FILE NAME: the text exrheader prints for one attribute (its first line and what follows)
attr() { exrheader "$1" | sed -n "/^$2 (/,/^[a-zA-Z]/p" | sed '$d;1s/^[^:]*: *//'; }

# output.denoise=off: the PNG is checked against the EXR through the tone map, so both must be
# the image as rendered (auto denoises the PNG alone)
pano=(render --preset sky-noon --camera panorama --width 128 --height 64 --samples 16 --quiet
      --set sun.angular_radius_deg=4 --set post.exposure=10 --set post.tonemap=exposure
      --set camera.yaw_deg=30 --set output.denoise=off --blender)

# sun_at Z A: render with the sun at zenith angle Z, azimuth A and check its pixel
sun_at() {
    local z=$1 a=$2
    if ! "$atmo" "${pano[@]}" --set sun.zenith_deg="$z" --set sun.azimuth_deg="$a" \
        -o "sun$a.exr" -o "sun$a.pfm" -o "sun$a.png" 2>"sun$a.err"; then
        bad "render sun $z/$a: $(cat "sun$a.err")"
        return
    fi
    if python3 - "sun$a.pfm" "$z" "$a" <<'EOF'; then ok; else bad "sun $z/$a not at Blender's pixel"; fi
import struct, sys
path, z, a = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
data = open(path, "rb").read()
parts = data.split(b"\n", 3)
w, h = map(int, parts[1].split())
scale = float(parts[2])
fmt = "<" if scale < 0 else ">"
px = struct.unpack(fmt + "%df" % (w * h * 3), parts[3][: w * h * 12])
sx = sy = sw = 0.0
for row in range(h):                      # PFM: bottom row first
    y = h - 1 - row
    for x in range(w):
        r, g, b = px[3 * (row * w + x): 3 * (row * w + x) + 3]
        lum = 0.2126 * r + 0.7152 * g + 0.0722 * b
        if lum > 1e6:
            sx += lum * (x + 0.5); sy += lum * (y + 0.5); sw += lum
if sw == 0:
    sys.exit("no sun pixel")
cx, cy = sx / sw, sy / sw
want_x = ((0.25 + a / 360.0) % 1.0) * w
want_y = z / 180.0 * h
print("sun z %g a %g: centroid (%.3f, %.3f), Blender's mapping (%.3f, %.3f)" % (z, a, cx, cy, want_x, want_y))
sys.exit(0 if abs(cx - want_x) < 0.5 and abs(cy - want_y) < 0.5 else 1)
EOF
}

sun_at 60 30
sun_at 80 200

# the attributes of the --blender EXR
f=sun30.exr
[ "$(exrheader "$f" | sed -n '/^channels/,/^[a-z]/p' | grep -c '32-bit floating-point')" = 3 ] &&
    [ "$(exrheader "$f" | sed -n '/^channels/,/^[a-z]/p' | awk '/floating/ {printf "%s", $1}')" = "B,G,R," ] &&
    ok || bad "channels are not exactly R, G, B: $(attr "$f" channels)"
chroma=$(attr "$f" chromaticities | tr -s ' \n' ' ')
[ "$chroma" = " red (0.64 0.33) green (0.3 0.6) blue (0.15 0.06) white (0.3127 0.329) " ] &&
    ok || bad "chromaticities: '$chroma'"
[ "$(attr "$f" colorInteropID)" = '"lin_rec709_scene"' ] && ok || bad "colorInteropID: $(attr "$f" colorInteropID)"
attr "$f" quantity | grep -q '^"luminance' && ok || bad "quantity: $(attr "$f" quantity)"
[ "$(attr "$f" unit)" = '"cd m^-2"' ] && ok || bad "unit: $(attr "$f" unit)"
[ -z "$(attr "$f" wavelengths)" ] && ok || bad "an RGB file names wavelengths: $(attr "$f" wavelengths)"
[ "$(attr "$f" blenderWorldStrength)" = '"0.0001"' ] && ok ||
    bad "blenderWorldStrength $(attr "$f" blenderWorldStrength), want 10 x 1e-5"

# the strength rule: the PNG is the EXR's values times S and m through the tone map
S=$(attr "$f" blenderWorldStrength | tr -d '"')
M=$(attr "$f" blenderWhiteBalance | tr -d '"')
if python3 - sun30.pfm sun30.png "$S" $M <<'EOF'; then ok; else bad "PNG is not strength x EXR through the tone map"; fi
import math, struct, sys, zlib
pfm, png, s = sys.argv[1], sys.argv[2], float(sys.argv[3])
m = [float(v) for v in sys.argv[4:7]]
data = open(pfm, "rb").read()
parts = data.split(b"\n", 3)
w, h = map(int, parts[1].split())
fmt = "<" if float(parts[2]) < 0 else ">"
lin = struct.unpack(fmt + "%df" % (w * h * 3), parts[3][: w * h * 12])
raw = open(png, "rb").read()
pos, idat = 8, b""
while pos < len(raw):
    n, kind = struct.unpack(">I4s", raw[pos: pos + 8])
    if kind == b"IHDR":
        pw, ph, depth, ctype = struct.unpack(">IIBB", raw[pos + 8: pos + 18])
        assert (pw, ph, depth, ctype) == (w, h, 8, 2), (pw, ph, depth, ctype)
    if kind == b"IDAT":
        idat += raw[pos + 8: pos + 8 + n]
    pos += 12 + n
rows, prev, stride = zlib.decompress(idat), bytearray(w * 3), w * 3
img = []
for y in range(h):
    ft, line = rows[y * (stride + 1)], bytearray(rows[y * (stride + 1) + 1: (y + 1) * (stride + 1)])
    for i in range(stride):
        left = line[i - 3] if i >= 3 else 0
        up, ul = prev[i], prev[i - 3] if i >= 3 else 0
        if ft == 1: line[i] = (line[i] + left) & 255
        elif ft == 2: line[i] = (line[i] + up) & 255
        elif ft == 3: line[i] = (line[i] + (left + up) // 2) & 255
        elif ft == 4:
            p = left + up - ul
            pa, pb, pc = abs(p - left), abs(p - up), abs(p - ul)
            line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else ul)) & 255
    img.append(line)
    prev = line
def srgb(v):
    v = min(max(v, 0.0), 1.0)
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
worst = 0
for y in range(h):
    row = h - 1 - y                       # PFM rows bottom first
    for x in range(w):
        for c in range(3):
            v = lin[3 * (row * w + x) + c]
            want = math.floor(255 * srgb(-math.expm1(-s * m[c] * v)) + 0.5)
            worst = max(worst, abs(img[y][3 * x + c] - want))
print("PNG vs strength x EXR through the tone map: worst %d of 255" % worst)
sys.exit(0 if worst <= 1 else 1)
EOF

# radiance output: wavelengths, no chromaticities, no Blender attributes
if "$atmo" render --preset sky-sunset --width 16 --height 8 --samples 1 --quiet -o rad.exr 2>rad.err; then
    [ "$(attr rad.exr wavelengths)" = '"R 680 nm, G 550 nm, B 440 nm"' ] && ok ||
        bad "radiance wavelengths: $(attr rad.exr wavelengths)"
    [ -z "$(attr rad.exr chromaticities)$(attr rad.exr colorInteropID)$(attr rad.exr blenderWorldStrength)" ] &&
        ok || bad "radiance output claims RGB primaries or Blender settings"
else
    bad "radiance render: $(cat rad.err)"
fi

# the scene key: a saved --blender scene renders the same settings without rescaling again
"$atmo" "${pano[@]}" --save-scene blender.json 2>save.err && grep -qE '"blender":[[:space:]]*true' blender.json &&
    ok || bad "--save-scene with --blender: $(cat save.err)"
if "$atmo" render --scene blender.json --width 16 --height 8 --samples 1 --quiet -o again.exr 2>again.err; then
    [ "$(attr again.exr blenderWorldStrength)" = '"0.0001"' ] && ! grep -q "for Blender" again.err &&
        ok || bad "the saved scene is rewritten again: $(attr again.exr blenderWorldStrength) $(cat again.err)"
else
    bad "render of the saved scene: $(cat again.err)"
fi

cli_end test_blender
