#!/usr/bin/env python3
"""eta_bench.py -- how well `atmo render` predicts its own time: the "about N s" line printed
after the first pass over the image, and the progress bar's ETA, against the time the render
actually took.

Each case runs `atmo render` on a pseudo-terminal (so it draws its bar, redrawn every 0.2 s)
and reads every redraw: the percentage done, the elapsed seconds and the ETA. The render's
actual time is the elapsed time of its last redraw (100 %, on the same clock). For each redraw
the actual remaining time is that minus the redraw's elapsed time, and the ETA's error is
ETA / actual remaining - 1. The summary states, per case, the prediction's ratio to the actual
time and the largest |error| of the ETA over the redraws between 10 % and 90 % done (beyond 90 %
a remaining time under a second is within the 0.2 s redraw period and the timer's noise).

Usage: tools/eta_bench.py ATMO OUT_DIR [--quick]
Writes OUT_DIR/eta_redraws.csv (every redraw) and OUT_DIR/eta_summary.csv (one row per case),
and prints the summary.
"""
import csv
import os
import pty
import re
import select
import subprocess
import sys
import time

# (name, arguments): two thesis views with terrain and a path-traced one, at 320 x 180
CASES = [
    ("thesis-1", ["--preset", "thesis-1", "--samples", "4"]),
    ("thesis-9", ["--preset", "thesis-9", "--samples", "4"]),
    ("thesis-7 path", ["--preset", "thesis-7", "--samples", "16"]),
]
QUICK_SIZE = ["--width", "160", "--height", "90"]
SIZE = ["--width", "320", "--height", "180"]

BAR = re.compile(r"render \[[#.]+\]\s+([\d.]+)%\s+([\d.]+)s elapsed\s+ETA ([\d.]+|--)s?")
ABOUT = re.compile(r"about (\d+) s to render")


def run_case(atmo, args, out_png):
    """Run one render on a pty; returns (redraws [(percent, elapsed, eta or None)], about)."""
    master, slave = pty.openpty()
    proc = subprocess.Popen([atmo, "render", *args, "--output", out_png, "--force"],
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    text = b""
    while True:
        ready, _, _ = select.select([master], [], [], 1.0)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:
                break
            if not chunk:
                break
            text += chunk
        elif proc.poll() is not None:
            break
    proc.wait()
    os.close(master)
    if proc.returncode != 0:
        sys.exit("atmo render %s failed (exit %d): %s" % (" ".join(args), proc.returncode,
                                                          text.decode(errors="replace")[-500:]))
    decoded = text.decode(errors="replace")
    redraws = []
    for m in BAR.finditer(decoded):
        eta = None if m.group(3) == "--" else float(m.group(3))
        redraws.append((float(m.group(1)), float(m.group(2)), eta))
    about = ABOUT.search(decoded)
    return redraws, (float(about.group(1)) if about else None)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    atmo, out_dir = sys.argv[1], sys.argv[2]
    size = QUICK_SIZE if "--quick" in sys.argv[3:] else SIZE
    os.makedirs(out_dir, exist_ok=True)
    rows, summary = [], []
    for name, args in CASES:
        redraws, about = run_case(atmo, args + size, os.path.join(out_dir, "eta_render.png"))
        actual = redraws[-1][1]
        worst = 0.0
        for percent, elapsed, eta in redraws:
            left = actual - elapsed
            err = eta / left - 1.0 if eta is not None and left > 0.0 else None
            rows.append([name, percent, elapsed, "" if eta is None else eta, round(left, 2),
                         "" if err is None else round(err, 4)])
            if err is not None and 10.0 <= percent <= 90.0:
                worst = max(worst, abs(err))
        summary.append([name, " ".join(args + size), about if about is not None else "",
                        actual, "" if about is None else round(about / actual, 3),
                        round(worst, 3)])
    os.remove(os.path.join(out_dir, "eta_render.png"))
    with open(os.path.join(out_dir, "eta_redraws.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "percent", "elapsed_s", "eta_s", "actual_remaining_s", "eta_error"])
        w.writerows(rows)
    with open(os.path.join(out_dir, "eta_summary.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "arguments", "predicted_s", "actual_s", "predicted_over_actual",
                    "eta_worst_error_10_to_90_percent"])
        w.writerows(summary)
    for row in summary:
        print("%-14s predicted %6s s, actual %7.1f s (ratio %s), ETA worst error %.0f %% "
              "(10-90 %% done)" % (row[0], row[2], row[3], row[4], 100.0 * row[5]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
