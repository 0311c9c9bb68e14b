#!/usr/bin/env bash
# submit.sh — submit a split render to Slurm: an array job of N parts and the merge after it.
#
#   tools/slurm/submit.sh N OUTDIR OUTPUT[,OUTPUT...] [atmo render options...]
#
# e.g. tools/slurm/submit.sh 16 /shared/sunset sunset.exr,sunset.png --preset thesis-5
#          --samples 4096
# submits `sbatch --array=0-(N-1) render-part.sbatch OUTDIR options...` and then
# `sbatch --dependency=afterok:<array job> merge.sbatch OUTDIR N --output OUTPUT ...`, and prints
# the two job ids ("ARRAY MERGE"). With --frames A..B among the options, task k renders whole
# frames A+k, A+k+N, ... to OUTPUT names numbered per frame (OUTDIR/NAME.0001.exr ...), and
# there is no merge job ("ARRAY -"). OUTDIR must be on a file system all nodes share. Extra sbatch
# options (partition, time, CPUs per task) go in SBATCH_* environment variables or
# $ATMO_SBATCH_OPTIONS (words), which both submissions get.
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: $0 N OUTDIR OUTPUT[,OUTPUT...] [atmo render options...]" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
count=$1 outdir=$2 outputs=$3
shift 3
case $count in '' | *[!0-9]* | 0) echo "$0: N must be a whole number >= 1, got '$count'" >&2; exit 2 ;; esac
mkdir -p "$outdir"
read -r -a extra <<<"${ATMO_SBATCH_OPTIONS:-}"
merge_args=() frames=0
IFS=, read -r -a names <<<"$outputs"
for o in "${names[@]}"; do merge_args+=(--output "$o"); done
for a in "$@"; do [ "$a" = --frames ] && frames=1; done
if [ $frames = 1 ]; then
    frame_outputs=()
    for o in "${names[@]}"; do frame_outputs+=(--output "$outdir/$(basename "$o")"); done
    array=$(sbatch --parsable "${extra[@]}" --array=0-$((count - 1)) \
        --output="$outdir/frames.%a.log" "$here/render-part.sbatch" "$outdir" "$@" \
        "${frame_outputs[@]}")
    echo "${array%%;*} -"
    exit 0
fi
array=$(sbatch --parsable "${extra[@]}" --array=0-$((count - 1)) \
    --output="$outdir/part.%a.log" "$here/render-part.sbatch" "$outdir" "$@")
array=${array%%;*}
merge=$(sbatch --parsable "${extra[@]}" --dependency=afterok:"$array" --kill-on-invalid-dep=yes \
    --output="$outdir/merge.log" "$here/merge.sbatch" "$outdir" "$count" "${merge_args[@]}")
echo "$array ${merge%%;*}"
