#!/bin/bash
# test_radiance_direct.sh — `atmo radiance --irradiance` under a cloud: the direct beam is the
# sun's irradiance times the scene's transmittance toward the sun, clouds included.
# labels: cli
#
# Oracle: Beer-Lambert in closed form. The air switched off (no Rayleigh, aerosol or ozone), a
# homogeneous shell of cumulus from 1000 to 2000 m with cloud.lwc_g_m3 = 1 / (sigma_ext/LWC at
# 550 nm x 1000 m), so tau(550 nm) = 1 (sigma_ext/LWC per channel from `atmo mie --json`, the
# solver and cache the plan uses); the camera at 999 m, just below it. Without the cloud the
# direct irradiance is E mu0 (the atmosphere transmits everything); with it
#     direct = E mu0 exp(-sigma l),
# l the sun's chord through the shell from the camera (1000 m with the sun at the zenith, the
# spherical chord, in double here, at sun zenith 60 deg). Tolerance 2e-6 relative: the kernels
# compute exp(-sigma l) in float, with sigma rounded to float (6e-8) and l from geometry.h's
# root formula at planet scale (a few 1e-7 of l), so the exponent (<= 2) errs by ~1e-6 at most;
# the rest is double on the host (measured: 1.7e-7).
set -u
atmo=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

"$atmo" mie --dsd cumulus --wavelength-nm 680 --wavelength-nm 550 --wavelength-nm 440 --json \
    >"$tmp/mie.json" || { echo "atmo mie failed"; exit 1; }
lwc=$(python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['results']; print('%.17g' % (1/(r[1]['sigma_ext_per_lwc']*1000)))" "$tmp/mie.json")
air="--set atmosphere.rayleigh_coefficient=0 --set atmosphere.mie_extinction_per_m=0 --set atmosphere.ozone_column_du=0"
shell="--set cloud.enabled=true --set cloud.dsd=cumulus --set cloud.bottom_m=1000 --set cloud.top_m=2000 --set cloud.phase=hg --set cloud.hg_g=0.85 --set cloud.lwc_g_m3=$lwc"
for zenith in 0 60; do
    for cloud in clear shell; do
        extra=""
        [ "$cloud" = shell ] && extra=$shell
        # shellcheck disable=SC2086
        "$atmo" radiance --altitude-m 999 --sun-zenith-deg $zenith --irradiance --method single \
            --samples 64 $air $extra --json >"$tmp/$cloud-$zenith.json" ||
            { echo "radiance run ($cloud, sun zenith $zenith) failed"; fail=1; }
    done
done
python3 - "$tmp" "$lwc" <<'PY' || fail=1
import json, math, sys
tmp, lwc = sys.argv[1], float(sys.argv[2])
sigma = [r["sigma_ext_per_lwc"] * lwc for r in json.load(open(tmp + "/mie.json"))["results"]]
R, base, top, h = 6360e3, 1000.0, 2000.0, 999.0

def inside(r, mu, rs):  # length of the half-line from radius r, cosine mu, inside radius rs
    b = r * mu
    disc = b * b - (r * r - rs * rs)
    if disc <= 0:
        return 0.0
    q = math.sqrt(disc)
    return max(-b + q, 0.0) - max(-b - q, 0.0)

for zenith in (0, 60):
    mu0 = math.cos(math.radians(zenith))
    chord = inside(R + h, mu0, R + top) - inside(R + h, mu0, R + base)
    clear = json.load(open("%s/clear-%d.json" % (tmp, zenith)))["irradiance"]["direct"]
    shell = json.load(open("%s/shell-%d.json" % (tmp, zenith)))["irradiance"]["direct"]
    for k in range(3):
        want = clear[k] * math.exp(-sigma[k] * chord)
        assert abs(shell[k] / want - 1) < 2e-6, (zenith, k, shell[k], want, clear[k])
    print("sun zenith %d: chord %.3f m, tau(550) %.6f; direct under the shell %s, "
          "closed form %s, worst relative error %.1e"
          % (zenith, chord, sigma[1] * chord, ["%.6e" % x for x in shell],
             ["%.6e" % (c * math.exp(-s * chord)) for c, s in zip(clear, sigma)],
             max(abs(shell[k] / (clear[k] * math.exp(-sigma[k] * chord)) - 1) for k in range(3))))
PY
exit $fail
