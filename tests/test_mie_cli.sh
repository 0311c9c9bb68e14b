#!/bin/bash
# test_mie_cli.sh — `atmo mie` end to end: JSON for a case-10-like input, table file, table
# cache, chart, `atmo bench mie --quick`, bad input.
# labels: cli
#
# Oracle: MIEV0 case 10 (m = 1.33 - 1e-5 i, x = 100; ../shared/reference/mie.md): r = 10 um at
# lambda = 200 pi nm gives x = 100 to rounding. Q_ext, Q_sca, g within 1e-6 relative plus half a
# unit of the printed digit, S1/S2 at 0 and 180 deg within 1e-6 |S| (as test_mie_solver); the
# JSON must carry the sign convention. Bad input: one line on stderr and exit status 2.
# Cache: a second run with the same parameters loads the table and must write a byte-identical
# CSV (the oracle is the first, computed, run); --no-cache must agree too. Chart: an SVG with one
# path per wavelength exists; without gnuplot on PATH, exit 1 with one line naming gnuplot and no
# file. Bench: the CSVs have one row per phase option and per table setting, all numbers finite.
# Radius rule: --tolerance T stops with its own change estimate <= T RMS and 5 T at most (what
# the rule promises) at a finer step than a fixed --radius-step, which reports no estimate.
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
export ATMO_CACHE_DIR="$tmp/cache"

"$atmo" mie --radius-um 10 --wavelength-nm 628.3185307179586 --index 1.33+1e-5i \
    --angles-deg 0,90,180 --json >"$tmp/out.json" || { echo "atmo mie failed"; fail=1; }
python3 - "$tmp/out.json" <<'PY' || fail=1
import json, sys
d = json.load(open(sys.argv[1]))
assert "MIEV0" in d["convention"], d["convention"]
r = d["results"][0]
def near(got, want, half_ulp):
    tol = max(1e-6 * abs(want), half_ulp)
    assert abs(got - want) <= tol, (got, want, tol)
near(r["Qext"], 2.101321, 5e-7)
near(r["Qsca"], 2.096594, 5e-7)
near(r["g"], 0.868959, 5e-7)
assert r["angles_deg"] == [0, 90, 180] and len(r["P"]) == 3
for got, want in ((r["S1"][0], (5253.302, -124.3188)), (r["S2"][2], (56.59205, -46.50974))):
    err = abs(complex(*got) - complex(*want))
    assert err <= 1e-6 * abs(complex(*want)), (got, want)
print("case 10 via the CLI: ok")
PY

"$atmo" mie --dsd stratus --wavelength-nm 550 --wavelength-nm 440 --table "$tmp/t.csv" \
    >"$tmp/out.txt" || { echo "table run failed"; fail=1; }
head -1 "$tmp/t.csv" | grep -q '^theta_deg,P_550nm,P_440nm$' || { echo "bad table header"; fail=1; }
[ "$(tail -1 "$tmp/t.csv" | cut -d, -f1)" = "180.000000" ] || { echo "table must end at 180"; fail=1; }
ls "$tmp" | grep -q tmp && { echo "temporary file left behind"; fail=1; }

# second run: from the cache, same bytes; --no-cache: same bytes again
"$atmo" mie --dsd stratus --wavelength-nm 550 --wavelength-nm 440 --table "$tmp/t2.csv" \
    >"$tmp/out2.txt" || { echo "cached table run failed"; fail=1; }
cmp -s "$tmp/t.csv" "$tmp/t2.csv" || { echo "table from the cache differs"; fail=1; }
cmp -s "$tmp/out.txt" "$tmp/out2.txt" || { echo "bulk output from the cache differs"; fail=1; }
[ "$(ls "$tmp/cache" | grep -c '^mie-table-.*\.bin$')" = 2 ] || { echo "expected 2 cached tables"; fail=1; }
"$atmo" mie --dsd stratus --wavelength-nm 550 --wavelength-nm 440 --table "$tmp/t3.csv" --no-cache \
    >/dev/null && cmp -s "$tmp/t.csv" "$tmp/t3.csv" || { echo "--no-cache table differs"; fail=1; }

