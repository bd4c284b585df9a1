#!/usr/bin/env python3
"""The large-loop figures of issue 14 (docs/smoother.md, "Large loop"): the filter with its local
window of static landmarks and the smoother on the large-loop scenario family, seed by seed, and
the cost curve from 100 to 5000 landmarks.

For every run: slammtt-world (config/scenarios/large-loop.yaml, its landmark count changed for
the curve) -> slammtt-replay with estimator/config/large-loop.yaml (its `smoother:` section, or
--smoother-yaml) -> slammtt-eval --json, and the replay's timing log read scan by scan:

  per-scan cost      the estimator's and the smoother's STAGE_TIMING total of the same scan
                     (utime), summed: what one core spends on the scan;
  amortised cost     the per-scan cost averaged over the second that ends at the scan (8 scans
                     at 8 Hz): the smoother's occasional refactorisation spread over the scans
                     of one second, as a smoother thread with one second of latency would;

p50 / p99 / max over the run's scans. Times are wall-clock times of the replay on this machine
(check `uptime`: on a shared machine they are upper bounds).

Usage:
  scripts/measure-large-loop.py OUT [--seeds 1-10] [--curve 100,500,1000,2000,5000]
      [--curve-seed 1] [--no-seeds] [--no-curve] [--smoother-yaml FILE] [--keep-logs]
      [--bin-dir DIR] [--estimator-set KEY=VALUE ...]
Prints one line per run and writes OUT/large-loop.json. Needs the venv of
scripts/python-env.sh (the log reader) as every Python tool: run it with build/venv/bin/python
or PYTHONPATH=python and a venv holding lcm.
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))

from slammtt.lcmlog import LogReader  # noqa: E402
from slammtt.msgs import decode  # noqa: E402

SCAN_RATE_HZ = 8
# 1 m apart leaves no room for 5000 landmarks in the 2-12 m bands of the loop (the world
# refuses): above this count the curve's scenarios place them 0.5 m apart.
DENSE_COUNT = 2500


def seeds_of(text):
    first, _, last = text.partition("-")
    return list(range(int(first), int(last or first) + 1))


def percentile(values, share):
    ordered = sorted(values)
    if not ordered:
        return None
    index = min(len(ordered) - 1, max(0, int(round(share * (len(ordered) - 1)))))
    return ordered[index]


def scenario_file(out, count):
    with open(os.path.join(ROOT, "config", "scenarios", "large-loop.yaml")) as f:
        text = f.read()
    text, n = re.subn(r"(?m)^  count: \d+$", f"  count: {count}", text)
    if n != 1:
        raise SystemExit("large-loop.yaml: no `  count:` line under scattered_landmarks")
    if count > DENSE_COUNT:
        text = re.sub(r"(?m)^  min_spacing_m: .*$", "  min_spacing_m: 0.5", text)
    path = os.path.join(out, f"large-loop-{count}.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def config_file(out, smoother_yaml, estimator_keys=()):
    with open(os.path.join(ROOT, "estimator", "config", "large-loop.yaml")) as f:
        text = f.read()
    for key_value in estimator_keys:
        key, _, value = key_value.partition("=")
        text = re.sub(r"(?m)^estimator:\n", f"estimator:\n  {key}: {value}\n", text, count=1)
    if smoother_yaml:
        text = re.sub(r"(?ms)^smoother:.*", "", text)
        with open(smoother_yaml) as f:
            text += f.read()
    elif not re.search(r"(?m)^smoother:", text):
        text += "smoother: {}\n"
    path = os.path.join(out, "large-loop-config.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def run(command):
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        raise SystemExit(" ".join(command) + " failed:\n" + result.stdout)
    return result.stdout


def costs(timing_log):
    """Per scan (utime): estimator and smoother total ns, and the estimator's counters."""
    per_scan = {}
    counters = {}
    for event in LogReader(timing_log).events():
        if event.channel != "STAGE_TIMING":
            continue
        t = decode(event.data)
        scan = per_scan.setdefault(t.utime, {"estimator": 0, "smoother": 0})
        if t.stage in scan:
            scan[t.stage] += t.total_ns
        if t.stage == "estimator":
            counters[t.utime] = dict(zip(t.counter_name, t.counter_value))
    return per_scan, counters


def cost_figures(per_scan):
    utimes = sorted(per_scan)
    filter_ms = [per_scan[u]["estimator"] * 1e-6 for u in utimes]
    smoother_ms = [per_scan[u]["smoother"] * 1e-6 for u in utimes]
    total_ms = [a + b for a, b in zip(filter_ms, smoother_ms)]
    amortised_ms = []
    for k in range(len(total_ms)):
        window = total_ms[max(0, k - SCAN_RATE_HZ + 1):k + 1]
        amortised_ms.append(sum(window) / len(window))

    def summary(values):
        return {"p50_ms": percentile(values, 0.5), "p99_ms": percentile(values, 0.99),
                "max_ms": max(values), "mean_ms": statistics.fmean(values)}

    return {"scans": len(utimes), "filter": summary(filter_ms), "smoother": summary(smoother_ms),
            "per_scan": summary(total_ms), "amortised": summary(amortised_ms)}


