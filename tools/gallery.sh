#!/usr/bin/env bash
# gallery.sh — renders the gallery (every thesis view, `space` and the `sky-*` presets) and writes
# its page, docs/gallery/views.md: each image beside what it shows, the command that made it, its
# samples, its time and the device.
#
#   tools/gallery.sh [--atmo PATH] [--out DIR] [--size WxH] [--only NAME,NAME,...] [--table-only]
#                    [--note TEXT]
#
# Defaults: build/atmo, docs/gallery, 1280x720, every entry. Each entry is rendered with the
# samples it lists below and denoised (output.denoise=high, Open Image Denoise must be
# installed: ./setup.sh does it); its run report DIR/NAME.json keeps the settings, the device and
# the stage timings, and the page is written from the reports, so --only re-renders some entries
# and --table-only rewrites the page without rendering. The time on the page is the report's
# whole run (kernel build, precompute, render, denoise, write) with the caches as they were;
# --note adds a sentence under the page's header (e.g. what else loaded the machine).
set -euo pipefail
atmo=build/atmo
out=docs/gallery
size=1280x720
only=
table_only=0
note=
while [ $# -gt 0 ]; do
    case "$1" in
    --atmo) atmo=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --table-only) table_only=1; shift ;;
    --note) note=$2; shift 2 ;;
    *) echo "gallery.sh: unknown option '$1' (options: --atmo --out --size --only --table-only --note)" >&2
       exit 2 ;;
    esac
done
case "$size" in
[0-9]*x[0-9]*) width=${size%x*} height=${size#*x} ;;
*) echo "gallery.sh: --size '$size' is not WxH (e.g. 1280x720)" >&2; exit 2 ;;
esac
[ -x "$atmo" ] || { echo "gallery.sh: no atmo at '$atmo' (build it: ./setup.sh build)" >&2; exit 2; }

# name | preset | samples | extra flags | what to see
entries=(
"thesis-1|thesis-1|2||sunset over snowy mountains, a sunlit cumulus left of the peak; the foreground lies in the peak's shadow"
"thesis-2|thesis-2|1||looking down at a small sphere and a box standing on the terrain, the low sun's long shadows"
"thesis-3|thesis-3|1||the low sun in frame over the hills beside the open box's site"
"thesis-4|thesis-4|4||the planet from 2000 km: terminator, cloud field, blue limb"
"thesis-5|thesis-5|2||cloud tops from 42 km away from the sun: the fog bow and the glory"
"thesis-6|thesis-6|1||cumulus toward a 28° sun, lens flare, bright cloud edges"
"thesis-7|thesis-7|32||an open box, path traced: the coloured walls' light on the floor and the spheres"
"thesis-8|thesis-8|1||clouds over the mountains at a moderate sun"
"thesis-9|thesis-9|2||a high-altitude sunset over the cloud field"
"space|space|1||the planet from 2000 km: continents, oceans, terminator, blue limb"
"sky-noon|sky-noon|1||a clear sky at noon, looking at the horizon"
"sky-afternoon|sky-afternoon|1||the afternoon sky, the sun 30° high to the right"
"sky-sunset|sky-sunset|1||a sunset looking toward the sun"
"sky-sunset-panorama|sky-sunset|1|--camera panorama|the sunset as a 360° panorama (the Blender environment map's view)"
)

selected() {
    [ -z "$only" ] && return 0
    case ",$only," in *",$1,"*) return 0 ;; esac
    return 1
}

mkdir -p "$out"
if [ "$table_only" = 0 ]; then
    for e in "${entries[@]}"; do
        IFS='|' read -r name preset samples extra what <<< "$e"
        selected "$name" || continue
        w=$width h=$height
        [ "$extra" = "--camera panorama" ] && w=$width h=$((width / 2))
        echo "gallery: $name ($w x $h, $samples samples)" >&2
        # shellcheck disable=SC2086
        "$atmo" render --force --quiet --preset "$preset" $extra --width "$w" --height "$h" \
            --samples "$samples" --denoise high --output "$out/$name.png" --report "$out/$name.json"
    done
fi

# the page, from the reports
{
    echo "# Gallery: the thesis views, space and the skies"
    echo
    echo "Rendered by \`tools/gallery.sh\` (this page is its output), each in the preset's default"
    echo "mode and denoised with Open Image Denoise (\`--denoise high\`). The time is the whole run"
    echo "as the report records it (kernel build and precompute included where the cache was cold,"
    echo "marked so). What each thesis view should show: [the thesis' views](../thesis.md)."
    [ -n "$note" ] && { echo; echo "$note"; }
    echo
    echo "| view | image | what it shows | samples | time | command |"
    echo "|---|---|---|---|---|---|"
    for e in "${entries[@]}"; do
        IFS='|' read -r name preset samples extra what <<< "$e"
        report="$out/$name.json"
        [ -f "$report" ] || continue
        read -r w h spp secs cold device < <(python3 - "$report" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
s = r["seconds"]
cold = "cold" if not (r["render"].get("kernel_cache_hit") and r["render"].get("lut_cache_hit", True)) else "warm"
dev = r["device"]["name"].replace(" ", "_")
# the guide pass: seconds.guides, or in reports written before that key only under denoise
guides = 0.0 if "guides" in s else r["render"].get("denoise", {}).get("guide_pass_seconds", 0.0)
print(r["render"]["width"], r["render"]["height"], r["render"]["samples_max"],
      "%.1f" % (sum(s.values()) + guides), cold, dev)
EOF
        )
        cmd="atmo render --preset $preset${extra:+ $extra} --width $w --height $h --samples $spp --denoise high --output $name.png"
        echo "| \`$name\` | ![$name]($name.png) | $what | $spp | $secs s ($cold caches; ${w}×${h}; ${device//_/ }) | \`$cmd\` |"
    done
} > "$out/views.md"
echo "gallery: wrote $out/views.md" >&2
