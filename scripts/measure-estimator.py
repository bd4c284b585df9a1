#!/usr/bin/env python3
"""Measures every figure of the estimator's issue (issue 6) with the shipped programs.

    scripts/measure-estimator.py OUTDIR [--seeds 1-5] [--scenarios s1-crossing,...]
        [--modes ml_ransac,...] [--summary] [--set KEY=VALUE ...] [--no-odometry]

For each scenario and seed it runs exactly what the target tests run
(tests/estimator/pipeline_runner.cc):

    slammtt-world --scenario S --seed N --log world.lcm
    { cat estimator/config/S.yaml; echo "  mode: MODE"; } > MODE.yaml
    slammtt-replay world.lcm -o out.lcm --config MODE.yaml [--stage segmenter] --stage estimator
    slammtt-eval out.lcm --json report.json
    slammtt-timing --json out.lcm.timing.lcm

in mode ml_ransac everywhere, static_nn (baseline a) on s1-crossing and ransac_all_pairs
(baseline b) on s1-crossing and s2-lobby. ml_ransac runs are also scored without the two
evaluation rules of docs/evaluation.md (--min-beams 1 --min-moving-speed-mps 0), column
"MOTA norules". Column "MOTA" scores the reported tracks (track_t.reported), "MOTA coast" every
confirmed track, coasting ones included; "people MOTA" / "people IDSW" the visible people,
standing ones counted (docs/evaluation.md), at --people-match-m (0.75 m, issue 13's office
target); "people in map" (office, corridor): final-map landmarks within that distance of a
person's path. --summary adds, per scenario and mode, the worst seed and the median of the
columns in SUMMARISED. The pseudo-scenario s1-static-only is s1-crossing with its five movers
taken out (the same landmarks, robot path and sensor): the robot error EKF-SLAM reaches when
nothing moves. --no-odometry runs each ml_ransac run once more with `slammtt-replay
--drop-channel ODOMETRY` (mode "ml_ransac no-odometry": a robot without wheel odometry, issue
13 item 5), whose column "ATE ratio" is its ATE over the ATE of the same seed with odometry;
column "non-person movers/min" is slammtt-eval's non_person_movers_per_minute (at
--people-match-m). --set KEY=VALUE appends an estimator option to every run's configuration,
--set segmenter.KEY=VALUE a segmenter option (in a `segmenter:` section after it).

Prints one Markdown table row per run; every file stays in OUTDIR. Needs a build (build/bin) and
python3 with no extra modules. Per-scan times depend on the machine's load: quote them from a
quiet machine.
"""
import argparse
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "bin")
SCENARIOS = ["s1-crossing", "s1-static-only", "s2-lobby", "s3-no-static", "rplidar-a2",
             "crowd-zara02", "office", "corridor"]
# The columns summarised over the seeds of each scenario and mode (--summary): worst and median.
# Higher is better for MOTA, lower for the others.
SUMMARISED = {"MOTA": max, "MOTA coast": max, "people MOTA": max, "people IDSW": min,
              "IDSW": min, "ATE m": min, "movers in map": min, "people in map": min,
              "non-person movers/min": min, "ATE ratio": min}


def modes_of(scenario):
    if scenario in ("s1-crossing", "s1-static-only"):
        return ["ml_ransac", "static_nn"] + (["ransac_all_pairs"] if scenario == "s1-crossing"
                                             else [])
    if scenario == "s2-lobby":
        return ["ml_ransac", "ransac_all_pairs"]
    return ["ml_ransac"]


def run(command):
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        last_line = (result.stderr.strip().splitlines() or ["exit " + str(result.returncode)])[-1]
        sys.exit(f"measure-estimator: {' '.join(command)}: {last_line}")
    return result.stdout


def config_text(shipped_config, mode, settings):
    """The shipped estimator configuration (its `estimator:` section last) with `mode` and the
    --set settings: `KEY=VALUE` into `estimator:`, `segmenter.KEY=VALUE` into a `segmenter:`
    section after it."""
    estimator_lines = [f"  mode: {mode}"]
    segmenter_lines = []
    for setting in settings:
        key, _, value = setting.partition("=")
        section, _, name = key.rpartition(".")
        if section not in ("", "estimator", "segmenter"):
            sys.exit(f"measure-estimator: --set {setting}: only estimator and segmenter options")
        (segmenter_lines if section == "segmenter" else estimator_lines).append(
            f"  {name}: {value}")
    text = shipped_config + "\n".join(estimator_lines) + "\n"
    if segmenter_lines:
        text += "segmenter:\n" + "\n".join(segmenter_lines) + "\n"
    return text


