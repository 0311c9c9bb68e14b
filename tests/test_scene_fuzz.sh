#!/usr/bin/env bash
# test_scene_fuzz — mutated scene files through the loader: a clear refusal or a valid scene,
# never a crash, never a file left behind.
# labels: cli
#
# Oracle: the CLI contract (DESIGN.md, Errors): input errors are one line on stderr and exit 2
# and write nothing; anything else the loader accepts is a scene, which --save-scene writes and
# which reads back to the same bytes (the save -> load round trip of scene_json.c). 400 mutants
# of the glory preset's saved scene (every section, numbers, names, booleans, vec3s), made with
# a fixed seed so a failure reproduces: byte flips, deletions, duplications of a span, a number
# swapped for a string or a string for a number, odd numerals (0x10, 010, 1e999, -0, NaN), and
# an escaped NUL in a string. Each goes through `atmo render --scene M --save-scene out/s.json`
# (the scene loader and the validation, no render). Both outcomes must occur, so a loader that
# refused everything or accepted everything would fail here too.
set -u
atmo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$atmo" render --preset glory --save-scene base.json 2>/dev/null ||
    { echo "cannot save the base scene" >&2; exit 1; }
python3 - base.json <<'EOF'
import random, re, sys
text = open(sys.argv[1], "rb").read()
rng = random.Random(20261201)
numbers = [m.span() for m in re.finditer(rb"-?\d+(\.\d+)?([eE][+-]?\d+)?", text)]
strings = [m.span() for m in re.finditer(rb'"[a-z-]+"(?!\s*:)', text)]
odd = [b"0x10", b"010", b"1e999", b"-0", b"NaN", b'"8"', b"8.5", b"99999999999999999999", b" 8"]
def mutate(t):
    kind = rng.randrange(6)
    n = len(t)
    if kind == 0:  # flip one bit
        i = rng.randrange(n)
        return t[:i] + bytes([t[i] ^ (1 << rng.randrange(8))]) + t[i + 1:]
    if kind == 1:  # delete a span
        i = rng.randrange(n); j = min(n, i + rng.randint(1, 8))
        return t[:i] + t[j:]
    if kind == 2:  # duplicate a span in place
        i = rng.randrange(n); j = min(n, i + rng.randint(1, 24))
        return t[:j] + t[i:j] + t[j:]
    if kind == 3:  # a number becomes a string
        i, j = rng.choice(numbers)
        return t[:i] + b'"' + t[i:j] + b'"' + t[j:]
    if kind == 4:  # a string becomes a number, or a number an odd numeral
        i, j = rng.choice(strings + numbers)
        return t[:i] + rng.choice(odd + [b"1", b"0"]) + t[j:]
    i, j = rng.choice(strings)  # an escaped NUL inside a name
    return t[:j - 1] + b"\\u0000" + t[j - 1:]
for k in range(400):
    t = text
    for _ in range(rng.randint(1, 3)):
        t = mutate(t)
    open("m%03d.json" % k, "wb").write(t)
EOF

accepted=0
refused=0
failed=0
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
for m in m*.json; do
    rm -rf out && mkdir out
    "$atmo" render --scene "$m" --save-scene out/s.json >stdout.txt 2>stderr.txt </dev/null
    rc=$?
    case $rc in
    0)
        if [ -s stderr.txt ] || [ ! -s out/s.json ]; then
            bad "$m: exit 0 without a clean saved scene"; cat stderr.txt >&2; continue
        fi
        "$atmo" render --scene out/s.json --save-scene out/again.json 2>/dev/null &&
            cmp -s out/s.json out/again.json || { bad "$m: saved scene does not read back"; continue; }
        accepted=$((accepted + 1)) ;;
    2)
        lines=$(wc -l <stderr.txt)
        if [ "$lines" -ne 1 ] || ! grep -q . stderr.txt; then
            bad "$m: exit 2 with $lines stderr lines"; cat stderr.txt >&2; continue
        fi
        if [ -n "$(ls out)" ]; then bad "$m: refused but left $(ls out)"; continue; fi
        refused=$((refused + 1)) ;;
    *)
        bad "$m: exit $rc (a crash or a runtime error on input)"; cat stderr.txt >&2 ;;
    esac
done
echo "test_scene_fuzz: $accepted mutants accepted, $refused refused with one line, $failed failed"
[ $failed -eq 0 ] && [ $accepted -gt 0 ] && [ $refused -gt 0 ]
