#!/bin/bash
# test_dem_cli.sh — `atmo dem info` and the terrain.heightmap_* keys end to end.
# labels: cli
#
# Oracles: a 16-bit greyscale PNG written here (Python's zlib and struct, from the PNG
# specification) holds the values 0 .. 65535 in a known pattern, so with scale S and offset O
# the heights are O + S v / 65535: the lowest O and the highest O + S exactly (both exact in
# float for the values used), the extent the given east-west size and that size times
# height/width north-south, the cell size extent / samples. An EXR that `atmo render` writes
# has three channels (R, G, B), which a heightmap is not: refused. The keys are listed by
# `atmo params --json` with their types; a scene saved with a heightmap file reads back to the
# same bytes. Bad input (no file, a missing file, no extent) exits 2 with one line on stderr
# naming what is wrong, before any rendering (no output file is written). A heightmap file
# drawn as terrain replaces the procedural heights: the render differs from the procedural one,
# and with terrain.heightmap_detail the fBm's detail below its cells changes it again.
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "FAIL: $*" >&2; fail=1; }

# one_line_error RC_FILE NEEDLE: exit 2, one line on stderr containing NEEDLE
one_line_error() {
    local rc=$1 needle=$2
    if [ "$rc" -ne 2 ] || [ "$(wc -l <"$tmp/err")" -ne 1 ] || ! grep -qF -- "$needle" "$tmp/err"; then
        bad "expected exit 2 and one line with '$needle', got $rc:"
        cat "$tmp/err" >&2
    fi
}

python3 - "$tmp/ramp.png" <<'PY'
import struct, sys, zlib
w, h = 40, 25
rows = b""
for y in range(h):
    rows += b"\0" + b"".join(struct.pack(">H", (65535 * ((x + 3 * y) % 41)) // 40) for x in range(w))
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 0, 0, 0, 0))
png += chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")
open(sys.argv[1], "wb").write(png)
PY

keys=(--set terrain.heightmap_file_extent_m=4000 --set terrain.heightmap_scale_m=512
      --set terrain.heightmap_offset_m=-64)
"$atmo" dem info "$tmp/ramp.png" "${keys[@]}" --json >"$tmp/info.json" 2>"$tmp/err" ||
    { bad "atmo dem info --json failed"; cat "$tmp/err" >&2; }
python3 - "$tmp/info.json" <<'PY' || fail=1
import json, sys
d = json.load(open(sys.argv[1]))
assert d["width"] == 40 and d["height"] == 25, d
assert d["extent_m"] == [4000, 4000 * 25 / 40], d["extent_m"]
assert d["cell_m"] == [100, 100], d["cell_m"]
assert d["min_m"] == -64 and d["max_m"] == 448, (d["min_m"], d["max_m"])
assert d["format"].startswith("16-bit PNG") and d["nodata_filled"] == 0, d
assert d["nodata_fill"] == "neighbours", d
assert d["geographic"] is False and "terrain.heightmap_file_extent_m" in d["projection"], d
print("atmo dem info: 40 x 25 samples, %g x %g m, heights %g .. %g m" %
      (d["extent_m"][0], d["extent_m"][1], d["min_m"], d["max_m"]))
PY
"$atmo" dem info "$tmp/ramp.png" "${keys[@]}" >"$tmp/info.txt" 2>"$tmp/err" || bad "atmo dem info failed"
for field in "size        40 x 25 samples" "extent      4000 x 2500 m" "height      -64 .. 448 m" \
    "projection  none" "nodata      0 samples"; do
    grep -qF "$field" "$tmp/info.txt" || bad "atmo dem info: no line '$field'"
done

# bad input: one line, exit 2
"$atmo" dem info "$tmp/ramp.png" 2>"$tmp/err" >/dev/null
one_line_error $? "terrain.heightmap_file_extent_m"
"$atmo" dem info "$tmp/none.tif" 2>"$tmp/err" >/dev/null
one_line_error $? "none.tif"
"$atmo" dem info 2>"$tmp/err" >/dev/null
one_line_error $? "atmo dem info FILE"
"$atmo" dem 2>"$tmp/err" >/dev/null
one_line_error $? "info FILE"
"$atmo" dem info "$tmp/ramp.png" --set terrain.heightmap_file_extent_m=-1 2>"$tmp/err" >/dev/null
one_line_error $? "terrain.heightmap_file_extent_m"
# method single: the smallest program to build (PoCL compiles it in a few seconds)
"$atmo" render --preset sky-sunset --quiet --width 4 --height 4 --samples 1 --set atmosphere.method=single \
    --output "$tmp/rgb.exr" 2>"$tmp/err" || bad "render to EXR failed"
