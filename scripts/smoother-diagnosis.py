#!/usr/bin/env python3
"""What the smoother was given, and where its trajectory goes wrong, against the world's truth
(docs/smoother.md, "Why the smoothed ATE is worse on some seeds").

    build/venv/bin/python scripts/smoother-diagnosis.py OUTDIR [--scenario s1-crossing]
        [--seeds 1-10] [--json FILE]

OUTDIR is what scripts/measure-smoother.sh left: SCENARIO-seedN.lcm (slammtt-world) and
SCENARIO-seedN-replay.lcm (SMOOTHER_INPUT, POSE, SMOOTHED_POSE). Per seed, without running
anything:

- The measurements on SMOOTHER_INPUT: each one's chi^2 at the truth (the measured range and
  bearing against the true object nearest to where the true robot pose puts it, whitened by the
  measurement's own R; 2 degrees of freedom, so a mean near 2 and about 1 in 3000 above 16 when
  the noise is as stated), how many are above 16, and the landmark ids whose sightings fall on
  more than one true object (a merge or a wrong association: the ids and the share) or on a
  true mover (and whether the estimator removed the id).
- The odometry increments: their error against the true motion between the same scans,
  normalised by the stated sigma (rms, per component: forward, sideways, heading), and the
  heading errors' correlation between consecutive scans (0 for white noise, as the smoother
  assumes).
- The filter's (POSE) and the smoother's (SMOOTHED_POSE) trajectory, anchored at the first
  pose as slammtt-eval anchors it: the ATE, the rotation about the first pose that fits the
  trajectory best to the truth (one angle, least squares), and the ATE once that rotation is
  taken out. A smoothed ATE that is worse only until the rotation is taken out is the map's
  rotation about the start, which only the first scans' sightings and increments fix.

Prints one line per seed and a summary; --json keeps every figure.

    build/venv/bin/python scripts/smoother-diagnosis.py --rotation-model

prints instead what a one-dimensional model of that rotation gives for its sigma
(rotation_sigma_model): the robot's heading a random walk of the increments (the stated sigma
of s1-crossing's, 8.3 and 3.6 mrad on alternate scans, the true ones 0.57 of it as measured
above), each scan's bearings to 19 landmarks one measurement of the heading relative to the map
(sigma 2 deg / sqrt(19)), the first pose's heading known; weighted least squares with the
increments' variance scaled by 0.1-1 (the truth stays), with and without the first scan's
bearings (the estimator's smoother_first_sightings).
"""
import argparse
import bisect
import collections
import json
import math
import os
import sys

from slammtt.lcmlog import LogReader

KIND_FURNITURE, KIND_POST, KIND_DISC, KIND_PERSON, KIND_LEG = 2, 3, 4, 5, 6
CLASS_STATIC = 0
OUTLIER_CHI2 = 16.0  # chi^2(2) exceeds it with probability exp(-8), 3.4e-4
MAX_LANDMARK_MATCH_M = 1.5  # a landmark farther from every true post is left out of its RMSE


def wrap(angle):
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        first, _, last = part.partition("-")
        seeds.extend(range(int(first), int(last or first) + 1))
    return seeds


def read_truth(world_log):
    """{utime: (robot pose, [(object id, x, y, class, kind)])} from GROUND_TRUTH."""
    truth = {}
    for m in LogReader(world_log):
        if m.channel != "GROUND_TRUTH":
            continue
        g = m.message
        objects = [(o.id, o.x_m, o.y_m, o.object_class, o.kind) for o in g.objects
                   if o.kind in (KIND_FURNITURE, KIND_POST, KIND_DISC, KIND_PERSON, KIND_LEG)]
        truth[g.utime] = ((g.robot_x_m, g.robot_y_m, g.robot_heading_rad), objects)
    return truth


def read_replay(replay_log):
    """SMOOTHER_INPUT in order; {channel: {utime: pose}} of POSE and SMOOTHED_POSE; the last
    MAP and SMOOTHED_MAP as [(x, y)]."""
    inputs, poses = [], {"POSE": {}, "SMOOTHED_POSE": {}}
    maps = {"MAP": [], "SMOOTHED_MAP": []}
    for m in LogReader(replay_log):
        if m.channel == "SMOOTHER_INPUT":
            inputs.append(m.message)
        elif m.channel in poses:
            p = m.message
            poses[m.channel][p.utime] = (p.x_m, p.y_m, p.heading_rad)
        elif m.channel in maps:
            maps[m.channel] = [(l.x_m, l.y_m) for l in m.message.landmarks]
    return inputs, poses, maps