def static_only_scenario(outdir):
    """s1-crossing without its movers: the text up to 'movers:', then 'movers: []', then the
    statics (the same as sed '/^movers:/,/^statics:/{/^statics:/!d}')."""
    with open(os.path.join(ROOT, "config", "scenarios", "s1-crossing.yaml")) as f:
        text = f.read()
    cut = re.search(r"^movers:.*?(?=^statics:)", text, re.M | re.S)
    if cut is None:
        sys.exit("measure-estimator: s1-crossing.yaml has no 'movers:' before 'statics:'")
    path = os.path.join(outdir, "s1-static-only.yaml")
    with open(path, "w") as f:
        f.write(text[:cut.start()] + "movers: []\n" + text[cut.end():])
    return path


def timing(timing_log):
    stages = json.loads(run([os.path.join(BIN, "slammtt-timing"), "--json", timing_log]))
    estimator = [s for s in stages["stages"] if s["stage"] == "estimator"][0]
    hypotheses = [c["value"] for c in estimator["counters"] if c["name"] == "hypotheses"][0]
    return (estimator["total_ns"]["median"] / 1000.0, estimator["total_ns"]["p99"] / 1000.0,
            round(hypotheses["mean"] * hypotheses["count"]))


def fmt(value, digits=3):
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}f}"
    return str(value)


