#!/usr/bin/env bash
# test_help_defaults — every command's --help states the default of every flag that takes a
# value, and the defaults it states are the ones the code uses.
# labels: cli
#
# Oracles: the code's own behaviour, observed through other doors:
# - the scene keys a flag stands for (--width is image.width, ...): the help's "V in PRESET" is
#   the value of that key in the scene `atmo render --save-scene -` resolves without flags;
# - --preset's default: the scene without --preset equals the scene of --preset DEFAULT;
# - --tile-size and --launch-budget-ms: the run report's render.tile_size and
#   render.launch_budget_ms of a render without them;
# - --output's default: a render without --output writes that file.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
export ATMO_CACHE_DIR=$work/cache TMPDIR=$work/tmp
mkdir -p "$TMPDIR"

# help_blocks CMD...: the help of atmo CMD as "FLAG<TAB>its text on one line", one per flag
help_blocks() {
    "$atmo" "$@" --help | python3 -c '
import re, sys
blocks, cur = {}, None
for line in sys.stdin:
    m = re.match(r"  (--[a-z-]+)", line)
    if m:
        cur = m.group(1)
        blocks[cur] = line.strip()
    elif cur and line.startswith("    "):
        blocks[cur] += " " + line.strip()
    else:
        cur = None
for flag, text in blocks.items():
    print(flag + "\t" + text)'
}

# every flag with a value states its default, in every command that has flags
for cmd in render view radiance mie bench merge "cache verify" "dem info" terrain; do
    help_blocks $cmd >blocks.txt
    lacking=$(python3 -c '
import re, sys
for line in open("blocks.txt"):
    flag, text = line.rstrip("\n").split("\t", 1)
    if re.match(r"--[a-z-]+(, -[a-z])? [^ (]", text) and "(default" not in text:
        print(flag)' | tr '\n' ' ')
    [ -z "$lacking" ] && ok || bad "atmo $cmd --help states no default for: $lacking"
done

# the scene-key flags' stated defaults are the default scene's values
help_blocks render >render.txt
"$atmo" render --save-scene - >default.json 2>err.txt || bad "render --save-scene -: $(cat err.txt)"
preset=$(grep -oE '^--preset.*\(default [a-z0-9-]+\)' render.txt | sed -E 's/.*\(default ([a-z0-9-]+)\)/\1/')
[ -n "$preset" ] && ok || bad "--preset states no default"
if python3 - render.txt default.json "$preset" <<'PY'
import json, re, sys
scene = json.load(open(sys.argv[2]))
preset = sys.argv[3]
checked = 0
for line in open(sys.argv[1]):
    flag, text = line.rstrip("\n").split("\t", 1)
    m = re.search(r"\(([a-z_]+\.[a-z_]+)\) \(default: the scene's; (\S+) in " + re.escape(preset), text)
    if not m:
        continue
    group, key = m.group(1).split(".")
    want = scene[group][key]
    got = m.group(2)
    same = str(want) == got or (isinstance(want, (int, float)) and not isinstance(want, bool)
                                and float(got) == float(want))
    assert same, (flag, m.group(1), got, want)
    checked += 1
assert checked >= 7, checked
PY
then ok; else bad "a scene flag's stated default differs from the scene's"; fi
"$atmo" render --preset "$preset" --save-scene - >named.json 2>err.txt
cmp -s default.json named.json && ok || bad "the scene without --preset is not --preset $preset's"

# --tile-size, --launch-budget-ms and --output: what a render without them uses
tile=$(grep -oE '^--tile-size.*\(default [0-9]+\)' render.txt | sed -E 's/.*\(default ([0-9]+)\)/\1/')
budget=$(grep -oE '^--launch-budget-ms.*\(default [0-9.]+\)' render.txt | sed -E 's/.*\(default ([0-9.]+)\)/\1/')
output=$(grep -oE '^--output.*\(default [a-z.]+\)' render.txt | sed -E 's/.*\(default ([a-z.]+)\)/\1/')
"$atmo" render --preset sky-sunset --width 8 --height 8 --samples 1 --quiet --report report.json 2>err.txt ||
    bad "a render without --output: $(cat err.txt)"
[ -n "$output" ] && [ -s "$output" ] && ok || bad "--output's stated default '$output' was not written"
python3 -c "
import json, sys
r = json.load(open('report.json'))['render']
sys.exit(not (r['tile_size'] == float('$tile') and r['launch_budget_ms'] == float('$budget')))" &&
    ok || bad "--tile-size $tile / --launch-budget-ms $budget differ from the report's: $(cat report.json)"

cli_end test_help_defaults