# the radius rule: the converged rule stops at an estimate within --tolerance; a fixed step has none
"$atmo" mie --dsd stratus --wavelength-nm 550 --angles-deg 140,180 --tolerance 3e-3 --json \
    >"$tmp/tol.json" || { echo "--tolerance run failed"; fail=1; }
"$atmo" mie --dsd stratus --wavelength-nm 550 --angles-deg 140,180 --radius-step 0.25 --json \
    >"$tmp/step.json" || { echo "--radius-step run failed"; fail=1; }
python3 - "$tmp/tol.json" "$tmp/step.json" <<'PY' || fail=1
import json, sys
t = json.load(open(sys.argv[1]))["results"][0]
s = json.load(open(sys.argv[2]))["results"][0]
assert 0 <= t["error_estimate_rms"] <= 3e-3 and t["error_estimate_max"] <= 1.5e-2, t
assert t["radius_step_dx"] <= 0.0625 and t["n_radii"] > s["n_radii"], (t["radius_step_dx"], s["n_radii"])
assert "error_estimate_rms" not in s and abs(s["radius_step_dx"] - 0.25) < 1e-3, s["radius_step_dx"]
PY

# chart
if command -v gnuplot >/dev/null; then
    "$atmo" mie --dsd stratus --wavelength-nm 550 --wavelength-nm 440 --chart "$tmp/c.svg" >/dev/null \
        || { echo "chart run failed"; fail=1; }
    grep -q '</svg>' "$tmp/c.svg" && grep -q 'glory' "$tmp/c.svg" && grep -q '440 nm' "$tmp/c.svg" \
        || { echo "chart incomplete"; fail=1; }
    ls "$tmp" | grep -q 'tmp\|\.gp' && { echo "chart left a temporary file"; fail=1; }
fi
PATH=/nonexistent "$atmo" mie --dsd stratus --wavelength-nm 550 --chart "$tmp/n.svg" >"$tmp/o" 2>"$tmp/e"
rc=$?
if [ $rc -ne 1 ] || [ "$(wc -l <"$tmp/e")" -ne 1 ] || ! grep -q gnuplot "$tmp/e" || [ -e "$tmp/n.svg" ]; then
    echo "missing gnuplot: exit $rc, stderr:"; cat "$tmp/e"; fail=1
fi

# atmo bench mie --quick: 7 phase options and 2 table builds, finite numbers
"$atmo" bench mie --quick --output "$tmp/bench" >/dev/null 2>"$tmp/bench.err" || { echo "bench mie failed"; cat "$tmp/bench.err"; fail=1; }
python3 - "$tmp/bench" <<'PY' || fail=1
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/mie.csv")))
want = ["hg", "two-term-hg", "cornette-shanks", "draine", "jendersie-deon", "mie-table", "mie-table-1deg"]
assert [r["method"] for r in rows] == want, [r["method"] for r in rows]
for r in rows:
    for c in ("err_0_10", "err_10_90", "err_130_150", "err_170_180", "err_all", "eval_ns", "sample_ns"):
        assert math.isfinite(float(r[c])) and float(r[c]) >= 0, (r["method"], c, r[c])
assert float(rows[5]["err_all"]) < 1e-3 < float(rows[0]["err_all"])  # the table is the reference
t = list(csv.DictReader(open(sys.argv[1] + "/mie_table.csv")))
assert len(t) == 2 and all(float(r["seconds"]) > 0 for r in t), t
PY
if command -v gnuplot >/dev/null; then grep -q '</svg>' "$tmp/bench/mie.svg" || { echo "no bench chart"; fail=1; }; fi

