#!/usr/bin/env bash
# test_cli — the atmo command line: bad input is one line on stderr with exit code 2 and leaves
# no output file; good input writes every requested file completely; --save-scene reproduces an
# image bit for bit; Ctrl-C writes the samples finished so far.
# labels: cli render
#
# Oracle: the CLI contract of DESIGN.md's "Errors" (exit codes 0/1/2, one-line errors, atomic
# outputs) and the readers of other projects: OpenEXR's exrheader for .exr, Python's json for the
# report.
set -u
atmo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# expect_usage DESCRIPTION PATTERN ARGS...: exit 2, exactly one stderr line matching PATTERN,
# and nothing written in the work directory
expect_usage() {
    local what=$1 pattern=$2
    shift 2
    rm -rf out && mkdir out
    "$atmo" "$@" >stdout.txt 2>stderr.txt </dev/null
    local rc=$? lines
    lines=$(wc -l <stderr.txt)
    if [ $rc -ne 2 ]; then bad "$what: exit $rc, want 2"; cat stderr.txt >&2; return; fi
    if [ "$lines" -ne 1 ]; then bad "$what: $lines stderr lines, want 1"; cat stderr.txt >&2; return; fi
    if ! grep -qiE -- "$pattern" stderr.txt; then bad "$what: message lacks '$pattern'"; cat stderr.txt >&2; return; fi
    if [ -n "$(ls out)" ]; then bad "$what: left files: $(ls out)"; return; fi
    ok
}

small=(--width 16 --height 8 --samples 2 --quiet)
expect_usage "unknown command" "unknown command" bogus
expect_usage "misspelt key" "did you mean 'sun.zenith_deg'" render "${small[@]}" --set sun.zenit=5 --output out/a.png
expect_usage "NaN value" "sun.zenith_deg" render "${small[@]}" --set sun.zenith_deg=nan --output out/a.png
expect_usage "out of range" "0 .. 180|range" render "${small[@]}" --set sun.zenith_deg=200 --output out/a.png
expect_usage "wrong type" "camera.kind" render "${small[@]}" --set camera.kind=orthographic --output out/a.png
expect_usage "vec3 syntax" "camera.position_m" render "${small[@]}" --set camera.position_m=1,2 --output out/a.png
expect_usage "set without =" "--set|=" render "${small[@]}" --set sun.zenith_deg --output out/a.png
expect_usage "bad width" "image.width" render --width 0 --output out/a.png
expect_usage "bad samples" "image.samples" render --samples -3 --output out/a.png
expect_usage "unknown format" "format" render "${small[@]}" --output out/a.jpg
expect_usage "unwritable dir" "not writable|directory" render "${small[@]}" --output /nonexistent/dir/a.png
expect_usage "unknown preset" "preset" render "${small[@]}" --preset nope --output out/a.png
expect_usage "missing scene" "missing.json" render "${small[@]}" --scene missing.json --output out/a.png
echo '{"sun": {"zenith_deg": 30,}' >broken.json
expect_usage "broken JSON" "broken.json" render "${small[@]}" --scene broken.json --output out/a.png
echo '{"sun": {"zenith_deg": "high"}}' >wrongtype.json
expect_usage "JSON wrong type" "sun.zenith_deg" render "${small[@]}" --scene wrongtype.json --output out/a.png
echo '{"sun": {"zenith_degs": 3}}' >unknown.json
expect_usage "JSON unknown key" "did you mean" render "${small[@]}" --scene unknown.json --output out/a.png
expect_usage "preset and scene" "preset|scene" render "${small[@]}" --preset sky-noon --scene unknown.json --output out/a.png
expect_usage "unknown option" "unknown option" render --frobnicate
expect_usage "missing value" "needs a value" render --output
expect_usage "bad tile size" "tile-size" render "${small[@]}" --tile-size 3 --output out/a.png
expect_usage "bad budget" "launch-budget" render "${small[@]}" --launch-budget-ms 0 --output out/a.png
expect_usage "bad device" "device" render "${small[@]}" --device 99 --output out/a.png
expect_usage "devices option" "unknown option" devices --frobnicate

# a good render writes every format, completely, and a report
if "$atmo" render "${small[@]}" --camera panorama --output a.pfm --output a.png --output a.exr \
    --output a.hdr --report run.json --save-scene scene.json 2>stderr.txt; then ok; else bad "render failed"; cat stderr.txt >&2; fi
for f in a.pfm a.png a.exr a.hdr run.json scene.json; do
    if [ -s "$f" ]; then ok; else bad "$f missing"; fi
done
if ls | grep -q '\.tmp\.'; then bad "temporary files left: $(ls)"; else ok; fi
if command -v exrheader >/dev/null; then
    if exrheader a.exr >exr.txt 2>&1 && grep -q "dataWindow" exr.txt; then ok; else bad "exrheader cannot read a.exr"; fi
fi
if python3 - run.json <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["render"]["samples_min"] == 2 and not r["render"]["interrupted"]
for k in ("device_init", "kernel_build", "precompute", "render", "write"):
    assert r["seconds"][k] >= 0, k
assert r["device"]["name"]
assert r["scene"]["camera"]["kind"] == "panorama"
PY
then ok; else bad "report content"; fi

# the saved scene reproduces the image bit for bit
if "$atmo" render --quiet --scene scene.json --output b.pfm 2>stderr.txt && cmp -s a.pfm b.pfm; then ok; else bad "--save-scene does not reproduce the image"; cat stderr.txt >&2; fi

# Ctrl-C: the samples so far are written, and the run says so (exit status 3: partial)
"$atmo" render --width 32 --height 16 --samples 1000000 --output int.pfm --report int.json 2>int.txt &
pid=$!
sleep 4
kill -INT $pid
wait $pid
rc=$?
if [ $rc -eq 3 ] && [ -s int.pfm ] && grep -q "interrupted" int.txt && grep -qE '"interrupted":[[:space:]]*true' int.json; then ok; else bad "interrupt: exit $rc"; cat int.txt >&2; fi

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