def nearest_truth(truth, utimes, utime):
    k = bisect.bisect_left(utimes, utime)
    near = [utimes[j] for j in (k - 1, k) if 0 <= j < len(utimes)]
    return truth[min(near, key=lambda u: abs(u - utime))]


def chi_square(residual, covariance):
    """r^T C^-1 r for a 2-vector and a row-major 2x2 covariance."""
    a, b, c, d = covariance
    determinant = a * d - b * c
    r0, r1 = residual
    return (d * r0 * r0 - (b + c) * r0 * r1 + a * r1 * r1) / determinant


def observations_against_truth(inputs, truth):
    utimes = sorted(truth)
    records = []  # (scan index, landmark id, true object, chi2)
    for index, scan in enumerate(inputs):
        (x, y, heading), objects = nearest_truth(truth, utimes, scan.utime)
        if not objects:
            continue
        c, s = math.cos(heading), math.sin(heading)
        laser_x = x + scan.sensor_forward_m * c - scan.sensor_left_m * s
        laser_y = y + scan.sensor_forward_m * s + scan.sensor_left_m * c
        laser_heading = heading + scan.sensor_yaw_rad
        for o in scan.observations:
            angle = laser_heading + o.bearing_rad
            px, py = laser_x + o.range_m * math.cos(angle), laser_y + o.range_m * math.sin(angle)
            best = min(objects, key=lambda t: (t[1] - px) ** 2 + (t[2] - py) ** 2)
            true_range = math.hypot(best[1] - laser_x, best[2] - laser_y)
            true_bearing = math.atan2(best[2] - laser_y, best[1] - laser_x) - laser_heading
            residual = (o.range_m - true_range, wrap(o.bearing_rad - true_bearing))
            records.append((index, o.landmark_id, best, chi_square(residual, o.covariance)))
    return records


def observation_figures(inputs, records):
    removed = {i for scan in inputs for i in scan.removed_landmark_ids}
    per_landmark = collections.defaultdict(collections.Counter)
    for _, landmark, best, _ in records:
        per_landmark[landmark][best[0]] += 1
    kind = {best[0]: (best[3], best[4]) for _, _, best, _ in records}
    merged, on_movers = [], []
    for landmark, counts in sorted(per_landmark.items()):
        total = sum(counts.values())
        main_object, main_count = counts.most_common(1)[0]
        if len(counts) > 1:
            merged.append({"landmark": landmark, "sightings": total,
                           "on_other_objects": total - main_count})
        if kind[main_object][0] != CLASS_STATIC:
            on_movers.append({"landmark": landmark, "sightings": total,
                              "removed": landmark in removed})
    chis = [r[3] for r in records]
    return {
        "observations": len(records),
        "chi2_mean": sum(chis) / max(len(chis), 1),
        "chi2_above_16": sum(1 for v in chis if v > OUTLIER_CHI2),
        "landmarks": len(per_landmark),
        "landmarks_on_several_objects": merged,
        "sightings_on_other_objects": sum(m["on_other_objects"] for m in merged),
        "landmarks_on_movers": on_movers,
        "mover_sightings_kept": sum(m["sightings"] for m in on_movers if not m["removed"]),
    }


