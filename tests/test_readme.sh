#!/usr/bin/env bash
# test_readme — the README's first steps work as written, and every relative link of the
# user's documentation (README.md, docs/*.md, docs/guide/, docs/gallery/, docs/bench/) points at
# a file of the checkout.
# labels: cli slow
#
# Oracle: the README itself. The commands are not copied here: they are extracted from the
# indented code blocks that follow a `<!-- readme-test: NAME -->` marker (blocks "setup" and
# "first-render"), with the binary under test standing in for `atmo`, and each is run in a new
# empty directory with its own cache. A command passes when it exits 0 and every file it names
# with --output exists, is not empty and is a PNG. `./setup.sh` lines are not run here: they are
# what CI itself runs (.ci/run is `./setup.sh test`). A marker whose block holds no command
# fails the test, so a README edit cannot empty it silently. Links: every Markdown link target
# that is not a URL or an anchor must exist, relative to the file that holds it (the anchor
# part is dropped); the checker is first shown a file with a broken link.
set -u
atmo=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=${ATMO_SOURCE_DIR:-$(cd "$(dirname "$0")/.." && pwd)}
. "$(dirname "$0")/support_cli.sh"
cli_begin
export ATMO_CACHE_DIR=$work/cache

# block NAME: the commands of the indented block after the marker NAME, one per line, with
# backslash continuations joined and trailing comments removed.
block() {
    awk -v name="$1" '
        index($0, "<!-- readme-test: " name " -->") { on = 1; seen = 0; next }
        on && /^    / { seen = 1; sub(/^    /, ""); print; next }
        on && seen && !/^    / { exit }
    ' "$src/README.md" | sed -e ':a' -e '/\\$/N; s/\\\n */ /; ta' | sed -E 's/[[:space:]]+#.*$//'
}

for name in setup first-render; do
    cmds=$(block "$name")
    if [ -z "$cmds" ]; then
        bad "README has no command block after <!-- readme-test: $name -->"
        continue
    fi
    while IFS= read -r cmd; do
        case $cmd in
        ./setup.sh*) continue ;;
        atmo\ * | atmo) ;;
        *) bad "block $name: not an atmo command: $cmd"; continue ;;
        esac
        dir=$(mktemp -d "$work/run.XXXX")
        args=${cmd#atmo}
        # shellcheck disable=SC2086 # the README's words, split as a shell would
        (cd "$dir" && eval "\"\$atmo\" $args" >out.txt 2>err.txt </dev/null)
        rc=$?
        if [ $rc -ne 0 ]; then
            bad "block $name: '$cmd' exited $rc"
            cat "$dir/err.txt" >&2
            continue
        fi
        outputs=$(echo "$cmd" | grep -oE -- '--output [^ ]+' | cut -d' ' -f2)
        [ -n "$outputs" ] || case $cmd in "atmo render"*) outputs=atmo.png ;; esac
        good=1
        for f in $outputs; do
            if [ ! -s "$dir/$f" ] || ! head -c 8 "$dir/$f" | grep -q PNG; then
                bad "block $name: '$cmd' left no PNG $f"
                good=0
            fi
        done
        [ $good -eq 1 ] && ok
    done <<<"$cmds"
done

# broken_links FILE...: prints "FILE: TARGET" for each relative link whose target is missing.
broken_links() {
    local f t dir
    for f in "$@"; do
        dir=$(dirname "$f")
        grep -oE '\]\([^) ]+\)' "$f" | sed -E 's/^\]\(//; s/\)$//' | while IFS= read -r t; do
            case $t in http://* | https://* | mailto:* | \#*) continue ;; esac
            t=${t%%#*}
            [ -e "$dir/$t" ] || echo "$f: $t"
        done
    done
}

mkdir -p linkcheck
printf '[ok](linkcheck.md) [gone](no-such-file.md) [web](https://example.org)\n' >linkcheck/linkcheck.md
found=$(broken_links linkcheck/linkcheck.md)
[ "$found" = "linkcheck/linkcheck.md: no-such-file.md" ] && ok ||
    bad "the link checker missed a broken link or flagged a good one: '$found'"

docs=("$src/README.md" "$src"/docs/*.md "$src"/docs/guide/*.md "$src"/docs/gallery/*.md
      "$src"/docs/bench/*.md)
broken=$(broken_links "${docs[@]}")
if [ -z "$broken" ]; then ok; else bad "broken links:"; echo "$broken" >&2; fi

cli_end test_readme