"$atmo" dem info "$tmp/rgb.exr" "${keys[@]}" 2>"$tmp/err" >/dev/null
one_line_error $? "3 channels"

# render: the file is checked while planning, before any work, and nothing is written
"$atmo" render --preset sky-sunset --quiet --width 4 --height 4 --samples 1 --set terrain.heightmap_file="$tmp/none.png" \
    --output "$tmp/out.png" 2>"$tmp/err" >/dev/null
one_line_error $? "none.png"
[ -e "$tmp/out.png" ] && bad "a refused render wrote its output"
"$atmo" render --preset sky-sunset --quiet --width 4 --height 4 --samples 1 --set terrain.heightmap_file="$tmp/ramp.png" \
    --output "$tmp/out.png" 2>"$tmp/err" >/dev/null
one_line_error $? "terrain.heightmap_file_extent_m"
"$atmo" render --preset sky-sunset --quiet --width 4 --height 4 --samples 1 --set terrain.heightmap_file="$tmp/ramp.png" \
    "${keys[@]}" --set atmosphere.method=single --output "$tmp/out.png" 2>"$tmp/err" >/dev/null ||
    bad "render with a heightmap failed"

# the keys: listed with their types; a saved scene reads back to the same bytes
"$atmo" params --json >"$tmp/params.json" || bad "atmo params --json failed"
python3 - "$tmp/params.json" <<'PY' || fail=1
import json, sys
types = {p["key"]: p["type"] for p in json.load(open(sys.argv[1]))}
want = {"terrain.heightmap_file": "string", "terrain.heightmap_file_extent_m": "float",
        "terrain.heightmap_center_m": "vec2", "terrain.heightmap_scale_m": "float",
        "terrain.heightmap_offset_m": "float", "terrain.heightmap_detail": "bool"}
for k, t in want.items():
    assert types.get(k) == t, (k, types.get(k))
PY
"$atmo" render --set terrain.heightmap_file="$tmp/my dem \"v2\".tif" \
    --set terrain.heightmap_center_m=1500,-2500 --save-scene "$tmp/s.json" 2>"$tmp/err" ||
    { bad "--save-scene with a heightmap failed"; cat "$tmp/err" >&2; }
"$atmo" render --scene "$tmp/s.json" --save-scene "$tmp/s2.json" 2>"$tmp/err" ||
    { bad "the saved scene does not load"; cat "$tmp/err" >&2; }
cmp -s "$tmp/s.json" "$tmp/s2.json" || bad "the saved scene does not read back to the same bytes"
python3 - "$tmp/s.json" "$tmp/my dem \"v2\".tif" <<'PY' || fail=1
import json, sys
t = json.load(open(sys.argv[1]))["terrain"]
assert t["heightmap_file"] == sys.argv[2] and t["heightmap_center_m"] == [1500, -2500], t
PY

# the file drawn as terrain (it implies terrain.enabled): it replaces the procedural heights
# (the image differs from the procedural's), and with terrain.heightmap_detail the fBm's
# octaves below its cells add to it (the image differs again, and has no NaN/Inf: a PFM's
# floats read back finite); the detail without a file is refused
view=(--preset sky-sunset --set terrain.enabled=true --set atmosphere.method=single --set camera.position_m=0,3000,12000
      --set camera.pitch_deg=-12 --set camera.yaw_deg=180 --width 32 --height 16 --samples 1 --quiet)
"$atmo" render "${view[@]}" --set terrain.heightmap_detail=true --output "$tmp/no.pfm" 2>"$tmp/err"
one_line_error $? "terrain.heightmap_file"
[ ! -e "$tmp/no.pfm" ] || bad "a refused render wrote its output"
"$atmo" render "${view[@]}" --output "$tmp/fbm.pfm" 2>"$tmp/err" || { bad "procedural render"; cat "$tmp/err" >&2; }
"$atmo" render "${view[@]}" --set terrain.heightmap_file="$tmp/ramp.png" \
    --set terrain.heightmap_file_extent_m=20000 --set terrain.heightmap_scale_m=2000 \
    --output "$tmp/dem.pfm" 2>"$tmp/err" || { bad "render with the DEM as terrain"; cat "$tmp/err" >&2; }
[ -s "$tmp/dem.pfm" ] && ! cmp -s "$tmp/fbm.pfm" "$tmp/dem.pfm" ||
    bad "the DEM render is missing or equals the procedural terrain's"
"$atmo" render "${view[@]}" --set terrain.heightmap_file="$tmp/ramp.png" \
    --set terrain.heightmap_file_extent_m=20000 --set terrain.heightmap_scale_m=2000 \
    --set terrain.heightmap_detail=true --output "$tmp/detail.pfm" 2>"$tmp/err" ||
    { bad "render with the DEM and its detail"; cat "$tmp/err" >&2; }
