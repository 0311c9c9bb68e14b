#!/bin/bash
# test_presets_default.sh — every preset renders with its own defaults (atmosphere.method = auto
# where the preset names no method), and auto's choice is printed and reported.
# labels: cli render slow
#
# Oracle: the plan's rule for atmosphere.method = auto (atmo_plan_auto_method, include/atmo/plan.h):
# march for a scene with the fBm cloud layer, the cloud shell or the observer, fast otherwise.
# Each preset of `atmo presets` renders at smoke size (16 x 9, 1 sample) with nothing but its
# defaults: exit status 0 and a complete PFM without NaN or Inf. The run report's
# render.method is the preset's own method, or auto's choice by the rule, and
# render.method_auto is present exactly when auto chose; without --quiet one line on stderr
# says "method M (auto: ...)", with --quiet nothing does. A clear sky with clouds switched on
# (sky-noon, clouds.enabled=true: refused by fast) renders with auto's march.
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
cd "$tmp" || exit 1

check() { # name, then render arguments
    local name=$1
    shift
    if ! "$atmo" render "$@" --width 16 --height 9 --samples 1 --output "$name.pfm" \
        --report "$name.json" 2>"$name.err"; then
        echo "$name: render failed:"
        cat "$name.err"
        fail=1
        return
    fi
    python3 - "$name" "$@" <<'PY' || fail=1
import json, math, struct, sys
name, args = sys.argv[1], sys.argv[2:]
r = json.load(open(name + ".json"))
s = r["scene"]
asked = s["atmosphere"]["method"]
clouds = s["clouds"]["enabled"] and not (s["render"]["mode"] == "path" and s["path"]["clouds"] == "volume")
want = asked if asked != "auto" else ("march" if clouds or s["cloud"]["enabled"] or s["observer"]["enabled"] else "fast")
got = r["render"]["method"]
assert got == want, (name, asked, got, want)
assert ("method_auto" in r["render"]) == (asked == "auto"), (name, r["render"])
err = open(name + ".err").read()
line = [l for l in err.splitlines() if "(auto: " in l]
if "--quiet" in args or asked != "auto":
    assert not line, (name, err)
else:
    assert len(line) == 1 and ("method %s (auto: " % got) in line[0], (name, err)
data = open(name + ".pfm", "rb").read()
head = data.split(b"\n", 3)
w, h = map(int, head[1].split())
order = "<" if float(head[2]) < 0 else ">"
pix = struct.unpack("%s%df" % (order, 3 * w * h), head[3][: 12 * w * h])
assert (w, h) == (16, 9) and all(math.isfinite(x) for x in pix), name
print("%-14s method %-9s (asked %s)%s" % (name, got, asked, " " + line[0] if line else ""))
PY
}

presets=$("$atmo" presets | awk '{print $1}')
[ -n "$presets" ] || { echo "no presets listed"; exit 1; }
for p in $presets; do
    check "$p" --preset "$p"
done
check sky-noon-clouds --preset sky-noon --set clouds.enabled=true
check sky-noon-clouds-quiet --preset sky-noon --set clouds.enabled=true --quiet
exit $fail
