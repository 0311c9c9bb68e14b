#!/usr/bin/env python3
"""make_segment_table.py — the stored aerial-perspective table that tests/test_aerial.c compares
the methods' segments against (tests/data/reference_segments.csv).

It runs `atmo radiance --method reference --distance-m D --json` (the Monte Carlo path tracer,
all orders, its camera ray stopped by a black surface at D; kernels/atmosphere/method_reference.h) for
cameras at the ground and at 10 km, sun zenith 0, 45, 80 and 90 deg, distances 1, 10 and
100 km, and views at zenith 0, 60 and 85 deg toward the sun (azimuth 0), 85 deg away from it
(180) and, from 10 km, 100 deg across it (90; a ray toward the ground). Every (camera, sun,
distance) is first run with --samples N; views whose in-scattered radiance has a relative
standard error above the target in any channel are run again with twice the samples (another
seed) and the runs are merged, weighted by their sample counts, until the target is met or
--max-rounds runs are spent. The CSV holds per view the in-scattered radiance and the
transmittance with their standard errors, and the commands, seeds and device in '#' comments.

usage: tools/make_segment_table.py ATMO [--samples N] [--target REL] [--output FILE]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

ALTITUDE = [0, 10000]
SUN_ZENITH = [0, 45, 80, 90]
DISTANCE = [1000, 10000, 100000]
KEYS = [("radiance", "radiance_standard_error"), ("transmittance", "transmittance_standard_error")]


def views(altitude):
    out = [(0.0, 0.0), (60.0, 0.0), (85.0, 0.0), (85.0, 180.0)]
    return out + [(100.0, 90.0)] if altitude > 0 else out


def run(atmo, altitude, sun, distance, vs, samples, seed):
    cmd = [atmo, "radiance", "--method", "reference", "--altitude-m", str(altitude),
           "--sun-zenith-deg", str(sun), "--distance-m", str(distance), "--samples", str(samples),
           "--seed", str(seed), "--json"]
    for z, a in vs:
        cmd += ["--view", "%g,%g" % (z, a)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out), cmd


def merge(acc, view, samples):
    """Runs weighted by samples: mean = sum n m / sum n, se^2 = sum n^2 se^2 / (sum n)^2."""
    if acc is None:
        acc = {"n": 0, "sum": {k: [0.0] * 3 for k, _ in KEYS},
               "var": {k: [0.0] * 3 for k, _ in KEYS}}
    acc["n"] += samples
    for key, se_key in KEYS:
        for c in range(3):
            acc["sum"][key][c] += samples * view[key][c]
            acc["var"][key][c] += (samples * view[se_key][c]) ** 2
    return acc


def result(acc, key):
    n = acc["n"]
    return [s / n for s in acc["sum"][key]], [math.sqrt(v) / n for v in acc["var"][key]]


def worst_relative(acc):
    mean, se = result(acc, "radiance")
    return max(s / m for m, s in zip(mean, se))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("atmo")
    ap.add_argument("--samples", type=int, default=1 << 18)
    ap.add_argument("--target", type=float, default=0.003)
    ap.add_argument("--max-rounds", type=int, default=4)
    ap.add_argument("--output", default=os.path.join(os.path.dirname(__file__), "..", "tests",
                                                      "data", "reference_segments.csv"))
    args = ap.parse_args()
    t0 = time.time()
    rows, device, commands = [], "", []
    for altitude in ALTITUDE:
        for sun in SUN_ZENITH:
            for distance in DISTANCE:
                acc = {v: None for v in views(altitude)}
                pending = list(acc)
                for rnd in range(args.max_rounds):
                    seed = 1000 * sun + 10 * DISTANCE.index(distance) + rnd + (altitude > 0) * 500
                    samples = args.samples * (2 ** rnd)
                    data, cmd = run(args.atmo, altitude, sun, distance, pending, samples, seed)
                    device = data["device"]
                    commands.append(" ".join(os.path.basename(c) if i == 0 else c
                                             for i, c in enumerate(cmd)))
                    for v, d in zip(pending, data["views"]):
                        acc[v] = merge(acc[v], d, data["samples"])
                    pending = [v for v in pending if worst_relative(acc[v]) > args.target]
                    print("altitude %g sun %g distance %g: round %d, %d samples, %d views above "
                          "target, %.0f s" % (altitude, sun, distance, rnd, samples, len(pending),
                                              time.time() - t0), file=sys.stderr)
                    if not pending:
                        break
                for v in views(altitude):
                    L, L_se = result(acc[v], "radiance")
                    T, T_se = result(acc[v], "transmittance")
                    rows.append((altitude, sun, v[0], v[1], distance, acc[v]["n"], L, L_se, T,
                                 T_se))
    worst = max(s / m for r in rows for m, s in zip(r[6], r[7]))
    lines = [
        "# Aerial perspective of the default atmosphere: radiance in-scattered toward the camera",
        "# over the first distance_m metres of each view (W m^-2 sr^-1 nm^-1 at 680, 550, 440 nm,",
        "# all orders, black surface at distance_m) and the transmittance to there, from the Monte",
        "# Carlo reference method (kernels/atmosphere/method_reference.h); se_* = standard error of the mean.",
        "# generated by: tools/make_segment_table.py (%.0f s)" % (time.time() - t0),
        "# device: %s" % device,
        "# target relative standard error of L %.3g; worst reached %.3g" % (args.target, worst),
        "# commands (runs of one view merged by sample count):",
    ] + ["#   " + c for c in commands] + [
        "altitude_m,sun_zenith_deg,view_zenith_deg,view_azimuth_deg,distance_m,samples,"
        "L_680,L_550,L_440,se_680,se_550,se_440,T_680,T_550,T_440,T_se_680,T_se_550,T_se_440"
    ]
    for alt, sun, z, a, dist, n, L, L_se, T, T_se in rows:
        lines.append("%g,%g,%g,%g,%g,%d,%.7e,%.7e,%.7e,%.3e,%.3e,%.3e,%.7e,%.7e,%.7e,%.3e,%.3e,%.3e"
                     % (alt, sun, z, a, dist, n, *L, *L_se, *T, *T_se))
    tmp = args.output + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, args.output)
    print("wrote %s: %d rows, worst relative standard error %.3g" % (args.output, len(rows), worst),
          file=sys.stderr)


if __name__ == "__main__":
    main()
