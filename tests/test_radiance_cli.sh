#!/bin/bash
# test_radiance_cli.sh — `atmo radiance` end to end: text and JSON shape, values, bad input.
# labels: cli
#
# Oracles: (1) the double-precision host reference (atmo_ref_single_scattering +
# atmo_ref_ground_radiance, adaptive quadrature to 1e-9), evaluated for the default atmosphere,
# camera at 1000 m, sun zenith 30 deg, at the float rays the CLI builds; the single-scattering
# method through the CLI must match within 1 % (test_sky_single's target; 64 march segments, 64
# jittered samples). (2) Published direct irradiance at sun zenith 30 deg on the ground
# (atmosphere.md: 1.189 / 1.360 / 1.211 W m^-2 nm^-1), within half a unit of the last printed digit
# plus 1e-4. (3) The stored reference table tests/data/reference_sky.csv
# (tools/make_reference_table.py) still describes the reference method: three of its rows re-run
# live with 65536 samples must agree within |z| < 4, z using the live and the stored standard
# errors combined.
# (4) Aerial perspective (--distance-m): a segment longer than every ray is the sky radiance,
# the same numbers with the same seed; in-scattering only adds light along a ray and T only
# falls, so for d = 1 km < 10 km < the whole ray the radiance rises and the transmittance falls
# (test_aerial checks the values against the double and Monte Carlo references).
# (5) Its scene without --scene is the scene defaults (clear air), as the help says: the output
# equals that of a scene file that sets nothing, byte for byte.
# Shape: one text line per view; the JSON parses and has its documented keys; the reference
# method reports standard errors. Bad input: exit status 2 and one line on stderr.
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

views="--view 0,0 --view 60,0 --view 80,180 --view 45,90 --view 120,0"
"$atmo" radiance --altitude-m 1000 --sun-zenith-deg 30 $views --method single \
    --set render.view_steps=64 --json >"$tmp/single.json" || { echo "single run failed"; fail=1; }
python3 - "$tmp/single.json" <<'PY' || fail=1
import json, sys
d = json.load(open(sys.argv[1]))
assert d["method"] == "single" and d["wavelengths_nm"] == [680, 550, 440], d
want = {  # atmo_ref_single_scattering (+ ground radiance for 120 deg), double precision
    (0, 0): (6.592100e-03, 1.685173e-02, 3.680478e-02),
    (60, 0): (1.286263e-02, 3.196739e-02, 6.537723e-02),
    (80, 180): (1.908867e-02, 4.560586e-02, 7.776468e-02),
    (45, 90): (6.710481e-03, 1.769724e-02, 3.835451e-02),
    (120, 0): (3.816987e-02, 4.440715e-02, 4.118441e-02),
}
assert len(d["views"]) == len(want)
worst = 0.0
for v in d["views"]:
    w = want[(v["zenith_deg"], v["azimuth_deg"])]
    for got, ref in zip(v["radiance"], w):
        worst = max(worst, abs(got / ref - 1))
    assert v["luminance_cd_m2"] > 0
assert worst < 0.01, worst
assert "irradiance" not in d
print("single method via the CLI: worst relative error %.2e against the double reference" % worst)
PY

"$atmo" radiance --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --view 85,180 --irradiance \
    --method single >"$tmp/text.txt" || { echo "text run failed"; fail=1; }
[ "$(grep -cE '^ +[0-9.]+ +[0-9.-]+ +([0-9.e+-]+ +){3}[0-9.e+-]+$' "$tmp/text.txt")" = 2 ] ||
    { echo "expected one text line per view:"; cat "$tmp/text.txt"; fail=1; }
python3 - "$tmp/text.txt" <<'PY' || fail=1
import re, sys
line = [l for l in open(sys.argv[1]) if l.startswith("irradiance")][0]
nums = [float(x) for x in re.findall(r"[0-9.]+e[+-][0-9]+", line)]
direct, sky = nums[:3], nums[3:]
for got, want in zip(direct, (1.189, 1.360, 1.211)):
    assert abs(got - want) <= 5e-4 + 1e-4 * want, (got, want)
assert all(0 < s < d for s, d in zip(sky, direct)), (sky, direct)
print("direct irradiance matches atmosphere.md; sky irradiance", sky)
PY

"$atmo" radiance --altitude-m 0 --sun-zenith-deg 60 --view 0,0 --method reference \
    --samples 4096 --irradiance --json >"$tmp/ref.json" || { echo "reference run failed"; fail=1; }
python3 - "$tmp/ref.json" <<'PY' || fail=1
import json, sys
d = json.load(open(sys.argv[1]))
v = d["views"][0]
assert d["method"] == "reference" and d["samples"] == 4096
assert all(0 < s < 0.1 * L for L, s in zip(v["radiance"], v["radiance_standard_error"])), v
assert len(d["irradiance"]["direct"]) == 3 and len(d["irradiance"]["sky"]) == 3
PY

