#!/usr/bin/env bash
# test_reliability_cache — the cache directory heals and never stops a render: PoCL's compiled
# programs cut short (bitcode, shared objects) are found, removed and compiled again; `atmo
# cache verify` finds them too and `atmo cache clear` removes PoCL's folder with atmo's files; a
# FIFO in place of a cache entry or of the heightmap does not block; an unusable cache
# directory (here: a regular file) is named with what is wrong, and the render runs without
# the cache, silently with --no-kernel-cache --no-lut-cache.
# labels: reliability cli render slow
#
# Oracle: the first render of the scene into an empty cache. Renders are bitwise deterministic
# on one device, so every render that recovered (or ran without a cache) must give the same
# bytes (cmp). Exit statuses and stderr lines are the contract of docs/reliability.md. PoCL's
# cache is the one atmo keeps under ATMO_CACHE_DIR (POCL_CACHE_DIR unset), and $TMPDIR (the
# private PoCL folder of a run without a usable cache) is inside the test's directory; a
# render that blocks is ended by timeout(1) after 120 s (exit 124).
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
unset POCL_CACHE_DIR
export ATMO_CACHE_DIR=$work/cache TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
r=(render --width 8 --height 8 --samples 2 --quiet --force)

# run NAME ARGS...: atmo ARGS (at most 120 s), exit status in rc, stderr in NAME.err
run() { local name=$1; shift; timeout 120 "$atmo" "$@" 2>"$name.err"; rc=$?; }
# same NAME WHAT: exit 0 and the reference image
same() {
    [ $rc -eq 0 ] && ok || { bad "$2: exit $rc"; cat "$1.err" >&2; }
    cmp -s ref.pfm "$1.pfm" && ok || bad "$2: not the reference image"
}
lines() { wc -l <"$1"; }

run ref "${r[@]}" --output ref.pfm
[ $rc -eq 0 ] || { bad "reference render: exit $rc"; cat ref.err >&2; exit 1; }
bc=$(find cache/pocl -name program.bc | head -1)
[ -n "$bc" ] && ok || { bad "no PoCL program in cache/pocl"; exit 1; }
program=$(dirname "$bc")

# PoCL's bitcode cut to 100 bytes (this aborted every later render with SIGABRT)
truncate -s 100 "$bc"
rm -f cache/kernel-*.bin
run bc_cut "${r[@]}" --output bc_cut.pfm
same bc_cut "program.bc cut to 100 bytes"
[ "$(lines bc_cut.err)" -eq 1 ] && grep -q "PoCL's cached program .*is damaged (program.bc: cut short" bc_cut.err && ok ||
    bad "program.bc cut: want one line naming it, got: $(cat bc_cut.err)"

# every kernel's shared object emptied
find cache/pocl -name '*.so' -exec truncate -s 0 {} \;
run so_empty "${r[@]}" --output so_empty.pfm
same so_empty "shared objects emptied"
grep -q "\.so: not an ELF file" so_empty.err && ok || bad "empty .so: not named: $(cat so_empty.err)"

# a FIFO in place of atmo's kernel binary and of PoCL's bitcode: no render blocks
kernel=$(ls cache/kernel-*.bin | head -1)
rm -f "$kernel" && mkfifo "$kernel"
run fifo_kernel "${r[@]}" --output fifo_kernel.pfm
same fifo_kernel "a FIFO as the cached kernel binary"
bc=$(find cache/pocl -name program.bc | head -1)
rm -f "$bc" && mkfifo "$bc"
run fifo_bc "${r[@]}" --output fifo_bc.pfm
same fifo_bc "a FIFO as PoCL's bitcode"

# verify sees a shared object cut by one byte; clear removes PoCL's folder
run warm "${r[@]}" --output warm.pfm
so=$(find cache/pocl -name '*.so' | head -1)
truncate -s -1 "$so"
"$atmo" cache verify >verify.out 2>verify.err
rc=$?
[ $rc -eq 0 ] && grep -q "is damaged ($(basename "$(dirname "$(dirname "$so")")")/.*\.so: cut short" verify.out &&
    grep -q ": 1 removed" verify.out && [ ! -e "$so" ] && ok ||
    bad "cache verify missed a cut .so (exit $rc): $(cat verify.out verify.err)"
"$atmo" cache verify >verify2.out 2>&1
grep -q ": 0 removed" verify2.out && ok || bad "a second verify removed something: $(cat verify2.out)"
run warm2 "${r[@]}" --output warm2.pfm
"$atmo" cache clear >clear.out 2>&1
rc=$?
[ $rc -eq 0 ] && [ ! -e cache/pocl ] && [ -z "$(ls cache)" ] && ok ||
    bad "cache clear left $(ls cache) (exit $rc): $(cat clear.out)"

# a FIFO as the heightmap: refused at once, exit 2, one line
mkfifo dem.fifo
refused "a FIFO as terrain.heightmap_file" "heightmap 'dem.fifo'.*not a regular file \(a FIFO\)" \
    "${r[@]}" --set terrain.heightmap_file=dem.fifo --set terrain.heightmap_file_extent_m=8000 --output out/a.pfm

# an unusable cache directory: a regular file
echo x >not_a_dir
export ATMO_CACHE_DIR=$work/not_a_dir
run plain "${r[@]}" --output plain.pfm
same plain "cache directory is a file"
[ "$(lines plain.err)" -eq 1 ] && grep -q "cache directory '$work/not_a_dir' is unusable (it is not a directory)" plain.err && ok ||
    bad "unusable cache dir: want one warning naming it, got: $(cat plain.err)"
run told "${r[@]}" --no-kernel-cache --no-lut-cache --output told.pfm
same told "cache directory is a file, --no-kernel-cache --no-lut-cache"
[ "$(lines told.err)" -eq 0 ] && ok || bad "told to run without the cache, yet: $(cat told.err)"
"$atmo" cache verify >v.out 2>v.err
rc=$?
[ $rc -eq 1 ] && grep -q "cache directory '$work/not_a_dir' is unusable: it is not a directory" v.err && ok ||
    bad "cache verify of a file (exit $rc): $(cat v.out v.err)"
[ -z "$(ls "$TMPDIR")" ] && ok || bad "left in TMPDIR: $(ls "$TMPDIR")"
[ "$(cat not_a_dir)" = x ] && ok || bad "the file named as cache directory was changed"

cli_end test_reliability_cache
