#!/bin/bash
# test_clouds_dsd.sh — clouds.dsd takes any droplet size distribution of `atmo mie --dsd`: a
# preset name or a SPEC, checked with a one-line error.
# labels: cli
#
# Oracles: the presets' definitions (host/mie/mie_dsd.c: cumulus is gamma:10,0.1 and stratus
# gamma:6,0.1), so a render of the layer with its optics from the distribution
# (clouds.extinction_per_m=0, method single, 8x8) must be bit for bit the same with the preset's
# name, its SPEC and (for cumulus) the empty default, and stratus must differ from cumulus.
# Bad input (an unknown name, a SPEC with a missing or an extra number, a negative radius): exit
# status 2, exactly one line on stderr naming clouds.dsd, and no output file.
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
common=(--preset sky-sunset --set clouds.enabled=true --set atmosphere.method=single --set clouds.extinction_per_m=0
        --set camera.pitch_deg=20 --set clouds.coverage=0.8 --width 8 --height 8 --quiet)

render() { # NAME DSD
    "$atmo" render "${common[@]}" --set "clouds.dsd=$2" --output "$tmp/$1.pfm" ||
        { echo "render with clouds.dsd=$2 failed"; fail=1; }
}
render cumulus cumulus
render cumulus_spec gamma:10,0.1
render default ""
render stratus stratus
render stratus_spec gamma:6,0.1
for pair in "cumulus cumulus_spec" "cumulus default" "stratus stratus_spec"; do
    set -- $pair
    cmp -s "$tmp/$1.pfm" "$tmp/$2.pfm" || { echo "$1 and $2 differ"; fail=1; }
done
if cmp -s "$tmp/cumulus.pfm" "$tmp/stratus.pfm"; then
    echo "cumulus and stratus give the same image"; fail=1
fi

for bad in bogus gamma:10 gamma:10,0.1,3 mono:-1; do
    "$atmo" render "${common[@]}" --set "clouds.dsd=$bad" --output "$tmp/bad.pfm" \
        2>"$tmp/err" >/dev/null
    rc=$?
    lines=$(wc -l <"$tmp/err")
    if [ "$rc" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -q "clouds.dsd" "$tmp/err" ||
        [ -e "$tmp/bad.pfm" ]; then
        echo "clouds.dsd=$bad: exit $rc, $lines lines:"; cat "$tmp/err"; fail=1
    fi
done
[ "$fail" -eq 0 ] && echo "clouds.dsd: presets and SPECs agree bit for bit, bad input refused"
exit "$fail"