for args in "--dsd nope --wavelength-nm 550" "--radius-um 10" "--radius-um -1 --wavelength-nm 550" \
            "--radius-um 10 --wavelength-nm 550 --index 1.33-0.1i" \
            "--radius-um 10 --wavelength-nm 550 --angles-deg 0,200" \
            "--radius-um 10 --dsd fog --wavelength-nm 550" "--radius-um 10 --wavelength-nm 550 --bogus 1" \
            "--dsd fog --wavelength-nm 550 --tolerance 0" \
            "--dsd fog --wavelength-nm 550 --tolerance 1e-3 --radius-step 0.5"; do
    "$atmo" mie $args >"$tmp/o" 2>"$tmp/e"
    rc=$?
    if [ $rc -ne 2 ] || [ "$(wc -l <"$tmp/e")" -ne 1 ]; then
        echo "atmo mie $args: exit $rc, stderr:"; cat "$tmp/e"; fail=1
    fi
done

# The radius range, stated in radius at the user's wavelength: 2 pi r / lambda in [1e-6, 2e4]
# and r <= 5000 um, so at 550 nm 8.75352e-08 .. 1750.7 um. Outside it (the ends of the series'
# precision: at 1e-300 x^2 underflows, at 1e-100 Q_sca does): exit 2, one line naming the range.
for r in 1e-300 1e-100 8.7e-8 1751 5000 6000; do
    "$atmo" mie --radius-um $r --wavelength-nm 550 >"$tmp/o" 2>"$tmp/e"
    rc=$?
    if [ $rc -ne 2 ] || [ "$(wc -l <"$tmp/e")" -ne 1 ] ||
       ! grep -q "outside 8.75352e-08-1750.7 um.*at 550 nm" "$tmp/e"; then
        echo "atmo mie --radius-um $r: exit $rc, stderr:"; cat "$tmp/e"; fail=1
    fi
done
# Inside it, at both ends: finite numbers. Small end (x = 1.0001e-6) against the Rayleigh limit
# (Bohren & Huffman eq. 5.8-5.9, K = (m^2 - 1)/(m^2 + 2)): Q_abs = 4 x Im K' (K' with m = n - ik
# in the MIEV0 convention: 4 x Im(-K) here), Q_sca = 8/3 x^4 |K|^2, g -> 0; the series' own
# corrections are O(x^2) = 1e-12, so 1e-9 relative bounds the solver and the JSON's 15 digits.
"$atmo" mie --radius-um 8.7544e-8 --wavelength-nm 550 --index 1.33+1e-3i --json >"$tmp/small.json" \
    2>"$tmp/e" || { echo "small end refused:"; cat "$tmp/e"; fail=1; }
"$atmo" mie --radius-um 1750 --wavelength-nm 550 --json >"$tmp/large.json" 2>"$tmp/e" ||
    { echo "large end refused:"; cat "$tmp/e"; fail=1; }
python3 - "$tmp/small.json" "$tmp/large.json" <<'PY' || fail=1
import json, math, sys
r = json.load(open(sys.argv[1]))["results"][0]
x, m = r["x"], complex(1.33, 1e-3)
K = (m * m - 1) / (m * m + 2)
q_abs, q_sca = 4 * x * abs(K.imag), 8 / 3 * x**4 * abs(K) ** 2
for got, want in ((r["Qext"], q_abs + q_sca), (r["Qsca"], q_sca)):
    assert abs(got - want) <= 1e-9 * want, (got, want)
assert math.isfinite(r["g"]) and abs(r["g"]) < 1e-9, r["g"]
big = json.load(open(sys.argv[2]))["results"][0]
for k in ("Qext", "Qsca", "g"):
    assert math.isfinite(big[k]), (k, big[k])
assert abs(big["Qext"] - 2) < 0.01, big["Qext"]  # the extinction paradox: Q_ext -> 2
print("radius range ends: ok")
PY
exit $fail
