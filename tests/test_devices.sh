#!/usr/bin/env bash
# test_devices — `atmo devices` lists the OpenCL platforms and devices, says why a device is
# skipped and marks the one a render uses; a selector that names nothing is refused.
# labels: cli
#
# Oracles: the device a render actually opens (its run report's device), which `atmo devices`
# must mark for the same selector (none, --device N, --device NAME, ATMO_DEVICE); the selection
# rule of include/atmo/cl_runtime.h (first usable GPU, else CPU) recomputed from the JSON
# listing; OpenCL's own answer through PoCL, the platform this suite runs on (its device must be
# listed and usable); DESIGN.md's refusal contract (exit 2, one line, no output) for a selector
# that matches nothing, whose line must list the devices there are.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
if ! "$atmo" devices >list.txt 2>err.txt; then
    grep -q "no OpenCL platform" err.txt && { echo "test_devices: no OpenCL platform; skipped"; exit 77; }
    bad "atmo devices failed: $(cat err.txt)"
fi
"$atmo" devices --json >list.json || bad "atmo devices --json failed"

# the listing: PoCL's device is there, usable and (the only platform here) the one a render uses
python3 - list.json <<'EOF' && ok || bad "JSON listing"
import json, sys
d = json.load(open(sys.argv[1]))
devs = d["devices"]
assert [x["index"] for x in devs] == list(range(len(devs)))
pocl = [x for x in devs if "Portable Computing Language" in x["platform"]]
assert pocl and pocl[0]["usable"] and pocl[0]["skipped"] is None, pocl
for x in devs:
    for key in ("name", "vendor", "type", "device_version", "opencl_c_version", "driver_version"):
        assert isinstance(x[key], str), key
    assert x["compute_units"] > 0 and x["global_memory_bytes"] > 0
    assert x["usable"] == (x["skipped"] is None)
usable = [x for x in devs if x["usable"]]
rule = [x for x in usable if x["type"] == "GPU"] or [x for x in usable if x["type"] == "CPU"] or usable
assert d["selected"] == rule[0]["index"], (d["selected"], rule[0])
assert [x["index"] for x in devs if x["selected"]] == [d["selected"]]
assert sum(p["devices"] for p in d["platforms"]) == len(devs)
print("selected device %d: %s / %s" % (d["selected"], devs[d["selected"]]["platform"], devs[d["selected"]]["name"]))
EOF
name=$(python3 -c "import json; d=json.load(open('list.json')); print(d['devices'][d['selected']]['name'])")
grep -qF -- "* $(python3 -c "import json; print(json.load(open('list.json'))['selected'])"): $name" list.txt &&
    grep -q "^a render uses device" list.txt && ok || bad "text listing lacks the * mark: $(cat list.txt)"

# marked = opened: the render's report names the device the listing marks, for each selector
pocl_index=$(python3 -c "import json; print([x['index'] for x in json.load(open('list.json'))['devices'] if 'Portable' in x['platform']][0])")
check_selector() {
    local what=$1
    shift
    local marked opened
    marked=$("$@" devices --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(d['devices'][d['selected']]['name'])")
    "$@" render --width 8 --height 8 --samples 1 --quiet --force --output out.pfm --report run.json 2>render.err ||
        { bad "$what: render failed: $(cat render.err)"; return; }
    opened=$(python3 -c "import json; print(json.load(open('run.json'))['device']['name'])")
    [ "$marked" = "$opened" ] && ok || bad "$what: devices marks '$marked', render opened '$opened'"
}
check_selector "default" "$atmo"
check_selector "ATMO_DEVICE=pocl" env ATMO_DEVICE=pocl "$atmo"
"$atmo" devices --device pocl | grep -q "^a render uses device $pocl_index (\* above; --device pocl)" &&
    ok || bad "--device pocl is not marked"
"$atmo" devices --device "$pocl_index" --json | python3 -c "import json,sys; d=json.load(sys.stdin); assert d['selected'] == $pocl_index and d['selected_by'] == '--device'" &&
    ok || bad "--device $pocl_index is not selected"

# a selector that names nothing: exit 2, one line that lists the devices
refused "devices --device unknown" "no OpenCL device matches 'no-such-xyz'; give an index or part of a name: 0 '" devices --device no-such-xyz
grep -qF "$name" stderr.txt && ok || bad "the refusal does not list '$name'"
refused "devices --device 99" "OpenCL device 99 does not exist; give an index" devices --device 99
refused "render --device unknown" "no OpenCL device matches 'no-such-xyz'" render --width 8 --height 8 --device no-such-xyz --output out/a.png
refused "devices --device without a value" "missing value for '--device'" devices --device

cli_end test_devices
