#!/usr/bin/env bash
# test_outputs — every file `atmo render` and `atmo mie` will write is checked before any work:
# bad, colliding and oversized outputs exit 2 with one line naming the path and write nothing;
# the same file named twice is one output.
# labels: cli
#
# Oracle: the output contract of `atmo render --help` and host/cli/output_paths.c (directory
# exists and is writable, the name is not a directory and fits NAME_MAX and PATH_MAX with the
# temporary suffix, two options never name one file: realpath of the directory + the name),
# and the device limits CL_DEVICE_MAX_MEM_ALLOC_SIZE / CL_DEVICE_GLOBAL_MEM_SIZE. "Before any
# work" is timed: every render refusal runs with --no-kernel-cache, so reaching the kernel build
# alone (over 1 s for the default scene on PoCL here) would exceed the 1 s that a refusal may
# take; `atmo mie` computes for several seconds per table before it writes. The device case
# (16384 x 16384: two 4 GiB accumulation buffers) is refused on any device with under 8 GiB of
# global memory or a largest allocation under 4 GiB; on a larger device it is skipped.
set -u
atmo=$1
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work"
export ATMO_CACHE_DIR=$work/cache
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
now() { date +%s.%N; }

# refused DESCRIPTION PATTERN ARGS...: exit 2 within 1 s, one stderr line matching PATTERN,
# nothing new in out/
refused() {
    local what=$1 pattern=$2
    shift 2
    local before t0 rc dt
    before=$(ls -A out)
    t0=$(now)
    "$atmo" "$@" >stdout.txt 2>stderr.txt </dev/null
    rc=$?
    dt=$(echo "$(now) - $t0" | bc)
    if [ $rc -ne 2 ]; then bad "$what: exit $rc, want 2"; cat stderr.txt >&2; return; fi
    if [ "$(wc -l <stderr.txt)" -ne 1 ]; then bad "$what: $(wc -l <stderr.txt) stderr lines"; cat stderr.txt >&2; return; fi
    if ! grep -qE -- "$pattern" stderr.txt; then bad "$what: message lacks '$pattern'"; cat stderr.txt >&2; return; fi
    if [ "$(ls -A out)" != "$before" ]; then bad "$what: wrote $(ls -A out)"; return; fi
    if [ "$(echo "$dt < 1" | bc)" != 1 ]; then bad "$what: took $dt s, not before the work"; return; fi
    ok
}

mkdir out out/dir.png
r=(render --preset sky-sunset --width 64 --height 32 --samples 64 --no-kernel-cache)
long_name=$(printf 'n%.0s' $(seq 1 300)).png
long_path=out/$(printf 'd/%.0s' $(seq 1 2100))a.png
refused "output is a directory" "'out/dir.png' is a directory" "${r[@]}" --output out/dir.png
refused "report ends in /" "'out/' is a directory" "${r[@]}" --output out/a.png --report out/
refused "report is a directory" "--report 'out/dir.png' is a directory" "${r[@]}" --output out/a.png --report out/dir.png
refused "missing directory" "directory 'out/none' does not exist" "${r[@]}" --output out/none/a.png
refused "file name too long" "file name is too long.*NAME_MAX" "${r[@]}" --output "out/$long_name"
refused "path too long" "path is too long" "${r[@]}" --output "$long_path"
refused "output = report" "--report 'out/a.png' and --output 'out/a.png' are the same file" "${r[@]}" --output out/a.png --report out/a.png
refused "report = save-scene" "--save-scene 'out/s.json' and --report './out/s.json' are the same file" "${r[@]}" --output out/a.png --report ./out/s.json --save-scene out/s.json
refused "save-scene = output via .." "same file" "${r[@]}" --output out/a.png --save-scene out/dir.png/../a.png
gmem=$("$atmo" devices --json | python3 -c "import json,sys; print(json.load(sys.stdin)['devices'][0]['global_memory_bytes'])")
[ "${ATMO_DEVICE:-}" = "" ] && [ "$gmem" -lt $((8 * 1024 * 1024 * 1024 + 65536)) ] &&
refused "device too small" "CL_DEVICE_(MAX_MEM_ALLOC|GLOBAL_MEM)_SIZE" "${r[@]}" --width 16384 --height 16384 --output out/big.png
refused "mie table = chart" "same file" mie --radius-um 1 --wavelength-nm 550 --table out/t.csv --chart ./out/t.csv
refused "mie table is a directory" "is a directory" mie --radius-um 1 --wavelength-nm 550 --table out/dir.png
if [ "$(id -u)" -ne 0 ]; then # root writes anywhere
    mkdir out/ro && chmod a-w out/ro
    refused "read-only directory" "directory 'out/ro' is not writable" "${r[@]}" --output out/ro/a.png
fi

# the same file twice (as given, and through another spelling) is one output, said once
"$atmo" render --preset sky-sunset --width 16 --height 8 --samples 2 --output out/one.pfm --output ./out/one.pfm \
    --output out/dir.png/../one.pfm --report out/one.json 2>stderr.txt
rc=$?
if [ $rc -eq 0 ] && grep -q "wrote 1 image " stderr.txt; then ok; else bad "same output thrice: exit $rc"; cat stderr.txt >&2; fi
if python3 -c "import json,sys; sys.exit(json.load(open('out/one.json'))['outputs'] != ['out/one.pfm'])"; then ok; else bad "the report lists $(python3 -c "import json; print(json.load(open('out/one.json'))['outputs'])")"; fi
if [ -z "$(find . -name '*.tmp.*')" ]; then ok; else bad "temporary files left"; fi

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