table=${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/data/reference_sky.csv
for row in "30 0 0" "80 85 0" "90 60 180"; do
    set -- $row
    "$atmo" radiance --altitude-m 0 --sun-zenith-deg "$1" --view "$2,$3" --method reference \
        --samples 65536 --seed 7 --json >"$tmp/live.json" || { echo "live run failed"; fail=1; }
    python3 - "$tmp/live.json" "$table" "$@" <<'PY' || fail=1
import csv, json, math, sys
d = json.load(open(sys.argv[1]))["views"][0]
sun, z, a = (float(x) for x in sys.argv[3:6])
rows = [r for r in csv.reader(l for l in open(sys.argv[2]) if not l.startswith("#"))][1:]
row = [r for r in rows if (float(r[0]), float(r[1]), float(r[2])) == (sun, z, a)][0]
for c in range(3):
    L, se = float(row[4 + c]), float(row[7 + c])
    zz = (d["radiance"][c] - L) / math.hypot(se, d["radiance_standard_error"][c])
    assert abs(zz) < 4, (sun, z, a, c, d["radiance"][c], L, zz)
print("table row sun %g view %g,%g reproduced live" % (sun, z, a))
PY
done

views="--view 0,0 --view 85,180 --view 100,90"
for d in 1000 10000 1e9; do
    "$atmo" radiance --altitude-m 1000 --sun-zenith-deg 30 $views --method single --seed 3 \
        --distance-m $d --json >"$tmp/seg_$d.json" || { echo "segment run failed"; fail=1; }
done
"$atmo" radiance --altitude-m 1000 --sun-zenith-deg 30 $views --method single --seed 3 \
    --json >"$tmp/seg_sky.json" || { echo "sky run failed"; fail=1; }
python3 - "$tmp" <<'PY' || fail=1
import json, sys
runs = [json.load(open("%s/seg_%s.json" % (sys.argv[1], d))) for d in ("1000", "10000", "1e9")]
sky = json.load(open(sys.argv[1] + "/seg_sky.json"))
assert [r["distance_m"] for r in runs] == [1000, 10000, 1e9] and "distance_m" not in sky
for i, v in enumerate(sky["views"]):
    seg = [r["views"][i] for r in runs]
    assert all(len(s["transmittance"]) == 3 and len(s["transmittance_standard_error"]) == 3
               for s in seg)
    assert seg[2]["radiance"] == v["radiance"], (seg[2]["radiance"], v["radiance"])
    for c in range(3):
        L = [s["radiance"][c] for s in seg]
        T = [s["transmittance"][c] for s in seg]
        assert 0 < L[0] < L[1] <= L[2], (v["zenith_deg"], c, L)
        assert 1 >= T[0] > T[1] >= T[2] >= 0, (v["zenith_deg"], c, T)
print("segments: 1 km < 10 km < the whole ray; d = 1e9 m reproduces the sky radiance")
PY
"$atmo" radiance --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --view 85,180 --method single \
    --distance-m 5000 >"$tmp/seg.txt" || { echo "segment text run failed"; fail=1; }
# without --scene the scene is the defaults alone (not the default preset of render): the same
# output as a scene file that sets nothing
echo '{}' >"$tmp/empty.json"
"$atmo" radiance --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --view 85,180 --method single \
    --distance-m 5000 --scene "$tmp/empty.json" >"$tmp/seg_empty.txt" &&
    cmp -s "$tmp/seg.txt" "$tmp/seg_empty.txt" ||
    { echo "radiance without --scene differs from --scene {} (the defaults)"; fail=1; }
[ "$(grep -cE '^ +[0-9.]+ +[0-9.-]+ +([0-9.e+-]+ +){3}[0-9.e+-]+( +[0-9.]+){3}$' "$tmp/seg.txt")" = 2 ] ||
    { echo "expected one text line per view with three transmittances:"; cat "$tmp/seg.txt"; fail=1; }

bad() { # expect exit 2 and exactly one line on stderr
    "$atmo" radiance "$@" >/dev/null 2>"$tmp/err"
    local rc=$?
    if [ $rc != 2 ] || [ "$(wc -l <"$tmp/err")" != 1 ]; then
        echo "atmo radiance $*: exit $rc, stderr:"; cat "$tmp/err"; fail=1
    fi
}
bad --sun-zenith-deg 30 --view 0,0
bad --altitude-m 0 --view 0,0
bad --altitude-m 0 --sun-zenith-deg 30
bad --altitude-m 0 --sun-zenith-deg 30 --view 45
bad --altitude-m 0 --sun-zenith-deg 30 --view 200,0
bad --altitude-m -5 --sun-zenith-deg 30 --view 0,0
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --method nonsense
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --set no.such_key=1
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --samples 0
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --scene "$tmp/missing.json"
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --bogus
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --distance-m 0
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --distance-m -100
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --distance-m 10km
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --distance-m
bad --altitude-m 0 --sun-zenith-deg 30 --view 0,0 --method reference \
    --set reference.min_order=3 --set reference.max_order=2
exit $fail
