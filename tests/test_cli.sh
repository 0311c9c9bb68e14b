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
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin

small=(--width 16 --height 8 --samples 2 --quiet)
sunset=(--preset sky-sunset "${small[@]}") # the scene these checks were written for
refused "unknown command" "unknown command" bogus
refused "misspelt key" "did you mean 'sun.zenith_deg'" render "${sunset[@]}" --set sun.zenit=5 --output out/a.png
refused "NaN value" "sun.zenith_deg" render "${sunset[@]}" --set sun.zenith_deg=nan --output out/a.png
refused "out of range" "0 .. 180|range" render "${sunset[@]}" --set sun.zenith_deg=200 --output out/a.png
refused "wrong type" "camera.kind" render "${sunset[@]}" --set camera.kind=orthographic --output out/a.png
refused "vec3 syntax" "camera.position_m" render "${sunset[@]}" --set camera.position_m=1,2 --output out/a.png
refused "set without =" "--set|=" render "${sunset[@]}" --set sun.zenith_deg --output out/a.png
refused "bad width" "image.width" render --width 0 --output out/a.png
refused "bad samples" "image.samples" render --samples -3 --output out/a.png
refused "unknown format" "format" render "${sunset[@]}" --output out/a.jpg
refused "unwritable dir" "not writable|directory" render "${sunset[@]}" --output /nonexistent/dir/a.png
refused "unknown preset" "preset" render "${small[@]}" --preset nope --output out/a.png
refused "missing scene" "missing.json" render "${small[@]}" --scene missing.json --output out/a.png
echo '{"sun": {"zenith_deg": 30,}' >broken.json
refused "broken JSON" "broken.json" render "${small[@]}" --scene broken.json --output out/a.png
echo '{"sun": {"zenith_deg": "high"}}' >wrongtype.json
refused "JSON wrong type" "sun.zenith_deg" render "${small[@]}" --scene wrongtype.json --output out/a.png
echo '{"sun": {"zenith_degs": 3}}' >unknown.json
refused "JSON unknown key" "did you mean" render "${small[@]}" --scene unknown.json --output out/a.png
refused "preset and scene" "preset|scene" render "${small[@]}" --preset sky-noon --scene unknown.json --output out/a.png
refused "unknown option" "unknown option" render --frobnicate
refused "missing value" "needs a value" render --output
refused "bad tile size" "tile-size" render "${sunset[@]}" --tile-size 3 --output out/a.png
refused "bad budget" "launch-budget" render "${sunset[@]}" --launch-budget-ms 0 --output out/a.png
refused "bad device" "device" render "${sunset[@]}" --device 99 --output out/a.png
refused "devices option" "unknown option" devices --frobnicate

# did you mean: a near miss of a command, flag, preset, choice, method or key gets the nearest
# name; a far one gets none (no guess is better than a wrong one)
refused "misspelt command" "unknown command 'rendr' \(did you mean 'render'\?\)" rendr
refused "misspelt flag" "unknown option '--widht' \(did you mean '--width'\? atmo render --help\)" render --widht 8
refused "misspelt flag with =" "unknown option '--outptu' \(did you mean '--output'\?" render --outptu=out/a.png
refused "misspelt preset" "unknown preset 'thesis1' \(did you mean 'thesis-1'\? atmo presets lists them\)" render "${small[@]}" --preset thesis1 --output out/a.png
refused "misspelt presets NAME" "did you mean 'sky-noon'" presets sky-nono
refused "misspelt choice" "--camera: 'panoramma' is not one of .*did you mean 'panorama'" render "${sunset[@]}" --camera panoramma --output out/a.png
refused "misspelt method" "did you mean 'reference'\? use one of" render "${sunset[@]}" --set atmosphere.method=refrence --output out/a.png
refused "swapped letters in a choice" "did you mean 'piz'" render "${sunset[@]}" --exr-compression pzi --output out/a.exr
refused "misspelt bench suite" "unknown suite 'mei' \(did you mean 'mie'\?" bench mei
refused "unknown bench view" "--views: unknown view 'thesis-10'" bench views --views thesis-10 --output out/bench
refused "misspelt cache action" "did you mean 'verify'\?" cache verfy
refused "far preset: no guess" "^atmo render: unknown preset 'xyzzy'; use one of" render "${small[@]}" --preset xyzzy --output out/a.png
refused "far flag: no guess" "^atmo render: unknown option '--frobnicate' \(atmo render --help\)$" render --frobnicate
refused "far key: no guess" "unknown parameter 'qqq.zzz' \(from --set\); atmo params" render "${sunset[@]}" --set qqq.zzz=1 --output out/a.png
refused "not an integer" "--width: 'abc' is not an integer \(image.width: use a whole number in \[1, [0-9]+\], e.g. --width [0-9]+\)" render --width abc --output out/a.png
refused "bool with a value" "--quiet takes no value" render --quiet=yes --output out/a.png