[ -s "$tmp/detail.pfm" ] && ! cmp -s "$tmp/dem.pfm" "$tmp/detail.pfm" ||
    bad "the DEM render with detail is missing or equals the one without"
python3 - "$tmp/detail.pfm" <<'PY' || fail=1
import math, struct, sys
data = open(sys.argv[1], "rb").read()
head = data.split(b"\n", 3)
w, h = map(int, head[1].split())
scale = float(head[2])
vals = struct.unpack(("<" if scale < 0 else ">") + "%df" % (3 * w * h), head[3][:12 * w * h])
assert all(math.isfinite(v) for v in vals), "NaN/Inf in the render with detail"
PY

# atmo terrain --at probes the file as a render draws it: at a heightmap texel centre (the
# default 1024 texels over 65536 m: centres at 32 + 64 k m) the height is the file's bicubic
# interpolant there (the plan resamples it onto the centres) within the float rounding of
# heights up to 2 km (1e-3 m), and "height_ref_m" is that interpolant in double; beyond the
# heightmap's square (|X| > 32768 m) the procedural field goes on, as without the file
# (sky-sunset leaves the terrain keys at their defaults, which the detail's bound below assumes)
dem=(--preset sky-sunset --set terrain.heightmap_file="$tmp/ramp.png" --set terrain.heightmap_file_extent_m=20000
     --set terrain.heightmap_scale_m=2000)
"$atmo" terrain "${dem[@]}" --at 32,32 --at 2080,-3104 --at 40000,100 --json >"$tmp/probe.json" \
    2>"$tmp/err" || { bad "atmo terrain --at with a heightmap file failed"; cat "$tmp/err" >&2; }
"$atmo" terrain "${dem[@]}" --set terrain.heightmap_detail=true --at 32,32 --at 2080,-3104 \
    --json >"$tmp/probe_detail.json" 2>"$tmp/err" ||
    { bad "atmo terrain --at with a heightmap file and detail failed"; cat "$tmp/err" >&2; }
"$atmo" terrain --preset sky-sunset --at 40000,100 --json >"$tmp/probe_fbm.json" 2>"$tmp/err" ||
    { bad "atmo terrain --at failed"; cat "$tmp/err" >&2; }
python3 - "$tmp/probe.json" "$tmp/probe_fbm.json" <<'PY' || fail=1
import json, math, sys
pts = [json.loads(l) for l in open(sys.argv[1])]
fbm = json.loads(open(sys.argv[2]).readline())
assert len(pts) == 3, pts
for p in pts[:2]:
    assert abs(p["height_m"] - p["height_ref_m"]) <= 1e-3, p
    assert p["height_m"] > 0 and p["coverage"] == 1, p
    assert abs(math.sqrt(sum(c * c for c in p["normal"])) - 1) < 1e-5, p
assert abs(pts[0]["height_m"] - pts[1]["height_m"]) > 1, pts
assert pts[2]["height_m"] == fbm["height_m"], (pts[2], fbm)
print("atmo terrain with the file: %.3f and %.3f m at texel centres (file %.3f, %.3f); "
      "beyond the heightmap the procedural %.3f m" % (pts[0]["height_m"], pts[1]["height_m"],
      pts[0]["height_ref_m"], pts[1]["height_ref_m"], pts[2]["height_m"]))
PY
# with the detail: the height is the file's interpolant plus the double detail
# (terrain_ref_detail, in "height_ref_m") within the same 1e-3 m, differs from the file's alone
# by at most the detail's bound (2 A, A = 4000 0.8 / sum b 2^-11 = 0.78 m for 64 m texels, the
# first octave with a period <= 32 m being the 11th) and not by nothing
python3 - "$tmp/probe.json" "$tmp/probe_detail.json" <<'PY' || fail=1
import json, sys
plain = [json.loads(l) for l in open(sys.argv[1])][:2]
det = [json.loads(l) for l in open(sys.argv[2])]
amp = 4000 * 0.8 / (2 * (1 - 0.5 ** 9)) / 2 ** 11
for p, d in zip(plain, det):
    assert abs(d["height_m"] - d["height_ref_m"]) <= 1e-3, d
    assert 0 < abs(d["height_m"] - p["height_m"]) <= 2 * amp, (p, d)
print("atmo terrain with the detail: %+.3f and %+.3f m over the file's heights (bound %.3f m)" %
      (det[0]["height_m"] - plain[0]["height_m"], det[1]["height_m"] - plain[1]["height_m"],
       2 * amp))
PY

[ $fail -eq 0 ] && echo "test_dem_cli: passed"
exit $fail
