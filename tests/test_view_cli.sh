#!/usr/bin/env bash
# test_view_cli — `atmo view`'s command line: --help lists the keys, and bad input is refused
# with one line and exit status 2 before any window or device is opened; an atmo built without
# GLFW says how to get the viewer, in one line, with exit status 2.
# labels: cli
#
# Oracle: the contract of `atmo view --help` and DESIGN.md's error rule (one line: what, where,
# how to fix; exit 2; before any long work). "Before any work" is checked by running each
# refusal with DISPLAY unset: opening the window would fail with another message (exit 1).
set -u
atmo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

help=$("$atmo" view --help)
if echo "$help" | grep -q "built without GLFW"; then
    "$atmo" view --preset sky-noon >out.txt 2>err.txt
    rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l <err.txt)" -eq 1 ] && grep -q "libglfw3-dev" err.txt; then
        ok
    else
        bad "without GLFW: exit $rc, stderr: $(cat err.txt)"
    fi
    echo "test_view_cli: $passed passed, $failed failed (viewer not built)"
    [ "$failed" -eq 0 ]
    exit
fi

for key in "W A S D" "Q E" "arrow Up/Down" "1 ... 9" "Tab" "= -" "T " "H or F1" "P " "Esc"; do
    if echo "$help" | grep -qF -- "$key"; then ok; else bad "--help does not list '$key'"; fi
done
if "$atmo" --help | grep -q "^  view "; then ok; else bad "atmo --help does not list view"; fi

# refused DESCRIPTION PATTERN ARGS...: exit 2, one stderr line matching PATTERN, nothing written
refused() {
    local what=$1 pattern=$2
    shift 2
    env -u DISPLAY -u WAYLAND_DISPLAY "$atmo" view "$@" >stdout.txt 2>stderr.txt </dev/null
    local rc=$?
    if [ $rc -ne 2 ]; then bad "$what: exit $rc, want 2: $(cat stderr.txt)"; return; fi
    if [ "$(wc -l <stderr.txt)" -ne 1 ]; then bad "$what: $(wc -l <stderr.txt) stderr lines"; cat stderr.txt >&2; return; fi
    if ! grep -qE -- "$pattern" stderr.txt; then bad "$what: message lacks '$pattern': $(cat stderr.txt)"; return; fi
    if [ -n "$(ls -A | grep -vE '^(stdout|stderr)\.txt$|\.script$')" ]; then bad "$what: wrote $(ls -A)"; return; fi
    ok
}

printf 'wait-samples 2\npress W\njump 3\n' >bad.script
printf 'hold X 1\n' >badhold.script
refused "unknown option" "unknown option '--frobnicate'" --frobnicate
refused "missing value" "--script needs a value" --script
refused "screenshot without output" "--screenshot-after N and --output FILE go together" --screenshot-after 4
refused "output without screenshot" "go together" --output a.png
refused "bad sample count" "--screenshot-after: 0 is out of range \(use a whole number in \[1, 1000000\]" --screenshot-after 0 --output a.png
refused "unknown output format" "unknown image format" --screenshot-after 1 --output a.tif
refused "capture not png" "--window-capture 'a.pfm' must be a .png" --screenshot-after 1 --output a.png --window-capture a.pfm
refused "save without extension" "--save 'shots': unknown image format" --save shots
refused "missing directory" "directory 'nodir' does not exist" --screenshot-after 1 --output nodir/a.png
refused "bad window size" "--window needs WIDTHxHEIGHT" --window 640
refused "bad width" "--width: 'abc' is not an integer \(image.width: use a whole number in" --width abc
refused "width out of range" "--height: 0 is out of range" --height 0
refused "misspelt flag" "unknown option '--widht' \(did you mean '--width'\?" --widht 64
refused "misspelt camera" "did you mean 'panorama'" --camera panoramma
refused "bad key" "unknown key 'sun.zenith'|sun.zenith" --set sun.zenith=3
refused "spectral mode" "render.spectral_bands" --set render.spectral_bands=15
refused "preset and scene" "exclude each other" --preset sky-noon --scene x.json
refused "bad script line" "bad.script:3: not an action" --script bad.script
refused "bad hold key" "badhold.script:1: not an action" --script badhold.script
refused "missing script" "--script 'none.script': cannot open it" --script none.script

echo "test_view_cli: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
