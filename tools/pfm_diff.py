#!/usr/bin/env python3
"""pfm_diff.py — relative RMS difference of two PFM images (linear radiance), pure Python.

    tools/pfm_diff.py REFERENCE.pfm OTHER.pfm

Prints sqrt(mean((b - a)^2)) / sqrt(mean(a^2)) over every channel of every pixel (a bright sun
in the frame dominates it), the per-pixel relative RMS sqrt(mean(((b - a) / a)^2)) of the
pixels' mean over the channels (pixels with a > 0; every pixel counts alike), and the relative
difference of the images' means.
Exit 2 on unreadable or mismatched files, or a non-finite value."""
import math
import struct
import sys


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        count = width * height * channels
        data = struct.unpack(("<" if scale < 0 else ">") + "%df" % count, f.read(4 * count))
    return width, height, channels, data


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    try:
        a, b = read_pfm(sys.argv[1]), read_pfm(sys.argv[2])
    except (OSError, ValueError, struct.error) as err:
        print("pfm_diff: %s" % err, file=sys.stderr)
        sys.exit(2)
    if a[:3] != b[:3]:
        print("pfm_diff: the images differ in size or channels", file=sys.stderr)
        sys.exit(2)
    x, y, c = a[3], b[3], a[2]
    if not all(math.isfinite(v) for v in x + y):
        print("pfm_diff: a non-finite value", file=sys.stderr)
        sys.exit(2)
    rel = math.sqrt(sum((q - p) ** 2 for p, q in zip(x, y)) / sum(p * p for p in x))
    px = [sum(x[i:i + c]) / c for i in range(0, len(x), c)]
    py = [sum(y[i:i + c]) / c for i in range(0, len(y), c)]
    pairs = [(p, q) for p, q in zip(px, py) if p > 0.0]
    rel_px = math.sqrt(sum(((q - p) / p) ** 2 for p, q in pairs) / len(pairs))
    bias = (sum(y) - sum(x)) / sum(x)
    print("relative RMS %.3f %%, per-pixel relative RMS %.3f %%, mean %+.3f %%" %
          (100 * rel, 100 * rel_px, 100 * bias))


main()
