#!/usr/bin/env python3
"""Measures the figures of the estimator's line landmarks (issue 13, item 1) on the scenarios
with walls, with the shipped programs:

    scripts/measure-lines.py OUTDIR [--seeds 1-20] [--scenarios office,corridor] [--bin DIR]

For each scenario and seed:

    slammtt-world --scenario S --seed N --log S-N.world.lcm
    slammtt-replay S-N.world.lcm -o S-N.lcm --config estimator/config/S.yaml \\
        --stage segmenter --stage estimator
    slammtt-eval S-N.lcm --json S-N.json

and prints one Markdown row per run (robot ATE, final heading error, odometry ATE, line
landmarks matched / all, line angle error median / max, line distance error median / max,
point landmarks on walls, per-scan p50 / p99 of the estimator from slammtt-timing --json), then
the worst seed and the median of each column. Every file stays in OUTDIR. Needs a build
(build/bin, or --bin) and python3 with no extra modules; per-scan times depend on the load.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(command):
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        last = (result.stderr.strip().splitlines() or ["exit " + str(result.returncode)])[-1]
        sys.exit(f"measure-lines: {' '.join(command)}: {last}")
    return result.stdout


def seeds_of(text):
    if "-" in text:
        first, last = text.split("-")
        return list(range(int(first), int(last) + 1))
    return [int(s) for s in text.split(",")]


def estimator_times_ms(timing_json):
    for stage in timing_json.get("stages", []):
        if stage.get("stage") == "estimator":
            total = stage["total_ns"]
            return total["median"] / 1e6, total["p99"] / 1e6
    return None, None


def measure(bin_dir, outdir, scenario, seed):
    stem = os.path.join(outdir, f"{scenario}-{seed}")
    world = stem + ".world.lcm"
    if not os.path.exists(world):
        run([os.path.join(bin_dir, "slammtt-world"), "--quiet", "--scenario", scenario, "--seed",
             str(seed), "--log", world])
    out = stem + ".lcm"
    config = os.path.join(ROOT, "estimator", "config", scenario + ".yaml")
    run([os.path.join(bin_dir, "slammtt-replay"), "--quiet", world, "-o", out, "--config",
         config, "--stage", "segmenter", "--stage", "estimator"])
    run([os.path.join(bin_dir, "slammtt-eval"), "--quiet", out, "--json", stem + ".json"])
    timing = json.loads(run([os.path.join(bin_dir, "slammtt-timing"), "--json",
                             out + ".timing.lcm"]))
    with open(stem + ".json") as f:
        report = json.load(f)
    robot = report["detail"]["robot"]
    lines = (report["detail"].get("map") or {}).get("lines") or {}
    p50, p99 = estimator_times_ms(timing)
    return {
        "ate_m": report["ate_rmse_m"],
        "heading_deg": abs(math.degrees(robot["final_heading_error_rad"])),
        "odometry_ate_m": report["odometry_ate_rmse_m"],
        "lines": lines.get("lines", 0),
        "matched": lines.get("matched", 0),
        "angle_median_deg": lines.get("angle_error_deg", {}).get("median"),
        "angle_max_deg": lines.get("angle_error_deg", {}).get("max"),
        "distance_median_m": lines.get("distance_error_m", {}).get("median"),
        "distance_max_m": lines.get("distance_error_m", {}).get("max"),
        "points_on_walls": lines.get("point_landmarks_on_walls"),
        "p50_ms": p50,
        "p99_ms": p99,
    }


COLUMNS = ["ate_m", "heading_deg", "odometry_ate_m", "matched", "lines", "angle_median_deg",
           "angle_max_deg", "distance_median_m", "distance_max_m", "points_on_walls", "p50_ms",
           "p99_ms"]
# Columns where a larger value is worse (the worst seed); the others: smaller is worse.
WORSE_IF_LOWER = {"matched"}


def fmt(value):
    if value is None:
        return "-"
    if isinstance(value, int):
        return str(value)
    return f"{value:.3f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir")
    parser.add_argument("--seeds", default="1-20")
    parser.add_argument("--scenarios", default="office,corridor")
    parser.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    args = parser.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    print("| scenario | seed | " + " | ".join(COLUMNS) + " |")
    print("|---|---|" + "---|" * len(COLUMNS))
    for scenario in args.scenarios.split(","):
        rows = []
        for seed in seeds_of(args.seeds):
            row = measure(args.bin, args.outdir, scenario, seed)
            rows.append(row)
            print(f"| {scenario} | {seed} | " + " | ".join(fmt(row[c]) for c in COLUMNS) + " |",
                  flush=True)
        for name, pick in (("worst", None), ("median", statistics.median)):
            cells = []
            for c in COLUMNS:
                values = [r[c] for r in rows if r[c] is not None]
                if not values:
                    cells.append("-")
                elif pick is None:
                    cells.append(fmt(min(values) if c in WORSE_IF_LOWER else max(values)))
                else:
                    cells.append(fmt(pick(values)))
            print(f"| {scenario} | {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
