#!/bin/bash
# test_terrain_cli.sh — `atmo terrain --at X,Z`, the terrain keys in `atmo params` and the
# terrain presets in `atmo presets`.
# labels: cli
#
# Oracles: the double-precision host reference (host/terrain/terrain_ref.c), which the probe
# prints beside the kernels' float height: within the float rounding bound of
# test_terrain_noise (0.3 m for |X|, |Z| below 100 km); a unit normal (|n| = 1 within 1e-6,
# float rounding of a normalised vector); coverage in [0, 1]; material weights summing to 1
# within 1e-5 (five floats); water exactly where the height is at or below sea level, with
# weight 1 and the vertical as its normal (here the sea covers the planet: land_fraction=0).
# Bad input: exit status 2 and one line on stderr.
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

"$atmo" terrain --preset thesis-1 --at 23796,16636 --at -5000,12000 --at 90000,-40000 --json \
    >"$tmp/land.json" || { echo "terrain probe failed"; fail=1; }
"$atmo" terrain --preset thesis-1 --set terrain.land_fraction=0 --at 1000,2000 --json \
    >"$tmp/sea.json" || { echo "sea probe failed"; fail=1; }
python3 - "$tmp/land.json" "$tmp/sea.json" <<'PY' || fail=1
import json, math, sys
bad = 0
land = [json.loads(l) for l in open(sys.argv[1])]
sea = [json.loads(l) for l in open(sys.argv[2])]
if len(land) != 3 or len(sea) != 1:
    print("expected 3 + 1 JSON lines"); sys.exit(1)
for o in land + sea:
    for k in ("height_m", "normal", "coverage", "materials", "surface_m", "water"):
        if k not in o:
            print("missing key", k); bad = 1
    n = o["normal"]
    if abs(math.sqrt(sum(c * c for c in n)) - 1) > 1e-6:
        print("normal not unit:", n); bad = 1
    if not 0 <= o["coverage"] <= 1:
        print("coverage out of range:", o["coverage"]); bad = 1
    if abs(sum(o["materials"].values()) - 1) > 1e-5:
        print("material weights do not sum to 1:", o["materials"]); bad = 1
    if abs(o["height_m"] - o["height_ref_m"]) > 0.3:
        print("float height %.4f vs double %.4f" % (o["height_m"], o["height_ref_m"])); bad = 1
for o in land:
    if o["water"] or o["height_m"] <= 0:
        print("thesis site expected land:", o); bad = 1
s = sea[0]
if not s["water"] or s["materials"]["water"] != 1 or s["normal"][1] < 0.999999:
    print("expected water with a vertical normal:", s); bad = 1
sys.exit(bad)
PY

"$atmo" terrain --preset thesis-1 --at 23796,16636 | grep -q "height .* m above sea level" ||
    { echo "text output lacks the height line"; fail=1; }
"$atmo" params | grep -q "^terrain.enabled" || { echo "atmo params lacks terrain.enabled"; fail=1; }
for p in thesis-1 thesis-2 thesis-3 thesis-8 thesis-9 space; do
    "$atmo" presets | grep "^$p" | grep -q -i "terrain\|continents" ||
        { echo "atmo presets: $p does not say it has terrain"; fail=1; }
done

for args in "--at 1,2,3" "--at abc" "" "--at 1e9,0" "--at 1,2 --set terrain.octaves=0" \
    "--at 1,2 --bogus"; do
    "$atmo" terrain $args >/dev/null 2>"$tmp/err"
    rc=$?
    lines=$(wc -l <"$tmp/err")
    if [ "$rc" -ne 2 ] || [ "$lines" -ne 1 ]; then
        echo "atmo terrain $args: exit $rc with $lines stderr lines (want 2 and 1)"; fail=1
    fi
done
exit $fail
