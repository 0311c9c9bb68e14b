#!/usr/bin/env bash
# measure_split.sh — how evenly a split render's parts share the work, and what 4 parts gain
# over one process on this machine (docs/notes/split_render.md has the numbers).
#
#   tools/measure_split.sh ATMO WORKDIR SIZE SAMPLES [render options...]
#
# 1. Band costs: the image (SIZE x SIZE) rendered as B parts of one band each (--part b/B, B =
#    SIZE / 8, bands of 8 rows): the CPU seconds (user + sys, all of PoCL's threads) of each band less those of
#    a process that renders almost nothing (16 x 16, 1 sample: device, cached build, writing),
#    and the render's wall seconds. CPU time is the measure of work: on a shared machine the
#    wall time also counts the other processes. From the band costs, the cost of the 4 parts of
#    the interleaved split atmo uses (bands b, b + 4, ...) and of a contiguous split (B / 4
#    bands at a time from the top) for comparison.
# 2. A split of the sample range: 4 renders of the whole image with SAMPLES / 4 samples and
#    seeds 1..4 (the cost of 4 sample ranges: each pixel's work is the same whatever its
#    sample indices).
# 3. Speed-up: the wall time of one process rendering everything against 4 processes
#    rendering the 4 interleaved parts at once (xargs -P 4) followed by the merge.
# The cache (kernels, LUTs) is warmed first, so every run pays the device and the cached
# build only, as a cluster node with a warm cache does.
set -euo pipefail
atmo=$1 work=$2 size=$3 samples=$4
shift 4
mkdir -p "$work"
cd "$work"
export ATMO_CACHE_DIR=$work/cache
scene=(--width "$size" --height "$size" --samples "$samples" --quiet "$@")
bands=$((size / 8))
cpu() { /usr/bin/time -f "%U %S" -o t.txt "$@" && awk '{print $1 + $2}' t.txt; }
render_s() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['seconds']['render'])" "$1"; }
"$atmo" render --force "${scene[@]}" --output warm.pfm
base=$(cpu "$atmo" render --force "${scene[@]}" --width 16 --height 16 --samples 1 --output base.pfm)
echo "per-process CPU seconds without work: $base"
echo "band cpu_s render_s"
for ((b = 1; b <= bands; b++)); do
    c=$(cpu "$atmo" render --force "${scene[@]}" --part $b/$bands --output band$b.exr --report band$b.json)
    echo "$b $(echo "$c - $base" | bc -l) $(render_s band$b.json)"
done | tee bands.txt
python3 - "$bands" <<'PY'
import sys
bands = int(sys.argv[1])
rows = [l.split() for l in open("bands.txt") if l[0].isdigit()]
cpu = [float(r[1]) for r in rows]
def report(name, groups):
    t = [sum(cpu[b] for b in g) for g in groups]
    print(f"{name}: part CPU seconds {', '.join(f'{x:.2f}' for x in t)}; max/mean {max(t) / (sum(t) / len(t)):.3f}")
report("interleaved (atmo)", [[b for b in range(bands) if b % 4 == k] for k in range(4)])
report("contiguous", [list(range(k * bands // 4, (k + 1) * bands // 4)) for k in range(4)])
PY
echo "sample-range split (4 x $((samples / 4)) samples, whole image):"
for s in 1 2 3 4; do
    c=$(cpu "$atmo" render --force "${scene[@]}" --samples $((samples / 4)) --seed $s --output range$s.pfm)
    echo "range $s cpu_s $(echo "$c - $base" | bc -l)"
done
TIMEFORMAT="%R wall seconds, %U + %S CPU seconds"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "one process:"
time "$atmo" render --force "${scene[@]}" --output single.pfm
echo "4 parts at once (xargs -P 4), then the merge:"
time { printf '%s\n' 1 2 3 4 | xargs -P 4 -I{} "$atmo" render --force "${scene[@]}" --part {}/4 --output p{}.exr
       "$atmo" merge --quiet p1.exr p2.exr p3.exr p4.exr --output merged.pfm; }
echo "the merge alone:"
time "$atmo" merge --quiet p1.exr p2.exr p3.exr p4.exr --output merged2.pfm
cmp single.pfm merged.pfm && echo "merged = single, byte for byte"
