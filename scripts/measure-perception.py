#!/usr/bin/env python3
"""Measures the perception figures of issue 11 on the real recordings in ../shared/data/real.

    scripts/measure-perception.py OUTDIR [--shared DIR] [--match-m 0.2] [--leg-threshold P]

For each recording it runs the shipped programs:

    slammtt-import BAG -o OUTDIR/NAME.lcm --no-odometry
    slammtt-replay OUTDIR/NAME.lcm -o OUTDIR/NAME-out.lcm --stage segmenter

and reads the FEATURES of the output (and the LEG_LABELS the importer wrote from a training
bag's /leg_cluster_positions) with the project's Python package (build/venv, made by
scripts/python-env.sh). Figures, one Markdown table row per recording:

- leg recall and precision (positive_*_extracted): a label is found when a point feature with
  leg_likeness >= --leg-threshold (default: the segmenter's default leg_threshold, the trained
  model's threshold read from perception/leg_model.cc) lies within --match-m of it,
  one-to-one, nearest pairs first; precision = matched leg candidates / leg candidates. The
  labels are the legs inside the training box only (docs/perception.md);
- person features per scan and per minute (negative_2: nobody is there, every one is false);
- the distribution of people found per scan (leg_tracker_demo: 1-3 people walk).

positive_4_extracted and negative_2 are held out: no default was chosen on them.
"""
import argparse
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "bin")
VENV_PYTHON = os.path.join(ROOT, "build", "venv", "bin", "python")

RECORDINGS = [
    ("positive_1_extracted", "leg_tracker_training/positive_1_extracted.bag"),
    ("positive_2_extracted", "leg_tracker_training/positive_2_extracted.bag"),
    ("positive_3_extracted", "leg_tracker_training/positive_3_extracted.bag"),
    ("positive_4_extracted", "leg_tracker_training/positive_4_extracted.bag"),
    ("negative_2", "leg_tracker_training/negative_2.bag"),
    ("leg_tracker_demo", "leg_tracker_demo/demo_stationary_simple_environment.bag"),
]


def run(command):
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        last_line = (result.stderr.strip().splitlines() or ["exit " + str(result.returncode)])[-1]
        sys.exit(f"measure-perception: {' '.join(command)}: {last_line}")
    return result.stdout


def match_legs(candidates, labels, match_m):
    """Number of one-to-one pairs within match_m, nearest first (ties: lower indices)."""
    pairs = []
    for i, (cx, cy) in enumerate(candidates):
        for j, (lx, ly) in enumerate(labels):
            d = math.hypot(cx - lx, cy - ly)
            if d <= match_m:
                pairs.append((d, i, j))
    pairs.sort()
    used_c, used_l, matched = set(), set(), 0
    for _, i, j in pairs:
        if i in used_c or j in used_l:
            continue
        used_c.add(i)
        used_l.add(j)
        matched += 1
    return matched


def measure(out_log, match_m, leg_threshold):
    from slammtt.lcmlog import LogReader
    labels_by_utime = {}
    features = []
    for channel, _, message in LogReader(out_log):
        if channel == "LEG_LABELS":
            labels_by_utime[message.utime] = list(zip(message.x_m, message.y_m))
        elif channel == "FEATURES":
            features.append(message)
    scans = len(features)
    people = [m.num_people for m in features]
    legs = matched = candidates = 0
    label_utimes = sorted(labels_by_utime)
    for m in features:
        leg_candidates = [(f.range_m * math.cos(f.bearing_rad), f.range_m * math.sin(f.bearing_rad))
                          for f in m.features if f.leg_likeness >= leg_threshold]
        if not label_utimes:
            continue
        # The label message of this scan: the nearest utime, within 50 ms.
        nearest = min(label_utimes, key=lambda u: abs(u - m.utime))
        if abs(nearest - m.utime) > 50000:
            continue
        labels = labels_by_utime[nearest]
        legs += len(labels)
        candidates += len(leg_candidates)
        matched += match_legs(leg_candidates, labels, match_m)
    minutes = (features[-1].utime - features[0].utime) / 6e7 if scans > 1 else 0.0
    distribution = {}
    for n in people:
        distribution[n] = distribution.get(n, 0) + 1
    return {
        "scans": scans, "legs": legs,
        "leg_recall": matched / legs if legs else float("nan"),
        "leg_precision": matched / candidates if candidates else float("nan"),
        "people_per_scan": sum(people) / scans if scans else float("nan"),
        "people_per_minute": sum(people) / minutes if minutes > 0 else float("nan"),
        "distribution": " ".join(f"{k}:{distribution[k]}" for k in sorted(distribution)),
    }


def model_threshold():
    """The trained model's threshold: the last number of TrainedLegModel()'s initialiser in the
    generated perception/leg_model.cc (SegmenterOptions::leg_threshold's default)."""
    with open(os.path.join(ROOT, "perception", "leg_model.cc")) as f:
        source = f.read()
    found = re.search(r"static const LegModel model\{([^}]*)\}", source)
    if not found:
        sys.exit("measure-perception: no TrainedLegModel() in perception/leg_model.cc")
    return float(found.group(1).split(",")[-1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("outdir")
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(ROOT), "shared"))
    parser.add_argument("--match-m", type=float, default=0.2)
    parser.add_argument("--leg-threshold", type=float, default=None)
    args = parser.parse_args()
    if args.leg_threshold is None:
        args.leg_threshold = model_threshold()
    try:
        import slammtt.lcmlog  # noqa: F401
    except ImportError:
        if os.path.exists(VENV_PYTHON) and sys.executable != VENV_PYTHON:
            os.execv(VENV_PYTHON, [VENV_PYTHON] + sys.argv)
        sys.exit("measure-perception: no build/venv: run scripts/python-env.sh first")
    os.makedirs(args.outdir, exist_ok=True)
    print("| recording | scans | leg recall | leg precision | people per scan | people per minute "
          "| people per scan: scans |")
    print("|---|---|---|---|---|---|---|")
    for name, relative in RECORDINGS:
        bag = os.path.join(args.shared, "data", "real", relative)
        if not os.path.exists(bag):
            print(f"| {name} | skipped: {bag} is absent | | | | | |")
            continue
        log = os.path.join(args.outdir, name + ".lcm")
        out = os.path.join(args.outdir, name + "-out.lcm")
        run([os.path.join(BIN, "slammtt-import"), bag, "-o", log, "--no-odometry", "-q"])
        run([os.path.join(BIN, "slammtt-replay"), log, "-o", out, "--stage", "segmenter"])
        f = measure(out, args.match_m, args.leg_threshold)
        print(f"| {name} | {f['scans']} | {f['leg_recall']:.4f} | {f['leg_precision']:.4f} | "
              f"{f['people_per_scan']:.3f} | {f['people_per_minute']:.1f} | {f['distribution']} |")


if __name__ == "__main__":
    main()