def print_summary(results, seeds):
    """Worst seed and median of each summarised column, per scenario and mode."""
    print(f"\nseeds {seeds.start}-{seeds.stop - 1}: worst (seed) / median")
    print("| scenario | mode | " + " | ".join(SUMMARISED) + " |")
    print("|" + "---|" * (2 + len(SUMMARISED)))
    for (scenario, mode), rows in results.items():
        cells = []
        for column, worse in SUMMARISED.items():
            values = [(float(r[column]), r["seed"]) for r in rows if r[column] not in ("-",)]
            if not values:
                cells.append("-")
                continue
            # worst: the lowest MOTA, the highest error or count
            worst = min(values) if worse is max else max(values)
            ordered = sorted(v for v, _ in values)
            mid = len(ordered) // 2
            median = ordered[mid] if len(ordered) % 2 else 0.5 * (ordered[mid - 1] + ordered[mid])
            cells.append(f"{worst[0]:.3f} ({worst[1]}) / {median:.3f}")
        print(f"| {scenario} | {mode} | " + " | ".join(cells) + " |")
    for (scenario, mode), rows in results.items():
        if scenario != "s1-crossing" or mode != "ml_ransac":
            continue
        met = [r["seed"] for r in rows
               if r["IDSW"] == "0" and r["movers in map"] == "0" and float(r["MOTA"]) >= 0.95
               and float(r["ATE m"]) <= 0.3]
        print(f"\ns1-crossing targets (0 identity switches, MOTA >= 0.95, ATE <= 0.3 m, 0 movers "
              f"in the map) met on {len(met)} of {len(rows)} seeds: {' '.join(met)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir")
    parser.add_argument("--seeds", default="1-5", help="first-last (default 1-5)")
    parser.add_argument("--scenarios", default=",".join(SCENARIOS))
    parser.add_argument("--modes", default="", help="only these modes (default: all of each)")
    parser.add_argument("--people-match-m", default="0.75")
    parser.add_argument("--summary", action="store_true")
    parser.add_argument("--no-odometry", action="store_true",
                        help="also run every ml_ransac run without its ODOMETRY channel")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="an estimator option (segmenter.KEY: a segmenter option) appended "
                             "to every run's configuration (repeatable; for measuring an "
                             "option's effect)")
    args = parser.parse_args()
    first, _, last = args.seeds.partition("-")
    seeds = range(int(first), int(last or first) + 1)
    scenarios = args.scenarios.split(",")
    for scenario in scenarios:
        if scenario not in SCENARIOS:
            sys.exit(f"measure-estimator: unknown scenario '{scenario}' "
                     f"(known: {', '.join(SCENARIOS)})")
    os.makedirs(args.outdir, exist_ok=True)
    only_modes = [m for m in args.modes.split(",") if m]
    columns = ["scenario", "seed", "mode", "MOTA", "MOTA norules", "MOTA coast", "people MOTA",
               "people IDSW", "people in map", "non-person movers/min", "ATE ratio", "MOTP m",
               "IDSW", "frag",
               "OSPA m", "GOSPA m", "ATE m", "odom ATE m", "movers in map", "landmark RMSE m",
               "static recall", "class. acc.", "mean delay s", "max delay s", "hypotheses",
               "p50 us", "p99 us"]
    results = {}
    print("| " + " | ".join(columns) + " |")
    print("|" + "---|" * len(columns))
    for scenario in scenarios:
        source = scenario
        config_name = scenario
        if scenario == "s1-static-only":
            source = static_only_scenario(args.outdir)
            config_name = "s1-crossing"
        with open(os.path.join(ROOT, "estimator", "config", config_name + ".yaml")) as f:
            shipped_config = f.read()
        stages = ["--stage", "estimator"]
        if scenario not in ("s1-crossing", "s1-static-only"):
            stages = ["--stage", "segmenter"] + stages
        for seed in seeds:
            stem = os.path.join(args.outdir, f"{scenario}-{seed}")
            world = stem + ".world.lcm"
            if not os.path.exists(world):
                run([os.path.join(BIN, "slammtt-world"), "--quiet", "--scenario", source,
                     "--seed", str(seed), "--log", world])
            runs = [(m, m, []) for m in modes_of(scenario) if not only_modes or m in only_modes]
            if args.no_odometry and any(m == "ml_ransac" for m, _, _ in runs):
                runs.append(("ml_ransac", "ml_ransac no-odometry",
                             ["--drop-channel", "ODOMETRY"]))
            ate_with_odometry = None
            for mode, label, dropped in runs:
                config = f"{stem}-{mode}.yaml"
                with open(config, "w") as f:
                    f.write(config_text(shipped_config, mode, args.set))
                out = f"{stem}-{label.replace(' ', '-')}.out.lcm"
                run([os.path.join(BIN, "slammtt-replay"), "--quiet", world, "-o", out,
                     "--config", config] + stages + dropped)
                stem_label = f"{stem}-{label.replace(' ', '-')}"
                report_path = f"{stem_label}.json"
                run([os.path.join(BIN, "slammtt-eval"), "--quiet", out, "--json", report_path])
                with open(report_path) as f:
                    report = json.load(f)
                norules = "-"
                if mode == "ml_ransac":
                    norules_path = f"{stem_label}.norules.json"
                    run([os.path.join(BIN, "slammtt-eval"), "--quiet", out, "--json",
                         norules_path, "--min-beams", "1", "--min-moving-speed-mps", "0"])
                    with open(norules_path) as f:
                        norules = fmt(json.load(f)["mota"])
                people_path = f"{stem_label}.people.json"
                run([os.path.join(BIN, "slammtt-eval"), "--quiet", out, "--json", people_path,
                     "--match-threshold-m", args.people_match_m])
                with open(people_path) as f:
                    people_report = json.load(f)
                map_detail = people_report["detail"]["map"] or {}
                people_in_map = (len(map_detail.get("mover_landmark_ids", []))
                                 if scenario in ("office", "corridor") else None)
                p50, p99, hypotheses = timing(out + ".timing.lcm")
                classification = report["detail"]["classification"]
                ate = report["ate_rmse_m"]
                ratio = None
                if label == "ml_ransac":
                    ate_with_odometry = ate
                elif dropped and ate is not None and ate_with_odometry:
                    ratio = ate / ate_with_odometry
                row = [scenario, str(seed), label, fmt(report["mota"]), norules,
                       fmt(report["mota_with_coasting"]), fmt(people_report["people_mota"]),
                       fmt(people_report["people_id_switches"]), fmt(people_in_map),
                       fmt(people_report.get("non_person_movers_per_minute")), fmt(ratio),
                       fmt(report["motp_m"]), fmt(report["id_switches"]),
                       fmt(report["fragmentations"]), fmt(report["ospa_mean_m"]),
                       fmt(report["gospa_mean_m"]), fmt(report["ate_rmse_m"]),
                       fmt(report["odometry_ate_rmse_m"]), fmt(report["movers_in_static_map"]),
                       fmt(report["landmark_rmse_m"]), fmt(report["static_recall"]),
                       fmt(report["classification_accuracy"]),
                       fmt(classification.get("mean_delay_s"), 2),
                       fmt(classification.get("max_delay_s"), 2), str(hypotheses),
                       fmt(p50, 0), fmt(p99, 0)]
                print("| " + " | ".join(row) + " |", flush=True)
                results.setdefault((scenario, label), []).append(dict(zip(columns, row)))
    if args.summary:
        print_summary(results, seeds)


if __name__ == "__main__":
    main()