def increment_figures(inputs, truth):
    utimes = sorted(truth)
    normalised = [[], [], []]
    heading_errors = []
    for previous, scan in zip(inputs, inputs[1:]):
        if not scan.continues:
            continue
        (px, py, ph), _ = nearest_truth(truth, utimes, previous.utime)
        (x, y, h), _ = nearest_truth(truth, utimes, scan.utime)
        c, s = math.cos(ph), math.sin(ph)
        true_increment = (c * (x - px) + s * (y - py), -s * (x - px) + c * (y - py), wrap(h - ph))
        errors = (scan.dx_m - true_increment[0], scan.dy_m - true_increment[1],
                  wrap(scan.dtheta_rad - true_increment[2]))
        for k in range(3):
            variance = scan.increment_covariance[4 * k]
            if variance > 0.0:
                normalised[k].append(errors[k] / math.sqrt(variance))
        heading_errors.append(errors[2])
    rms = [math.sqrt(sum(v * v for v in n) / len(n)) if n else None for n in normalised]
    energy = sum(e * e for e in heading_errors)
    lag1 = (sum(a * b for a, b in zip(heading_errors, heading_errors[1:])) / energy
            if energy > 0.0 else None)
    return {"normalised_rms_forward": rms[0], "normalised_rms_sideways": rms[1],
            "normalised_rms_heading": rms[2], "heading_error_lag1_correlation": lag1}


def trajectory_figures(poses, landmarks, truth):
    """ATE anchored at the first pose; the best rotation about it; the ATE without it; the final
    map's error (each landmark against the nearest true post within MAX_LANDMARK_MATCH_M; not
    slammtt-eval's matching, so compare it only with itself) with and without that rotation."""
    utimes = sorted(u for u in poses if u in truth)
    if not utimes:
        return None
    t0, e0 = truth[utimes[0]][0], poses[utimes[0]]
    turn = t0[2] - e0[2]
    c, s = math.cos(turn), math.sin(turn)
    estimate, true = [], []
    for u in utimes:
        e, t = poses[u], truth[u][0]
        dx, dy = e[0] - e0[0], e[1] - e0[1]
        estimate.append((c * dx - s * dy, s * dx + c * dy))  # from the start, world axes
        true.append((t[0] - t0[0], t[1] - t0[1]))
    cross = sum(a[0] * b[1] - a[1] * b[0] for a, b in zip(estimate, true))
    dot = sum(a[0] * b[0] + a[1] * b[1] for a, b in zip(estimate, true))
    rotation = math.atan2(cross, dot)  # turns the estimate onto the truth
    cr, sr = math.cos(rotation), math.sin(rotation)

    def rmse(points):
        return math.sqrt(sum((p[0] - b[0]) ** 2 + (p[1] - b[1]) ** 2
                             for p, b in zip(points, true)) / len(true))

    rotated = [(cr * a[0] - sr * a[1], sr * a[0] + cr * a[1]) for a in estimate]
    posts = [(o[1] - t0[0], o[2] - t0[1]) for o in truth[utimes[-1]][1]
             if o[3] == CLASS_STATIC and o[4] == KIND_POST]
    anchored = []
    for x, y in landmarks:
        dx, dy = x - e0[0], y - e0[1]
        anchored.append((c * dx - s * dy, s * dx + c * dy))
    turned = [(cr * a[0] - sr * a[1], sr * a[0] + cr * a[1]) for a in anchored]
    return {"ate_m": rmse(estimate), "rotation_about_start_rad": -rotation,
            "ate_without_rotation_m": rmse(rotated),
            "landmark_rmse_m": landmark_rmse(anchored, posts),
            "landmark_rmse_without_rotation_m": landmark_rmse(turned, posts)}


def landmark_rmse(landmarks, posts):
    errors = []
    for x, y in landmarks:
        if posts:
            error = min(math.hypot(x - p[0], y - p[1]) for p in posts)
            if error <= MAX_LANDMARK_MATCH_M:
                errors.append(error)
    return math.sqrt(sum(e * e for e in errors) / len(errors)) if errors else None


def diagnose(out_dir, scenario, seed):
    world = os.path.join(out_dir, f"{scenario}-seed{seed}.lcm")
    replay = os.path.join(out_dir, f"{scenario}-seed{seed}-replay.lcm")
    truth = read_truth(world)
    inputs, poses, maps = read_replay(replay)
    records = observations_against_truth(inputs, truth)
    return {"seed": seed, "scans": len(inputs),
            "measurements": observation_figures(inputs, records),
            "increments": increment_figures(inputs, truth),
            "filter": trajectory_figures(poses["POSE"], maps["MAP"], truth),
            "smoothed": trajectory_figures(poses["SMOOTHED_POSE"], maps["SMOOTHED_MAP"], truth)}


