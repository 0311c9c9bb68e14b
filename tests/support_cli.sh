# support_cli.sh — shared by the command-line tests (sourced): a scratch directory, the pass/fail
# count and the check of DESIGN.md's refusal contract.
#
# cli_begin: makes a scratch directory, removes it when the test exits, and enters it; sets
# passed=0 and failed=0.
# ok / bad MESSAGE: count a passed check / a failed one (MESSAGE goes to stderr).
# refused DESCRIPTION PATTERN ARGS...: runs "$atmo" ARGS with stdin closed and counts a pass when
# it exits 2 with exactly one line on stderr matching the extended regular expression PATTERN and
# leaves nothing in out/ (emptied first); its stderr stays in stderr.txt.
# cli_end NAME: prints the count and returns 0 when nothing failed.

cli_begin() {
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    cd "$work" || exit 1
    passed=0
    failed=0
}

ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

refused() {
    local what=$1 pattern=$2
    shift 2
    rm -rf out && mkdir out
    "$atmo" "$@" >stdout.txt 2>stderr.txt </dev/null
    local rc=$? lines
    lines=$(wc -l <stderr.txt)
    if [ $rc -ne 2 ]; then bad "$what: exit $rc, want 2"; cat stderr.txt >&2; return; fi
    if [ "$lines" -ne 1 ]; then bad "$what: $lines stderr lines, want 1"; cat stderr.txt >&2; return; fi
    if ! grep -qE -- "$pattern" stderr.txt; then bad "$what: message lacks '$pattern'"; cat stderr.txt >&2; return; fi
    if [ -n "$(ls out)" ]; then bad "$what: left files: $(ls out)"; return; fi
    ok
}

cli_end() {
    echo "$1: $passed passed, $failed failed"
    [ "$failed" -eq 0 ]
}