# --help states every default: the help of every flag that takes a value, but the repeatable
# ones, has "(default ...)"
"$atmo" render --help >help.txt
if python3 - help.txt <<'PY'
import re, sys
blocks, cur = {}, None
for line in open(sys.argv[1]):
    m = re.match(r"  (--[a-z-]+)", line)
    if m:
        cur = m.group(1)
        blocks[cur] = line
    elif cur and line.startswith("    "):
        blocks[cur] += line
    else:
        cur = None
valued = [f for f, b in blocks.items() if re.match(r"  --[a-z-]+(, -[a-z])? \S", b)]
lacking = [f for f in valued if "(default" not in blocks[f] and f not in ("--set", "--animate", "--scene")]
assert len(valued) >= 20 and not lacking, (len(valued), lacking)
assert "(default: the scene's; 2 in planet)" in blocks["--samples"], blocks["--samples"]
PY
then ok; else bad "--help does not state every default"; fi

# outputs are not overwritten without --force: one line naming the file and --force, the file
# untouched; with --force it is replaced
echo "an earlier image" >keep.png
cp keep.png keep.orig
refused "existing output" "--output 'keep.png' exists; add --force to overwrite it" render "${sunset[@]}" --output keep.png
if cmp -s keep.png keep.orig; then ok; else bad "a refused render changed keep.png"; fi
echo "{}" >keep.json
refused "existing report" "--report 'keep.json' exists; add --force" render "${sunset[@]}" --output out/a.png --report keep.json
echo "theta_deg" >keep.csv
refused "existing mie table" "--table 'keep.csv' exists; add --force" mie --radius-um 1 --wavelength-nm 550 --table keep.csv
if "$atmo" render "${sunset[@]}" --force --output keep.png 2>stderr.txt && ! cmp -s keep.png keep.orig; then ok; else bad "--force did not replace keep.png"; cat stderr.txt >&2; fi

# plurals: one sample per pixel is "1 sample/pixel", one image "1 image"; the cost line before
# the render states the size, the samples (16 x 8 x 1 = 128) and the method
if "$atmo" render --preset sky-sunset --width 16 --height 8 --samples 1 --set atmosphere.method=single \
    --output one.pfm 2>one.txt && grep -q "wrote 1 image (16x8, 1 sample/pixel" one.txt &&
    grep -q "^atmo render: 16x8 at 1 sample/pixel (0.000128 M samples), method single; 1 frame$" one.txt
then ok; else bad "plural or cost line: $(cat one.txt)"; fi

# a good render writes every format, completely, and a report
if "$atmo" render "${sunset[@]}" --camera panorama --output a.pfm --output a.png --output a.exr \
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
"$atmo" render --preset sky-sunset --width 32 --height 16 --samples 1000000 --output int.pfm --report int.json 2>int.txt &
pid=$!
sleep 4
kill -INT $pid
wait $pid
rc=$?
if [ $rc -eq 3 ] && [ -s int.pfm ] && grep -q "interrupted" int.txt && grep -qE '"interrupted":[[:space:]]*true' int.json; then ok; else bad "interrupt: exit $rc"; cat int.txt >&2; fi

cli_end test_cli
