#!/usr/bin/env bash
# test_reliability_signals — SIGHUP (the terminal closed) stops `atmo render` like SIGINT and
# SIGTERM: in the render the samples so far are written, marked partial, with exit status 3
# and a report that says so; in the write it lets the files be finished (exit 0), leaving no
# temporary file; `atmo render --help` documents the exit status of a second signal (130 for
# SIGINT).
# labels: reliability cli render
#
# Oracle: the interrupt contract of `atmo render --help` (host/cli/cmd_render.c), the same one
# test_interrupt checks for SIGINT and SIGTERM: exit 3, the image's "partial render" metadata,
# the report's "interrupted": true with 0 < samples_min < samples_requested, and no "*.tmp.*"
# file anywhere in the test's directory. The render asks for a million samples of a 32 x 16
# image, so the signal sent 4 s after the start always lands in the render.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
export ATMO_CACHE_DIR=$work/cache TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
single=(--preset sky-sunset --set atmosphere.method=single --width 32 --height 16)
no_tmp() { [ -z "$(find . -name '*.tmp.*')" ] && ok || bad "$1: temporary files left: $(find . -name '*.tmp.*')"; }

"$atmo" render "${single[@]}" --samples 1 --output warm.png --quiet || bad "warm-up run"
"$atmo" render "${single[@]}" --samples 1000000 --output hup.hdr --report hup.json --quiet 2>hup.txt &
pid=$!
sleep 4
kill -HUP $pid
wait $pid
rc=$?
[ $rc -eq 3 ] && ok || { bad "SIGHUP in the render: exit $rc, want 3"; cat hup.txt >&2; }
[ -s hup.hdr ] && grep -aq "partial render" hup.hdr && ok || bad "SIGHUP: no image marked partial"
python3 -c "import json,sys; r=json.load(open('hup.json'))['render']; sys.exit(not (r['interrupted'] and 0 < r['samples_min'] < r['samples_requested']))" &&
    ok || bad "SIGHUP: the report does not say interrupted with some samples"
no_tmp "SIGHUP in the render"

# SIGHUP while the files are written (eight PNGs of 1024 x 512, over 2 s of encoding here, the
# signal sent once the last progress line is on stderr): the writing finishes, exit 0, every
# file whole, no temporary file
mkdir wr
outs=()
for i in 1 2 3 4 5 6 7 8; do outs+=(--output "wr/w$i.png"); done
"$atmo" render --preset sky-sunset --set atmosphere.method=single --width 1024 --height 512 --samples 1 "${outs[@]}" 2>wr.txt &
pid=$!
until grep -q "100.0% done" wr.txt || ! kill -0 $pid 2>/dev/null; do sleep 0.01; done
kill -HUP $pid 2>/dev/null
wait $pid
rc=$?
[ $rc -eq 0 ] && [ "$(ls wr | grep -c '^w[0-9].png$')" -eq 8 ] && ok ||
    { bad "SIGHUP in the write: exit $rc, files: $(ls wr)"; cat wr.txt >&2; }
no_tmp "SIGHUP in the write"

"$atmo" render --help | grep -q "130 for SIGINT" && ok || bad "--help does not document the exit status of a second signal"

cli_end test_reliability_signals
