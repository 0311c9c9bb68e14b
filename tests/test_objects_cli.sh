#!/usr/bin/env bash
# test_objects_cli — the scene's object list and path mode on the command line: bad objects are
# one line on stderr with exit 2 before any work; --save-scene writes the list and loading it
# back reproduces the scene and the image bit for bit; every thesis preset renders at a tiny
# size in its own mode and in the other one with no non-finite sample.
# labels: cli render slow
#
# Oracle: the CLI contract of DESIGN.md's "Errors" (exit codes, one-line errors naming what,
# where and how to fix), the determinism contract (same scene, same device: same bytes, so the
# saved scene's render equals the original's with cmp), and the session's count of dropped
# non-finite samples in the run report (Python's json reads it), which must be 0.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin

small=(render --preset sky-sunset --width 8 --height 6 --samples 1 --quiet --output out/a.png)
refused "not an array" "objects.*JSON array" "${small[@]}" --set 'objects={"type": "sphere"}'
refused "no type" "objects\[0\].*type" "${small[@]}" --set 'objects=[{"center_m": [0, 1, 5]}]'
refused "unknown type" "objects\[0\].*sphere.*box" "${small[@]}" --set 'objects=[{"type": "cone"}]'
refused "missing radius" "objects\[0\].*radius_m" "${small[@]}" --set 'objects=[{"type": "sphere", "center_m": [0, 1, 5]}]'
refused "member of the other type" "objects\[1\]\.radius_m.*box" "${small[@]}" \
    --set 'objects=[{"type": "sphere", "center_m": [0, 1, 5], "radius_m": 1}, {"type": "box", "min_m": [0, 0, 0], "size_m": [1, 1, 1], "radius_m": 2}]'
refused "albedo out of range" "objects\[0\]\.albedo.*0 \.\. 1" "${small[@]}" \
    --set 'objects=[{"type": "box", "min_m": [0, 0, 0], "size_m": [1, 1, 1], "albedo": [0.5, 1.5, 0]}]'
refused "negative size" "objects\[0\]\.size_m.*range" "${small[@]}" \
    --set 'objects=[{"type": "box", "min_m": [0, 0, 0], "size_m": [1, -1, 1]}]'
refused "wrong JSON type" "objects\[0\]\.center_m.*3 numbers" "${small[@]}" \
    --set 'objects=[{"type": "sphere", "center_m": [0, 1], "radius_m": 1}]'
refused "duplicate member" "objects\[0\]\.radius_m.*twice" "${small[@]}" \
    --set 'objects=[{"type": "sphere", "center_m": [0, 1, 5], "radius_m": 1, "radius_m": 2}]'
refused "bad render mode" "render.mode.*preview, path" "${small[@]}" --set render.mode=fast
printf '{"objects": [{"type": "sphere", "center_m": [0, 1, 5], "radius_m": "one"}]}\n' >bad.json
refused "scene file" "objects\[0\]\.radius_m.*bad.json" render --width 8 --height 6 --quiet --scene bad.json --output out/a.png

# --save-scene writes the list; the saved scene renders the same bytes, in both modes
for mode in preview path; do
    args=(--preset thesis-2 --width 12 --height 8 --samples 2 --quiet --set render.mode=$mode)
    if "$atmo" render "${args[@]}" --force --save-scene scene.json --output a.pfm 2>err.txt &&
        "$atmo" render --scene scene.json --force --output b.pfm 2>>err.txt; then
        if python3 -c 'import json,sys; d=json.load(open("scene.json")); sys.exit(0 if len(d["objects"]) == 2 and d["objects"][1]["type"] == "box" and d["objects"][1]["albedo"] == [0, 0, 1] else 1)'; then ok; else bad "$mode: saved scene lacks the objects"; fi
        if cmp -s a.pfm b.pfm; then ok; else bad "$mode: the saved scene renders another image"; fi
    else
        bad "$mode: render failed: $(cat err.txt)"
    fi
done

# every thesis preset, tiny, in both modes: no dropped non-finite sample
for n in 1 2 3 4 5 6 7 8 9; do
    for mode in preview path; do
        if "$atmo" render --preset thesis-$n --width 8 --height 6 --samples 2 --quiet \
            --set render.mode=$mode --force --output t.pfm --report r.json 2>err.txt; then
            dropped=$(python3 -c 'import json; print(json.load(open("r.json"))["render"]["nonfinite_samples_dropped"])')
            if [ "$dropped" = 0 ]; then ok; else bad "thesis-$n $mode: $dropped non-finite samples"; fi
        else
            bad "thesis-$n $mode: $(cat err.txt)"
        fi
    done
done

cli_end test_objects_cli
