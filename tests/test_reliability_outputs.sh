#!/usr/bin/env bash
# test_reliability_outputs — an output never replaces what is not a regular file: a FIFO and
# "-" (standard output) are written through, a symbolic link to a regular file keeps the link
# and replaces the file it leads to, anything else (a socket, a dangling link) is refused with
# exit 2 and one line; an output that is one of the command's inputs (--report = --scene,
# --output = the scene's terrain.heightmap_file, merge --output = a part), by any spelling or
# link, is refused with exit 2 before any work and the input is left untouched.
# labels: reliability cli
#
# Oracle: the output contract of include/atmo/fileio.h (atmo_output_target) and
# host/cli/output_paths.c; POSIX file types as test(1) reports them (-p FIFO, -L link, -f
# regular) and byte equality (cmp) of what the reader of a stream got with the same output
# written to a regular file. Every path is under the test's temporary directory: the "device"
# is a FIFO made here, and $TMPDIR (where stream outputs are staged) points here too.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
export TMPDIR=$work/tmp ATMO_CACHE_DIR=$work/cache
mkdir -p "$TMPDIR"
r=(render --width 8 --height 8 --samples 1 --quiet --force)

# read_fifo FIFO FILE: a reader in the background (pid in reader) that ends after 60 s at most
read_fifo() { timeout 60 cat "$1" >"$2" & reader=$!; }
# end_reader RC FIFO: wait for the reader when atmo succeeded and FIFO is still one; else stop
# it (nothing will ever write that FIFO: atmo failed, or replaced it with a regular file)
end_reader() {
    [ "$1" -eq 0 ] && [ -p "$2" ] || kill "$reader" 2>/dev/null
    wait "$reader" 2>/dev/null
}

# --save-scene into a FIFO: the reader gets the scene, the FIFO stays a FIFO
"$atmo" "${r[@]}" --save-scene plain.json || bad "save-scene to a regular file"
mkfifo scene.fifo
read_fifo scene.fifo got_scene.json
"$atmo" "${r[@]}" --save-scene scene.fifo 2>err.txt
rc=$?
[ -p scene.fifo ] && ok || bad "--save-scene replaced the FIFO (exit $rc): $(cat err.txt)"
end_reader $rc scene.fifo
cmp -s plain.json got_scene.json && ok || bad "the FIFO's reader got other bytes than the file"

# --save-scene - : the scene on standard output, nothing else there
"$atmo" "${r[@]}" --save-scene - >stdout.json 2>err.txt
rc=$?
[ $rc -eq 0 ] && cmp -s plain.json stdout.json && ok || bad "--save-scene - (exit $rc): $(cat err.txt)"
[ ! -e ./- ] && ok || bad "--save-scene - wrote a file named '-'"

# --report into a FIFO and through a link to a FIFO, with a render
mkfifo report.fifo
ln -s report.fifo report_link.json
for name in report.fifo report_link.json; do
    read_fifo report.fifo got_report.json
    "$atmo" "${r[@]}" --output img.pfm --report $name 2>err.txt
    rc=$?
    [ $rc -eq 0 ] && [ -p report.fifo ] && ok || bad "--report $name (exit $rc): $(cat err.txt)"
    end_reader $rc report.fifo
    python3 -c "import json; json.load(open('got_report.json'))" 2>/dev/null && ok ||
        bad "--report $name: the reader got no JSON report"
done
[ -L report_link.json ] && ok || bad "the link to the FIFO was replaced"

# --output into a FIFO: the image bytes equal those written to a regular file
mkfifo img.fifo
ln -s img.fifo img_link.pfm
read_fifo img.fifo got.pfm
"$atmo" "${r[@]}" --output img_link.pfm 2>err.txt
rc=$?
[ $rc -eq 0 ] && [ -p img.fifo ] && [ -L img_link.pfm ] && ok || bad "--output through a link to a FIFO (exit $rc): $(cat err.txt)"
end_reader $rc img.fifo
cmp -s img.pfm got.pfm && ok || bad "the image read from the FIFO differs from the file"

# a link (through two links) to a regular file: the link stays, the file it leads to is replaced
echo old >real.json
ln -s real.json link1.json
ln -s link1.json link2.json
"$atmo" "${r[@]}" --save-scene link2.json 2>err.txt || bad "save-scene through links: $(cat err.txt)"
[ -L link2.json ] && [ -L link1.json ] && [ -f real.json ] && cmp -s plain.json real.json && ok ||
    bad "a link to a regular file was replaced instead of its target"
[ -z "$(find . -name '*.tmp.*')" ] && ok || bad "temporary files left: $(find . -name '*.tmp.*')"

# refused: a dangling link, a socket, a link to a socket
ln -s nowhere.json dangling.json
refused "dangling link" "'dangling.json' is a symbolic link that leads nowhere" "${r[@]}" --save-scene dangling.json
[ -L dangling.json ] && ok || bad "the dangling link was replaced"
python3 -c "import socket; socket.socket(socket.AF_UNIX).bind('sock.json')"
ln -s sock.json sock_link.json
refused "socket" "'sock.json' is a socket, not a regular file" "${r[@]}" --save-scene sock.json
refused "link to a socket" "'sock_link.json' is a socket" "${r[@]}" --output out/a.pfm --report sock_link.json
[ -S sock.json ] && [ -L sock_link.json ] && ok || bad "the socket or its link was replaced"
# two names of one FIFO are one file
refused "two options, one FIFO" "same file" "${r[@]}" --output img.pfm --report report.fifo --save-scene report_link.json

# outputs that are inputs: refused before any work, the input untouched
cp plain.json s.json
ln s.json hard.json
cp s.json s_before.json
refused "--report = --scene" "--report 's.json' is the input --scene 's.json'" render --force --scene s.json --output out/a.pfm --report s.json
refused "--save-scene = --scene (hard link)" "is the input --scene" render --force --scene s.json --save-scene hard.json
ln -s s.json s.pfm
refused "--output = --scene (a link)" "is the input --scene" render --force --scene s.json --output ./out/../s.pfm
cmp -s s.json s_before.json && ok || bad "the scene file was changed"
python3 - <<'PY'
import struct, zlib
def chunk(t, d):
    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
rows = b''.join(b'\0' + b''.join(struct.pack('>H', 1000 + 10 * (x + y)) for x in range(8)) for y in range(8))
open('dem.png', 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 8, 8, 16, 0, 0, 0, 0))
    + chunk(b'IDAT', zlib.compress(rows)) + chunk(b'IEND', b''))
PY
cp dem.png dem_before.png
ln -s dem.png dem_link.png
refused "--output = heightmap_file" "--output 'dem.png' is the input terrain.heightmap_file 'dem_link.png'" \
    "${r[@]}" --set terrain.heightmap_file=dem_link.png --set terrain.heightmap_file_extent_m=8000 --output dem.png
cmp -s dem.png dem_before.png && ok || bad "the DEM was changed"

cli_end test_reliability_outputs
