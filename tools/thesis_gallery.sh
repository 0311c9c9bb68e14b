#!/usr/bin/env bash
# thesis_gallery.sh — renders the nine thesis views (presets thesis-1 ... thesis-9) for the
# README's gallery and prints its Markdown table (each view beside what to see in it).
#
#   tools/thesis_gallery.sh [ATMO] [OUTDIR] [WIDTH] [HEIGHT]
#
# ATMO defaults to build/atmo, OUTDIR to docs/gallery, the size to 480 x 270. Each view is
# rendered as its preset says (the preview, or the path tracer for view 7, with 64 samples
# there and 4 elsewhere); the summary column is `atmo presets`' line for the view.
set -eu
atmo=${1:-build/atmo}
out=${2:-docs/gallery}
width=${3:-480}
height=${4:-270}
mkdir -p "$out"
echo "| view | image | what to see | command |"
echo "|---|---|---|---|"
for n in 1 2 3 4 5 6 7 8 9; do
    samples=4
    [ "$n" = 7 ] && samples=64
    file="$out/thesis-$n.png"
    cmd="atmo render --preset thesis-$n --width $width --height $height --samples $samples --output $file"
    "$atmo" render --force --preset "thesis-$n" --width "$width" --height "$height" --samples "$samples" \
        --output "$file" --quiet
    summary=$("$atmo" presets | awk -v p="thesis-$n" '$1 == p { $1 = ""; sub(/^ +/, ""); print }')
    echo "| \`thesis-$n\` | ![thesis-$n]($file) | $summary | \`$cmd\` |"
done
