#!/usr/bin/env bash
# test_param_sweep — every numeric scene parameter at its minimum and at its maximum renders
# without a single non-finite sample, with every method the parameter reaches.
# labels: render slow
#
# Oracle: the renderer's own guard. Each render counts the samples it drops because they are
# NaN or Inf (the run report's render.nonfinite_samples_dropped); radiance is finite and >= 0
# for any valid scene, so the count must be exactly 0. A value the validator refuses instead
# (exit 2 with one line naming the key: a combination such as an atmosphere thinner than
# nothing) is a handled input, not a pass by default: the script prints how many there were,
# and fails if a value is refused without naming its key or if anything exits otherwise.
#
# The ranges come from `atmo params --json` (so a new parameter is swept without editing this
# file). One tiny render per value: 8 x 4 pixels, 1 sample, the lut method at reduced LUT
# sizes. Parameters and the methods they reach:
#   lut.*                       lut
#   reference.*                 reference
#   cloud.*, observer.*         single and march with the cloud or the observer enabled
#   clouds.*                    single and march with the fBm cloud layer enabled
#   path.*                      single and fast in path mode, with a sphere in view
#   image.*, post.*, spectral   single (image.width/height at the maximum with the other 1,
#                               image.samples at the maximum on 1 x 1)
#   terrain.heightmap_file_extent_m, _scale_m, _offset_m   single (no heightmap file given)
#   everything else             single, march, fast, lut, reference (not the reference at the
#                               extinction maxima, rayleigh_coefficient or mie_extinction_per_m
#                               1 per m: optical depth ~1e5, where the Monte Carlo reference
#                               tracks every collision and one 8 x 4 image takes over 15 min)
# plus the scenes that dropped samples before: the observer at the camera's height 0 and
# 0.001 m, and rayleigh_coefficient 1 (optical depth ~1e5, where f_ms rounds to 1 in float).
set -u
atmo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export ATMO_CACHE_DIR="$work/cache"
passed=0
failed=0
refused=0
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

small_lut=(--set lut.r_size=4 --set lut.mu_size=8 --set lut.mu_s_size=4 --set lut.nu_size=2
           --set lut.steps=8 --set lut.sphere_samples=4 --set lut.orders=2)

# render KEY METHOD ARGS...: one tiny render; exit 0 with 0 dropped samples, or exit 2 with
# one line that names KEY
render() {
    local key=$1 method=$2
    shift 2
    rm -f out.pfm report.json
    "$atmo" render --preset sky-sunset --quiet --width 8 --height 4 --samples 1 "${small_lut[@]}" \
        --set atmosphere.method="$method" "$@" --output out.pfm --report report.json \
        >stdout.txt 2>stderr.txt </dev/null
    local rc=$?
    if [ $rc -eq 2 ]; then
        if [ "$(wc -l <stderr.txt)" -eq 1 ] && grep -qF -- "$key" stderr.txt; then
            refused=$((refused + 1))
        else
            bad "$key $method $*: refused without one line naming the key"
            cat stderr.txt >&2
        fi
        return
    fi
    if [ $rc -ne 0 ]; then
        bad "$key $method $*: exit $rc"
        cat stderr.txt >&2
        return
    fi
    local dropped
    dropped=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["render"]["nonfinite_samples_dropped"])' report.json)
    if [ "$dropped" != 0 ]; then
        bad "$key $method $*: $dropped non-finite samples dropped"
        return
    fi
    passed=$((passed + 1))
}

"$atmo" params --json >params.json || { echo "atmo params --json failed" >&2; exit 1; }
# one line per (key, bound, value as --set takes it)
python3 - params.json >values.txt <<'EOF'
import json, sys
for p in json.load(open(sys.argv[1])):
    if p["type"] not in ("int", "float", "vec3"):
        continue
    for bound in ("min", "max"):
        v = p[bound]
        text = ",".join([repr(v)] * 3) if p["type"] == "vec3" else repr(v)
        print(p["key"], bound, text)
EOF

all_methods=(single march fast lut reference)
while read -r key bound value; do
    case $key in
    lut.*) render "$key" lut --set "$key=$value" ;;
    reference.*) render "$key" reference --set "$key=$value" ;;
    cloud.*)
        for m in single march reference; do
            render "$key" $m --set cloud.enabled=true --set "$key=$value"
        done ;;
    observer.*)
        for m in single march; do
            render "$key" $m --set observer.enabled=true --set "$key=$value"
        done ;;
    clouds.*)
        for m in single march; do
            render "$key" $m --set clouds.enabled=true --set "$key=$value"
        done ;;
    path.*)
        for m in single fast; do
            render "$key" $m --set render.mode=path --set "$key=$value" \
                --set 'objects=[{"type": "sphere", "center_m": [0, 1.7, 4], "radius_m": 1}]'
        done ;;
    image.width)
        render "$key" single --set "$key=$value" --height 1 ;;
    image.height)
        render "$key" single --set "$key=$value" --width 1 ;;
    image.samples)
        render "$key" single --width 1 --height 1 --set "$key=$value" ;;
    image.* | post.* | render.spectral_bands)
        render "$key" single --set "$key=$value" ;;
    terrain.heightmap_file_extent_m | terrain.heightmap_scale_m | terrain.heightmap_offset_m)
        # they shape a heightmap file's grid: with none given, one method shows they are inert
        render "$key" single --set "$key=$value" ;;
    atmosphere.rayleigh_coefficient | atmosphere.mie_extinction_per_m)
        for m in single march fast lut; do
            render "$key" "$m" --set "$key=$value"
        done
        [ "$bound" = min ] && render "$key" reference --set "$key=$value" ;;
    *)
        for m in "${all_methods[@]}"; do
            render "$key" "$m" --set "$key=$value"
        done ;;
    esac
done <values.txt

for h in 0 0.001; do
    for m in single march; do
        render camera.position_m $m --set observer.enabled=true --set camera.position_m=0,$h,0 \
            --camera panorama
    done
done
for m in single march fast lut; do
    render atmosphere.rayleigh_coefficient "$m" --set atmosphere.rayleigh_coefficient=1 \
        --camera panorama
done

echo "test_param_sweep: $passed renders without a dropped sample, $refused values refused" \
    "with the key named, $failed failed"
[ $failed -eq 0 ] && [ $passed -gt 0 ]