def one_run(args, out, config, count, seed):
    stem = os.path.join(out, f"large-loop-{count}-seed{seed}")
    world, replay, report = stem + ".world.lcm", stem + ".lcm", stem + ".json"
    bin_dir = args.bin_dir
    run([os.path.join(bin_dir, "slammtt-world"), "--quiet", "--scenario",
         scenario_file(out, count), "--seed", str(seed), "--log", world])
    run([os.path.join(bin_dir, "slammtt-replay"), "--quiet", world, "-o", replay,
         "--config", config])
    subprocess.run([os.path.join(bin_dir, "slammtt-eval"), "--quiet", replay, "--config", config,
                    "--json", report], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    per_scan, counters = costs(replay + ".timing.lcm")
    with open(report) as f:
        evaluation = json.load(f)
    detail = evaluation.get("detail", {})
    last = counters[max(counters)] if counters else {}
    figures = {
        "landmarks": count, "seed": seed,
        "odometry_ate_m": evaluation.get("odometry_ate_rmse_m"),
        "filter_ate_m": evaluation.get("ate_rmse_m"),
        "smoothed_ate_m": evaluation.get("smoothed_ate_rmse_m"),
        "final_smoothed_ate_m": evaluation.get("final_smoothed_ate_rmse_m"),
        "filter_static_recall": evaluation.get("static_recall"),
        "smoothed_static_recall": (detail.get("smoothed_map") or {}).get("static_recall"),
        "filter_landmarks": (detail.get("map") or {}).get("landmarks"),
        "smoothed_landmarks": (detail.get("smoothed_map") or {}).get("landmarks"),
        "most_objects_in_state": max((c.get("objects", 0) for c in counters.values()),
                                     default=0),
        "archived_at_end": last.get("archived"),
        "cost": cost_figures(per_scan),
    }
    if not args.keep_logs:
        for path in (world, replay, replay + ".timing.lcm"):
            if os.path.exists(path):
                os.remove(path)
    return figures


def line(f):
    def fig(value, digits=3):
        return "null" if value is None else f"{value:.{digits}f}"
    c = f["cost"]
    return (f"{f['landmarks']:5d} {f['seed']:3d}  odo {fig(f['odometry_ate_m'], 2)}  "
            f"ATE filter {fig(f['filter_ate_m'])} smoothed {fig(f['smoothed_ate_m'])} "
            f"final {fig(f.get('final_smoothed_ate_m'))}  "
            f"recall filter {fig(f['filter_static_recall'])} smoothed "
            f"{fig(f['smoothed_static_recall'])}  state<= {f['most_objects_in_state']} "
            f"archive {f['archived_at_end']}  ms filter p50/p99 {fig(c['filter']['p50_ms'], 2)}/"
            f"{fig(c['filter']['p99_ms'], 2)} smoother {fig(c['smoother']['p50_ms'], 2)}/"
            f"{fig(c['smoother']['p99_ms'], 2)} per scan {fig(c['per_scan']['p50_ms'], 2)}/"
            f"{fig(c['per_scan']['p99_ms'], 2)} amortised {fig(c['amortised']['p50_ms'], 2)}/"
            f"{fig(c['amortised']['p99_ms'], 2)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--seeds", default="1-10")
    parser.add_argument("--count", type=int, default=1000, help="landmarks of the seed runs")
    parser.add_argument("--curve", default="100,500,1000,2000,5000")
    parser.add_argument("--curve-seed", type=int, default=1)
    parser.add_argument("--no-seeds", action="store_true")
    parser.add_argument("--no-curve", action="store_true")
    parser.add_argument("--smoother-yaml", default=None,
                        help="a file with a `smoother:` section replacing the configuration's")
    parser.add_argument("--keep-logs", action="store_true")
    parser.add_argument("--estimator-set", action="append", default=[], metavar="KEY=VALUE",
                        help="a key of the `estimator:` section (e.g. smoother_feedback=true)")
    parser.add_argument("--bin-dir", default=os.path.join(ROOT, "build", "bin"),
                        help="where slammtt-world, -replay and -eval are (default: build/bin)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    config = config_file(args.out, args.smoother_yaml, args.estimator_set)
    results = {"config": open(config).read(), "load_average": os.getloadavg(), "seeds": [],
               "curve": []}
    print("count seed  figures")
    if not args.no_seeds:
        for seed in seeds_of(args.seeds):
            figures = one_run(args, args.out, config, args.count, seed)
            results["seeds"].append(figures)
            print(line(figures), flush=True)
    if not args.no_curve:
        for count in [int(n) for n in args.curve.split(",") if n]:
            figures = one_run(args, args.out, config, count, args.curve_seed)
            results["curve"].append(figures)
            print(line(figures), flush=True)
    results["load_average_end"] = os.getloadavg()
    with open(os.path.join(args.out, "large-loop.json"), "w") as f:
        json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
