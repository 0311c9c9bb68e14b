#!/usr/bin/env bash
# test_denoise_cli — `atmo render --denoise` and output.denoise: what is denoised, what a missing
# library does, the EXR's denoising layers and the run report.
# labels: cli
#
# Oracle: the contract of include/atmo/outputs.h and DESIGN.md's error rules.
#   - A library that cannot be loaded (ATMO_OIDN_LIBRARY naming no file) with an explicit
#     quality: exit 2, one line that says how to install it (pyoidn), nothing written, before
#     any work (--no-kernel-cache: reaching the kernel build would take over a second).
#   - The same with output.denoise=auto (the default): the PNG is written undenoised, with one
#     warning line, exit 0, and the report says denoise.applied = false.
#   - With the library (setup.sh installs it; else these checks are skipped, saying so):
#     --denoise fast to an EXR with path.passes writes R, G, B and the layers "Noisy Image",
#     "Denoising Albedo", "Denoising Normal", "Denoising Depth" (their values: test_denoise);
#     the report names the quality and the library's version (2.x). The PNG of
#     output.denoise=auto equals the PNG of --denoise high (auto is high for PNG) and differs
#     from --denoise off's, in path mode and in a preview with terrain alike; a PFM beside the
#     preview's PNG stays as rendered (the --denoise off render's, byte for byte). The preview
#     of the air alone stays raw under auto: its PNG equals --denoise off's.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
export ATMO_CACHE_DIR=$work/cache
small=(--preset sky-noon --set render.mode=path --set sun.zenith_deg=60 --set camera.pitch_deg=-5
       --width 32 --height 16 --samples 2 --quiet --force)

ATMO_OIDN_LIBRARY=$work/none refused "explicit quality, no library" "pyoidn" \
    render "${small[@]}" --no-kernel-cache --denoise high --output out/a.png

ATMO_OIDN_LIBRARY=$work/none "$atmo" render "${small[@]}" --output auto.png --report auto.json \
    2>stderr.txt
rc=$?
[ $rc -eq 0 ] && ok || bad "auto without the library: exit $rc"
[ "$(wc -l <stderr.txt)" -eq 1 ] && grep -q "warning: not denoising" stderr.txt && ok ||
    { bad "auto without the library: want one warning line"; cat stderr.txt >&2; }
[ -s auto.png ] && ok || bad "auto without the library: no PNG"
python3 -c 'import json, sys; d = json.load(open(sys.argv[1]))["render"]["denoise"]
assert d["setting"] == "auto" and d["applied"] is False, d' auto.json && ok ||
    bad "auto without the library: report lacks applied false"

if ! "$atmo" render "${small[@]}" --denoise fast --output probe.pfm 2>probe.txt; then
    echo "skipped the checks with the library: $(cat probe.txt)"
    cli_end test_denoise_cli
    exit $?
fi

"$atmo" render "${small[@]}" --set path.passes=true --denoise fast --output d.exr \
    --report d.json || bad "--denoise fast to EXR failed"
channels=$(exrheader d.exr | sed -n 's/^ *\([^,]*\), 32-bit floating-point.*/\1/p' | tr '\n' ' ')
for c in R G B "Noisy Image.R" "Noisy Image.G" "Noisy Image.B" "Denoising Albedo.R" \
         "Denoising Normal.X" "Denoising Normal.Y" "Denoising Normal.Z" "Denoising Depth.Z"; do
    case " $channels" in *" $c "*) ok ;; *) bad "d.exr lacks channel '$c' (has: $channels)" ;; esac
done
python3 - d.json <<'EOF' && ok || bad "report's denoise object"
import json, sys
d = json.load(open(sys.argv[1]))["render"]["denoise"]
assert d["setting"] == "fast" and d["applied"] is True and d["quality"] == "fast", d
assert d["library_version"].startswith("2."), d
EOF
"$atmo" render "${small[@]}" --output auto.png && "$atmo" render "${small[@]}" --denoise high \
    --output high.png && "$atmo" render "${small[@]}" --denoise off --output off.png ||
    bad "PNG renders failed"
cmp -s auto.png high.png && ok || bad "auto PNG differs from --denoise high"
cmp -s auto.png off.png && bad "auto PNG equals --denoise off's" || ok
# a preview with terrain alike; its PFM beside it stays as rendered
preview=("${small[@]}" --set render.mode=preview --set terrain.enabled=true
         --set camera.position_m=0,600,0 --set camera.pitch_deg=-8)
"$atmo" render "${preview[@]}" --output pa.png --output pa.pfm &&
    "$atmo" render "${preview[@]}" --denoise high --output ph.png &&
    "$atmo" render "${preview[@]}" --denoise off --output po.png --output po.pfm ||
    bad "preview PNG renders failed"
cmp -s pa.png ph.png && ok || bad "preview: auto PNG differs from --denoise high"
cmp -s pa.png po.png && bad "preview: auto PNG equals --denoise off's" || ok
cmp -s pa.pfm po.pfm && ok || bad "preview: auto PFM differs from --denoise off's"
# the preview of the air alone: raw under auto
sky=("${small[@]}" --set render.mode=preview)
"$atmo" render "${sky[@]}" --output sa.png && "$atmo" render "${sky[@]}" --denoise off \
    --output so.png || bad "sky preview PNG renders failed"
cmp -s sa.png so.png && ok || bad "sky preview: auto PNG differs from --denoise off's"
cli_end test_denoise_cli