def rotation_sigma_model(first_scan_bearings, heading_variance_scale, scans=200,
                         true_ratio=0.57, bearing_sigma=math.radians(2.0), landmarks=19):
    """Sigma of the map's rotation about the first pose (rad) in the model of the docstring."""
    import numpy as np
    stated = np.array([0.0083 if k % 2 == 1 else 0.0036 for k in range(1, scans + 1)])
    scan_sigma = bearing_sigma / math.sqrt(landmarks)
    rows, true_variance, assumed_variance = [], [], []
    # Unknowns: the headings of scans 1..scans, then the map's rotation.
    for k in range(1, scans + 1):  # increment k: heading k - heading k-1
        row = np.zeros(scans + 1)
        row[k - 1] = 1.0
        if k > 1:
            row[k - 2] = -1.0
        rows.append(row)
        true_variance.append((true_ratio * stated[k - 1]) ** 2)
        assumed_variance.append(heading_variance_scale * stated[k - 1] ** 2)
    for k in range(0 if first_scan_bearings else 1, scans + 1):  # heading k - rotation
        row = np.zeros(scans + 1)
        row[scans] = -1.0
        if k > 0:
            row[k - 1] = 1.0
        rows.append(row)
        true_variance.append(scan_sigma ** 2)
        assumed_variance.append(scan_sigma ** 2)
    a = np.array(rows)
    weights = np.diag(1.0 / np.array(assumed_variance))
    gain = np.linalg.solve(a.T @ weights @ a, a.T @ weights)
    covariance = gain @ np.diag(true_variance) @ gain.T
    return math.sqrt(covariance[scans, scans])


def figure(value):
    return "     null" if value is None else f"{value:9.3f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir", nargs="?")
    parser.add_argument("--scenario", default="s1-crossing")
    parser.add_argument("--seeds", default="1-10")
    parser.add_argument("--json", help="every figure, per seed")
    parser.add_argument("--rotation-model", action="store_true",
                        help="print the one-dimensional model's sigma of the rotation and exit")
    args = parser.parse_args()
    if args.rotation_model:
        for first in (False, True):
            for scale in (1.0, 0.57 ** 2, 0.1):
                sigma = rotation_sigma_model(first, scale)
                print(f"first scan's bearings {str(first):5s} increments' heading variance x "
                      f"{scale:.3f}: rotation sigma {1e3 * sigma:.2f} mrad")
        return 0
    if not args.out_dir:
        parser.error("OUTDIR is needed (or --rotation-model)")
    results = []
    print("seed chi2/obs >16 stray movers_kept | increments fwd side head lag1 |"
          " filter ATE rot(mrad) w/o-rot landmarks w/o-rot |"
          " smoothed ATE rot(mrad) w/o-rot landmarks w/o-rot")
    for seed in parse_seeds(args.seeds):
        r = diagnose(args.out_dir, args.scenario, seed)
        results.append(r)
        m, i = r["measurements"], r["increments"]
        line = (f"{seed:4d} {m['chi2_mean']:8.2f} {m['chi2_above_16']:3d} "
                f"{m['sightings_on_other_objects']:5d} {m['mover_sightings_kept']:11d} | "
                f"{i['normalised_rms_forward']:14.2f} {i['normalised_rms_sideways']:4.2f} "
                f"{i['normalised_rms_heading']:4.2f} {i['heading_error_lag1_correlation']:5.2f}")
        for t in (r["filter"], r["smoothed"]):
            line += (f" | {t['ate_m']:6.3f} {1e3 * t['rotation_about_start_rad']:9.2f} "
                     f"{t['ate_without_rotation_m']:7.3f} {figure(t['landmark_rmse_m'])} "
                     f"{figure(t['landmark_rmse_without_rotation_m'])}")
        print(line, flush=True)
    for key, what in (("ate_m", "ATE"), ("ate_without_rotation_m", "ATE without the rotation"),
                      ("landmark_rmse_m", "landmark RMSE"),
                      ("landmark_rmse_without_rotation_m", "landmark RMSE without the rotation")):
        worse = [r["seed"] for r in results
                 if (r["smoothed"][key] or 0.0) > (r["filter"][key] or 0.0)]
        print(f"smoothed {what} worse than the filter's: {len(worse)} of {len(results)} {worse}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
