#!/bin/bash
# test_cache_cli.sh — damaged cache files through `atmo render`, and `atmo cache`.
# labels: cli render
#
# Oracles: the first render of a scene into an empty cache (renders are bitwise deterministic on
# one device, so a render that recovered from a damaged cache file must give the same bytes),
# and the cache-file format (`atmo cache verify` re-checks every file).
#  - A kernel binary cut by its last byte (this once aborted PoCL with SIGABRT on every later
#    run), the last 4 KiB of a Mie table overwritten: the next render exits 0 with exactly one
#    warning line naming the file, writes the same image as the fresh render, and leaves files
#    that verify. (Whether a render stores a LUT depends on how long it took, > 20 ms, so damaged
#    LUT files are tested at the precompute level, in test_cache_files and test_lut_cache.)
#  - --no-lut-cache writes no Mie table; without it the glory scene's three Mie
#    tables are cached, and the image is the same.
#  - `atmo cache verify` deletes a zeroed file and a temporary file of a dead writer (2 removed)
#    and nothing else; `atmo cache clear` deletes every atmo file and no other file; `list` shows
#    one line per file and the total. A bad action is exit 2 with one line.
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
cache="$tmp/cache"
export ATMO_CACHE_DIR="$cache"
tiny=(--width 16 --height 8 --samples 1 -q)

check() { # message, then a command that must succeed
    local msg=$1
    shift
    if "$@"; then echo "ok: $msg"; else echo "FAILED: $msg"; fail=1; fi
}

# one warning line naming the file, in the stderr file
one_warning() { [ "$(grep -c "cache file .*$(basename "$2")" "$1")" = 1 ]; }

render() { # name, render options...
    local name=$1
    shift
    "$atmo" render "$@" "${tiny[@]}" --output "$tmp/$name.pfm" 2>"$tmp/$name.err"
    local rc=$?
    [ $rc = 0 ] || { echo "render $name exited $rc:"; cat "$tmp/$name.err"; fail=1; }
}

render fresh --preset sky-noon
kernel=$(ls "$cache"/kernel-*.bin)
check "a fresh render caches a kernel" test -f "$kernel"

truncate -s -1 "$kernel"
render cut --preset sky-noon
check "kernel binary cut by one byte: one warning" one_warning "$tmp/cut.err" "$kernel"
check "kernel binary cut by one byte: the same image" cmp -s "$tmp/fresh.pfm" "$tmp/cut.pfm"

"$atmo" cache verify >"$tmp/verify0.out"
check "the repaired files verify" grep -q ": 0 removed" "$tmp/verify0.out"

render glory_nocache --preset glory --no-lut-cache
check "--no-lut-cache writes no Mie table" test -z "$(ls "$cache" | grep mie-table)"
render glory --preset glory
check "the glory scene caches its three Mie tables" test "$(ls "$cache" | grep -c mie-table)" = 3
check "Mie tables from the cache or not: the same image" \
    cmp -s "$tmp/glory_nocache.pfm" "$tmp/glory.pfm"
mie=$(ls "$cache"/mie-table-*.bin | head -1)
python3 -c "
import random, sys
random.seed(9)
f = open(sys.argv[1], 'r+b'); f.seek(-4096, 2); f.write(bytes(random.randrange(256) for _ in range(4096)))" "$mie"
render glory_bad --preset glory
check "a Mie table with its last 4 KiB randomised: one warning" \
    one_warning "$tmp/glory_bad.err" "$mie"
check "a Mie table with its last 4 KiB randomised: the same image" \
    cmp -s "$tmp/glory_nocache.pfm" "$tmp/glory_bad.pfm"
check "the repaired Mie table verifies" grep -q ": 0 removed" <("$atmo" cache verify)

# verify: a zeroed product and a dead writer's temporary file go, nothing else
head -c "$(stat -c %s "$mie")" /dev/zero >"$mie"
bash -c 'exit 0' &
dead=$!
wait $dead
echo partial >"$kernel.tmp.$dead"
echo mine >"$cache/notes.txt"
echo mine >"$cache/kernel-notes.txt"
before=$(ls "$cache" | wc -l)
"$atmo" cache verify >"$tmp/verify.out"
check "verify exits 0" test $? = 0
cat "$tmp/verify.out"
check "verify removes the zeroed file and the stale temporary file" \
    grep -q ": 2 removed" "$tmp/verify.out"
check "verify deleted exactly those" test ! -e "$mie" -a ! -e "$kernel.tmp.$dead" \
    -a "$(ls "$cache" | wc -l)" = $((before - 2))
"$atmo" cache verify >"$tmp/verify2.out"
check "a second verify removes nothing" grep -q ": 0 removed" "$tmp/verify2.out"

"$atmo" cache list >"$tmp/list.out"
check "list exits 0" test $? = 0
products=$(ls "$cache" | grep -c '\.bin$')
check "list: one line per file and the total" test "$(wc -l <"$tmp/list.out")" = $((products + 1))
check "list: the total counts them" grep -q "^$products files, " "$tmp/list.out"
check "list names the kinds" grep -q "^kernel " "$tmp/list.out"
check "list names the kinds" grep -q "^mie-table " "$tmp/list.out"

"$atmo" cache clear >"$tmp/clear.out"
check "clear exits 0" test $? = 0
check "clear says how many" grep -q "^removed $products files" "$tmp/clear.out"
check "clear leaves only the other files" \
    test "$(ls "$cache" | sort | tr '\n' ' ')" = "kernel-notes.txt notes.txt "
check "list after clear: 0 files" grep -q "^0 files" <("$atmo" cache list)

"$atmo" cache shrink 2>"$tmp/bad.err" >/dev/null
rc=$?
check "a bad action: exit 2 with one line" test $rc = 2 -a "$(wc -l <"$tmp/bad.err")" = 1
check "atmo --help lists cache" grep -q "^  cache " <("$atmo" --help)
exit $fail
